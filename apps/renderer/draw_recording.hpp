#pragma once
// Helpers shared by the camera passes for recording draws: push constants from a draw and
// its material, vertex layout, viewport and scissor.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>

#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "renderer/draw_data.hpp"
#include "renderer/shader_interface.hpp"

namespace penumbra::renderer {

// A single-layer 2D image of `format` for a camera pass's attachments.
gpu::Image create_camera_target(const gpu::Device& device, VkFormat format, uint32_t width, uint32_t height,
                                VkImageUsageFlags usage, VkImageAspectFlags aspect);

// Whether a pass's vertex shader reads the vertex colour: an attribute a shader does not
// consume is a validation warning, so only the lighting pass (lighting_color_vert) binds it.
enum class VertexColors { Read, Skipped };

// The scene's interleaved Vertex: position, normal, uv at locations 0, 1, 2, and with
// VertexColors::Read the colour at location 3.
gpu::VertexLayout scene_vertex_layout(VertexColors colors);

shader::DrawPushConstants draw_push_constants(const Draw& draw, const MaterialBinding& material);

void set_viewport_and_scissor(const gpu::Device& device, VkCommandBuffer cmd, uint32_t width, uint32_t height);

// Binds the material's descriptor set (unless `bind_material` is false: the set bound is
// already the batch's) and push constants, then issues the batch's instanced draw.
void record_batch(const gpu::Device& device, VkCommandBuffer cmd, VkPipelineLayout layout, const DrawData& data,
                  const DrawBatch& batch, bool bind_material = true);

VkPushConstantRange draw_push_constant_range();

// A colour attachment cleared to `clear` at the start of the pass and stored at its end.
VkRenderingAttachmentInfo cleared_color_attachment(VkImageView view, VkClearColorValue clear);

// A reverse-Z depth attachment cleared to 0 (far) at the start of the pass; `store`
// decides whether a later pass sees what it holds at the end.
VkRenderingAttachmentInfo cleared_depth_attachment(VkImageView view, VkAttachmentStoreOp store);

// A depth attachment tested but not written (an equal test over a pre-pass's depth): loaded,
// in VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, not stored.
VkRenderingAttachmentInfo read_only_depth_attachment(VkImageView view);

// Begins the dynamic rendering of a camera pass (one layer, the whole `width` x `height`
// area) with the given colour and depth attachments, then sets the viewport and scissor to
// the same area.
void begin_camera_rendering(const gpu::Device& device, VkCommandBuffer cmd,
                            std::span<const VkRenderingAttachmentInfo> colors, const VkRenderingAttachmentInfo& depth,
                            uint32_t width, uint32_t height);

// Binds the scene's vertex and index buffers and draws every draw of `data` as the camera
// passes do, nearest first, as DrawData::batches: single-sided materials with
// `single_sided` (back faces culled), then double-sided ones with `double_sided`. The frame
// set (RENDERER_SET_FRAME) must be bound: it holds the batches' model matrices. Passes
// that must cover the same fragments (the lighting and geometry-AOV passes) share this
// order, so depth ties resolve identically.
void record_camera_draws(const gpu::Device& device, VkCommandBuffer cmd, VkPipelineLayout layout, const DrawData& data,
                         VkPipeline single_sided, VkPipeline double_sided);

}  // namespace penumbra::renderer

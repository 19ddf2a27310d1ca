#include "renderer/geometry_aov_pass.hpp"

#include <array>

#include "penumbra/gpu/barriers.hpp"
#include "renderer/draw_recording.hpp"
#include "renderer/shader_interface.hpp"
#include "renderer_shaders.hpp"

namespace penumbra::renderer {
namespace {

constexpr VkFormat kPositionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

gpu::UniquePipeline create_pipeline(const gpu::Device& device, VkPipelineLayout layout, VkCullModeFlags cull_mode) {
    gpu::GraphicsPipelineDesc desc;
    desc.stages.push_back({VK_SHADER_STAGE_VERTEX_BIT, shaders::lighting_vert(), {}});
    desc.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, shaders::geometry_aovs_frag(), {}});
    desc.vertex_layout = scene_vertex_layout(VertexColors::Skipped);
    desc.layout = layout;
    desc.color_formats = {kPositionFormat, kNormalFormat};
    desc.depth_format = kDepthFormat;
    desc.depth_compare = VK_COMPARE_OP_GREATER;  // reverse-Z, as the lighting pass
    desc.cull_mode = cull_mode;
    return gpu::create_graphics_pipeline(device, desc);
}

}  // namespace

GeometryAovPass::GeometryAovPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                                 VkDescriptorSetLayout material_set_layout, uint32_t width, uint32_t height)
    : device_(device), width_(width), height_(height) {
    const VkImageUsageFlags color_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    targets_.world_position =
        create_camera_target(device, kPositionFormat, width, height, color_usage, VK_IMAGE_ASPECT_COLOR_BIT);
    targets_.world_normal =
        create_camera_target(device, kNormalFormat, width, height, color_usage, VK_IMAGE_ASPECT_COLOR_BIT);
    targets_.depth = create_camera_target(device, kDepthFormat, width, height,
                                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    const VkDescriptorSetLayout set_layouts[] = {frame_set_layout, material_set_layout};
    const VkPushConstantRange push_range = draw_push_constant_range();
    pipeline_layout_ = gpu::create_pipeline_layout(device, set_layouts, {&push_range, 1});
    single_sided_ = create_pipeline(device, pipeline_layout_, VK_CULL_MODE_BACK_BIT);
    double_sided_ = create_pipeline(device, pipeline_layout_, VK_CULL_MODE_NONE);
}

void GeometryAovPass::begin_rendering(VkCommandBuffer cmd) const {
    const VkClearColorValue no_geometry{{0.0f, 0.0f, 0.0f, 0.0f}};  // position w = 0: no geometry
    const std::array<VkRenderingAttachmentInfo, 2> colors{
        cleared_color_attachment(targets_.world_position.view, no_geometry),
        cleared_color_attachment(targets_.world_normal.view, no_geometry)};
    begin_camera_rendering(device_, cmd, colors,
                           cleared_depth_attachment(targets_.depth.view, VK_ATTACHMENT_STORE_OP_DONT_CARE), width_,
                           height_);
}

void GeometryAovPass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const DrawData& data) const {
    for (const gpu::Image* target : {&targets_.world_position, &targets_.world_normal}) {
        gpu::transition(device_, cmd, *target, gpu::ImageState::Undefined, gpu::ImageState::ColorAttachment);
    }
    gpu::transition(device_, cmd, targets_.depth, gpu::ImageState::Undefined, gpu::ImageState::DepthAttachment);

    begin_rendering(cmd);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, RENDERER_SET_FRAME, 1,
                                     &frame_set, 0, nullptr);
    // The lighting pass's draw order, so that equal-depth ties resolve to the same surface.
    record_camera_draws(device_, cmd, pipeline_layout_, data, single_sided_, double_sided_);
    device_->vkCmdEndRendering(cmd);

    for (const gpu::Image* target : {&targets_.world_position, &targets_.world_normal}) {
        gpu::transition(device_, cmd, *target, gpu::ImageState::ColorAttachment, gpu::ImageState::TransferSrc);
    }
}

}  // namespace penumbra::renderer

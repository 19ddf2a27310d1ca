#pragma once
// Geometry AOVs: the world position (RGBA32F, w = 1 where geometry, 0 none) and the
// shading normal (RGBA32F) of every pixel, for `penumbra compare` to trace its reference
// shadow rays from the very surface points the lighting pass shaded. It draws with the
// lighting pass's vertex shader, culling, depth test and draw order, so both passes
// rasterize the same fragments; the renderer runs it only when asked
// (RenderSettings::geometry_aovs), so ordinary frames pay nothing for it.
#include <vulkan/vulkan.h>

#include <cstdint>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "renderer/draw_data.hpp"

namespace penumbra::renderer {

struct GeometryAovTargets {
    gpu::Image world_position;  // R32G32B32A32_SFLOAT
    gpu::Image world_normal;    // R32G32B32A32_SFLOAT
    gpu::Image depth;           // D32_SFLOAT, reverse-Z
};

class GeometryAovPass {
public:
    // Set 0 is the renderer's frame set (the vertex shader reads the camera), set 1 the materials.
    GeometryAovPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                    VkDescriptorSetLayout material_set_layout, uint32_t width, uint32_t height);

    const GeometryAovTargets& targets() const { return targets_; }

    // Renders every draw; leaves the colour targets in TRANSFER_SRC for readback.
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const DrawData& data) const;

private:
    const gpu::Device& device_;
    void begin_rendering(VkCommandBuffer cmd) const;

    uint32_t width_;
    uint32_t height_;
    GeometryAovTargets targets_;
    gpu::UniquePipelineLayout pipeline_layout_;
    gpu::UniquePipeline single_sided_;  // back faces culled, as in the lighting pass
    gpu::UniquePipeline double_sided_;
};

}  // namespace penumbra::renderer

#pragma once
// Forward lighting pass: shades the scene with the sun, ambient and the cascaded
// shadow map, writing three colour targets (tone-mapped sRGB colour, the sun's exact
// visibility, the cascade index) and a reverse-Z depth buffer.
#include <vulkan/vulkan.h>

#include <cstdint>

#include "gpu/device.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "passes/draw_data.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

struct LightingTargets {
    gpu::Image color;       // R8G8B8A8_SRGB
    gpu::Image visibility;  // R16_UNORM, 1 where no geometry
    gpu::Image cascade;     // R8_UINT, PENUMBRA_NO_CASCADE where none applies
    gpu::Image depth;       // D32_SFLOAT, reverse-Z
};

class LightingPass {
public:
    // The pipelines are specialized for `filter` (shaders/include/shadow_filter_constants.glsl).
    LightingPass(const gpu::Device& device, VkDescriptorSetLayout material_set_layout, uint32_t width, uint32_t height,
                 const FilterSettings& filter = {});

    // Set 0: binding 0 = frame uniforms, 1 = the shadow map (sampler2DArrayShadow), 2 = the
    // same map's raw depth (sampler2DArray), 3 = the moments map (sampler2DArray; any
    // float array image, e.g. the depth map, when the filter reads no moments); 4 = the
    // local-light uniforms, 5 and 6 = the local lights' shadow map (comparison, raw depth).
    VkDescriptorSetLayout frame_set_layout() const { return frame_set_layout_; }
    const LightingTargets& targets() const { return targets_; }

    // Renders every draw; leaves the colour targets in TRANSFER_SRC for readback.
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const DrawData& data) const;

private:
    const gpu::Device& device_;
    void begin_rendering(VkCommandBuffer cmd) const;

    uint32_t width_;
    uint32_t height_;
    LightingTargets targets_;
    gpu::UniqueDescriptorSetLayout frame_set_layout_;
    gpu::UniquePipelineLayout pipeline_layout_;
    gpu::UniquePipeline single_sided_;  // back faces culled
    gpu::UniquePipeline double_sided_;  // no culling
};

}  // namespace penumbra::passes

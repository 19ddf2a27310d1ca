#pragma once
// Forward lighting pass of the tools' renderer: shades the scene with the sun, spot and
// point lights and ambient, every shadow sampled through Penumbra's descriptor set and
// GLSL library (set 2), writing three colour targets (tone-mapped sRGB colour, one
// light's exact visibility, the cascade index) and a reverse-Z depth buffer.
#include <vulkan/vulkan.h>

#include <cstdint>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/settings.hpp"
#include "penumbra/shadow_system.hpp"
#include "renderer/draw_data.hpp"

namespace penumbra::renderer {

struct LightingTargets {
    gpu::Image color;       // R8G8B8A8_SRGB
    gpu::Image visibility;  // R16_UNORM, 1 where no geometry
    gpu::Image cascade;     // R8_UINT, RENDERER_NO_CASCADE where none applies
    gpu::Image depth;       // D32_SFLOAT, reverse-Z
};

class LightingPass {
public:
    // Set 0 is `frame_set_layout` (the renderer's frame uniforms and lights), set 1 the
    // materials, set 2 the ShadowSystem's descriptor set; the fragment shader is specialized
    // with the ShadowSystem's filter constants.
    LightingPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                 VkDescriptorSetLayout material_set_layout, const ShadowSystem& shadows, uint32_t width,
                 uint32_t height);

    const LightingTargets& targets() const { return targets_; }

    // Renders every draw; leaves the colour targets in TRANSFER_SRC for readback.
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, VkDescriptorSet shadow_set, const DrawData& data) const;

private:
    const gpu::Device& device_;
    void begin_rendering(VkCommandBuffer cmd) const;

    uint32_t width_;
    uint32_t height_;
    LightingTargets targets_;
    gpu::UniquePipelineLayout pipeline_layout_;
    gpu::UniquePipeline single_sided_;  // back faces culled
    gpu::UniquePipeline double_sided_;  // no culling
};

}  // namespace penumbra::renderer

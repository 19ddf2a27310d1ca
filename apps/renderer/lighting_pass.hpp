#pragma once
// Lighting pass of the tools' renderer: shades the scene with the sun, spot and point
// lights and ambient, writing three colour targets (tone-mapped sRGB colour, one light's
// exact visibility, the cascade index). With ShadowResolve::Forward every shadow is
// sampled here through Penumbra's descriptor set and GLSL library (set 2), over a
// reverse-Z depth buffer of its own; with ShadowResolve::Deferred it draws over the
// ScreenPrepass's depth with an equal test and reads each light's shadow from the
// ShadowSystem's visibility image (set 3). When it traces contact shadows itself (forward,
// and for `--aov contact`) it draws over the pre-pass's depth and samples it too (set 3),
// with penumbra_sun_contact() / penumbra_light_contact().
#include <vulkan/vulkan.h>

#include <cstdint>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/settings.hpp"
#include "penumbra/shadow_system.hpp"
#include "renderer/draw_data.hpp"

namespace penumbra::renderer {

struct LightingTargets {
    gpu::Image color;       // R8G8B8A8_SRGB
    gpu::Image visibility;  // R16_UNORM, 1 where no geometry
    gpu::Image cascade;     // R8_UINT, RENDERER_NO_CASCADE where none applies
    gpu::Image depth;       // D32_SFLOAT, reverse-Z (only without a pre-pass: else the pass tests its depth)
};

class LightingPass {
public:
    // Set 0 is `frame_set_layout` (the renderer's frame uniforms and lights), set 1 the
    // materials, set 2 the ShadowSystem's descriptor set (set 3 the visibility image when
    // deferred or tracing contact shadows); the fragment shader is specialized with the
    // ShadowSystem's filter constants. `prepass_depth` is the ScreenPrepass's depth, null
    // without a pre-pass; deferred or with `contact_shadows` (the pass traces them) the pass
    // tests against it (and samples it for the trace), otherwise it draws a depth of its own.
    LightingPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                 VkDescriptorSetLayout material_set_layout, const ShadowSystem& shadows, uint32_t width,
                 uint32_t height, ShadowResolve resolve, bool contact_shadows, const gpu::Image* prepass_depth);

    const LightingTargets& targets() const { return targets_; }

    // Rebuilds the pipelines with the ShadowSystem's current specialization constants (after
    // an update_settings() that changed them); the GPU must be done with the old ones.
    void respecialize(const ShadowSystem& shadows);

    // Deferred: points set 3 at the ShadowSystem's visibility image (after record_visibility(),
    // before record(); the descriptor is rewritten only when the image changed, and the
    // previous frame must have completed).
    void use_visibility_image(const VisibilityImage& visibility);

    // Renders every draw; leaves the colour targets in TRANSFER_SRC for readback. Deferred,
    // the pre-pass's depth is in gpu::ImageState::DepthReadOnly and stays there.
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, VkDescriptorSet shadow_set, const DrawData& data) const;

private:
    const gpu::Device& device_;
    void begin_rendering(VkCommandBuffer cmd) const;

    uint32_t width_;
    uint32_t height_;
    ShadowResolve resolve_;
    bool contact_shadows_ = false;               // the pass traces contact shadows
    const gpu::Image* prepass_depth_ = nullptr;  // null: the pass has a depth buffer of its own
    LightingTargets targets_;
    gpu::UniqueDescriptorSetLayout screen_set_layout_;  // deferred or contact: set 3
    gpu::UniqueDescriptorPool screen_pool_;
    VkDescriptorSet screen_set_ = VK_NULL_HANDLE;
    VkImageView visibility_view_ = VK_NULL_HANDLE;  // what screen_set_ points at
    gpu::UniqueSampler nearest_;
    gpu::UniquePipelineLayout pipeline_layout_;
    gpu::UniquePipeline single_sided_;  // back faces culled
    gpu::UniquePipeline double_sided_;  // no culling
};

}  // namespace penumbra::renderer

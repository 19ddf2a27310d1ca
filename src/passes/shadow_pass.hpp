#pragma once
// Shadow-map depth pass for the sun's cascades. Owns the layered D32 shadow map (one
// layer per cascade) and the caster pipelines of its strategy: opaque casters with no
// fragment shader, alpha-masked casters whose fragment shader discards below the mask's
// cutoff. Per-cascade strategy: one rendering pass per layer with that cascade's culled
// draws. Multiview strategy: one pass whose view mask covers every cascade; the vertex
// shader adds gl_ViewIndex to the cascade.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "passes/casters.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/gpu/timestamps.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

class ShadowPass {
public:
    // `frame_set_layout` is set 0 of the caster pipelines (the frame's uniforms), and
    // `alpha_mask_set_layout` set 1. Multiview throws DeviceError without the multiview
    // feature, InputError for more cascades than the device renders views in one pass.
    ShadowPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
               VkDescriptorSetLayout alpha_mask_set_layout, uint32_t resolution, uint32_t cascade_count,
               ShadowStrategy strategy);

    const gpu::Image& shadow_map() const { return shadow_map_; }
    uint32_t cascade_count() const { return cascade_count_; }
    void prepare_pipelines(const VertexFormats& formats) { pipelines_.prepare(formats); }

    // Records the depth rendering of every cascade and leaves the shadow map in
    // ImageState::ShaderSampled. lists[c] are the draws for cascade c. With a timer, each
    // cascade's rendering is a scope "shadow_cascade_<c>" (multiview: one, "shadow_multiview").
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                const std::vector<DrawList>& lists, const BiasSettings& bias, const CasterFaceCulling& culling,
                gpu::GpuTimer* timer = nullptr) const;

private:
    void begin_rendering(VkCommandBuffer cmd, VkImageView view, uint32_t view_mask, const BiasSettings& bias) const;

    const gpu::Device& device_;
    uint32_t resolution_;
    uint32_t cascade_count_;
    ShadowStrategy strategy_;
    gpu::Image shadow_map_;
    gpu::UniquePipelineLayout pipeline_layout_;
    CasterPipelines pipelines_;
};

}  // namespace penumbra::passes

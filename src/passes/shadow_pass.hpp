#pragma once
// Shadow-map depth pass for the directional light's cascades. Owns the layered D32
// shadow map (one layer per cascade) and two pipelines per strategy: opaque casters
// with no fragment shader, and alpha-masked casters whose fragment shader discards
// below the material's cutoff. Per-cascade strategy: one rendering pass per layer with
// that cascade's culled draws. Multiview strategy: one pass whose view mask covers
// every cascade; the vertex shader picks the cascade matrix by gl_ViewIndex.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "gpu/device.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "gpu/timestamps.hpp"
#include "passes/draw_data.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

// Indices into DrawData::draws to render into one cascade.
using CascadeDrawList = std::vector<uint32_t>;

class ShadowPass {
public:
    // Builds the pipelines of `strategy` only. Throws InputError when multiview is asked for
    // more cascades than the device renders views in one pass (maxMultiviewViewCount).
    ShadowPass(const gpu::Device& device, VkDescriptorSetLayout material_set_layout, uint32_t resolution,
               uint32_t cascade_count, ShadowStrategy strategy);

    // Set 0 of the shadow pipelines: binding 0 = the frame uniform buffer.
    VkDescriptorSetLayout frame_set_layout() const { return frame_set_layout_; }
    const gpu::Image& shadow_map() const { return shadow_map_; }
    uint32_t cascade_count() const { return cascade_count_; }

    // Records the depth rendering of every cascade and leaves the shadow map ready for
    // fragment-shader sampling. draw_lists[c] are the draws for cascade c. With a timer,
    // each cascade's rendering is a scope "shadow_cascade_<c>" (multiview: one scope,
    // "shadow_multiview").
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const DrawData& data,
                const std::vector<CascadeDrawList>& draw_lists, const BiasSettings& bias,
                gpu::GpuTimer* timer = nullptr) const;

private:
    void record_per_cascade(VkCommandBuffer cmd, const DrawData& data, const std::vector<CascadeDrawList>& lists,
                            const BiasSettings& bias, gpu::GpuTimer* timer) const;
    void record_multiview(VkCommandBuffer cmd, const DrawData& data, const std::vector<CascadeDrawList>& lists,
                          const BiasSettings& bias, gpu::GpuTimer* timer) const;
    void record_draws(VkCommandBuffer cmd, const DrawData& data, const CascadeDrawList& list, uint32_t cascade,
                      VkPipeline opaque, VkPipeline masked) const;
    void begin_rendering(VkCommandBuffer cmd, VkImageView view, uint32_t view_mask, const BiasSettings& bias) const;

    const gpu::Device& device_;
    uint32_t resolution_;
    uint32_t cascade_count_;
    ShadowStrategy strategy_;
    gpu::Image shadow_map_;
    gpu::UniqueDescriptorSetLayout frame_set_layout_;
    gpu::UniquePipelineLayout pipeline_layout_;
    gpu::UniquePipeline opaque_per_cascade_;
    gpu::UniquePipeline masked_per_cascade_;
    gpu::UniquePipeline opaque_multiview_;
    gpu::UniquePipeline masked_multiview_;
};

}  // namespace penumbra::passes

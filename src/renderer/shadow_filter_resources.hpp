#pragma once
// What the renderer owns for the shadow filters beyond the depth pass: the raw-depth
// sampler (PCSS blocker search) and, for the moment filters (vsm, evsm, msm), the
// moments pass with its frame descriptor set. It also fills the lighting set's shadow
// bindings, pointing them at the depth map that the frame actually renders.
#include <optional>
#include <vector>

#include "core/render_settings.hpp"
#include "gpu/context.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "passes/draw_data.hpp"
#include "passes/moments_pass.hpp"

namespace penumbra::renderer {

class ShadowFilterResources {
public:
    ShadowFilterResources(const gpu::Context& context, VkDescriptorSetLayout material_set_layout,
                          const RenderSettings& settings, VkBuffer frame_uniforms, VkDeviceSize frame_uniforms_size);

    // True when the frame renders the moments pass instead of the depth pass.
    bool uses_moments() const { return moments_pass_.has_value(); }

    // The depth map the lighting pass reads: the moments pass's depth attachment for the
    // moment filters, else `depth_pass_map` (the depth pass's shadow map).
    const gpu::Image& depth_map(const gpu::Image& depth_pass_map) const;

    // Bindings 1-3 of the lighting frame set: the comparison sampler and the raw depth on
    // depth_map(depth_pass_map), and the moments (or that depth map again).
    void write_lighting_bindings(VkDescriptorSet lighting_set, const gpu::Image& depth_pass_map,
                                 VkSampler comparison_sampler) const;

    // Records the moments pass (requires uses_moments()).
    void record_moments(VkCommandBuffer cmd, const passes::DrawData& data,
                        const std::vector<std::vector<uint32_t>>& draw_lists) const;

    // GPU memory of the moments pass's images (0 without it).
    uint64_t memory_bytes() const;

private:
    const gpu::Context& context_;
    gpu::UniqueSampler depth_sampler_;
    std::optional<passes::MomentsPass> moments_pass_;
    gpu::UniqueDescriptorPool pool_;
    VkDescriptorSet moments_frame_set_ = VK_NULL_HANDLE;
};

}  // namespace penumbra::renderer

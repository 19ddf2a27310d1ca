#pragma once
// Moments pass for the prefiltered shadow filters (vsm, evsm, msm; docs/filters.md) of the sun.
// For every cascade it renders the casters into one layer of a layered colour target
// that holds the moments of their distance from the light (shaders/include/moments.glsl),
// depth-tested against its own layered reverse-Z depth attachment, after a full-screen
// triangle at the far plane has written the moments of "no caster". Then, optionally,
// the separable Gaussian blur of passes/moments_blur.hpp (which also names the formats).
// Casters render per cascade (no multiview variant); the depth attachment is a complete
// reverse-Z shadow map, so the renderer binds it where a depth map is expected.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "gpu/device.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "passes/draw_data.hpp"
#include "passes/moments_blur.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

class MomentsPass {
public:
    // Requires a moment filter (is_moment_filter(filter.mode)).
    MomentsPass(const gpu::Device& device, VkDescriptorSetLayout material_set_layout, uint32_t resolution,
                uint32_t cascade_count, const FilterSettings& filter);

    // Set 0 of the moments pipelines: binding 0 = the frame uniform buffer (vertex and
    // fragment stages: the encoding reads the EVSM exponents).
    VkDescriptorSetLayout frame_set_layout() const { return frame_set_layout_; }
    const gpu::Image& moments() const { return moments_; }
    const gpu::Image& depth() const { return depth_; }
    // Bilinear where the device filters the moments format linearly, else nearest.
    VkSampler moments_sampler() const { return sampler_; }
    // The moments, the depth attachment and the blur's scratch image.
    uint64_t memory_bytes() const;

    // Records moments (and blur) for every cascade; draw_lists[c] are the draws (indices
    // into data.draws) for cascade c. Leaves moments() and depth() in FragmentSampled.
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const DrawData& data,
                const std::vector<std::vector<uint32_t>>& draw_lists) const;

private:
    const gpu::Device& device_;
    void render_cascade(VkCommandBuffer cmd, const DrawData& data, const std::vector<uint32_t>& draws,
                        uint32_t cascade) const;

    uint32_t resolution_;
    uint32_t cascade_count_;
    gpu::Image moments_;
    gpu::Image depth_;
    gpu::UniqueSampler sampler_;
    gpu::UniqueDescriptorSetLayout frame_set_layout_;
    gpu::UniquePipelineLayout caster_layout_;
    gpu::UniquePipeline far_plane_;
    gpu::UniquePipeline casters_;
    std::optional<MomentsBlur> blur_;
};

}  // namespace penumbra::passes

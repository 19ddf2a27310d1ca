#pragma once
// Moments pass for the prefiltered shadow filters (vsm, evsm, msm; docs/filters.md) of the
// sun. For every cascade it renders the casters into one layer of a layered colour target
// that holds the moments of their distance from the light (penumbra/glsl/moments.glsl),
// depth-tested against its own layered reverse-Z depth attachment, after a full-screen
// triangle at the far plane has written the moments of "no caster". Then, optionally, the
// separable Gaussian blur of passes/moments_blur.hpp (which also names the formats).
// Casters render per cascade (no multiview variant); the depth attachment is a complete
// reverse-Z shadow map, so it is bound where a depth map is expected.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "passes/casters.hpp"
#include "passes/moments_blur.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

class MomentsPass {
public:
    // Requires a moment filter (is_moment_filter(filter.mode)). Set 0 of its pipelines is
    // `frame_set_layout` (the frame's uniforms: the moments encoding reads the EVSM
    // exponents), set 1 the alpha mask.
    MomentsPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                VkDescriptorSetLayout alpha_mask_set_layout, uint32_t resolution, uint32_t cascade_count,
                const FilterSettings& filter);

    const gpu::Image& moments() const { return moments_; }
    const gpu::Image& depth() const { return depth_; }
    // Bilinear where the device filters the moments format linearly, else nearest.
    VkSampler moments_sampler() const { return sampler_; }
    // The moments, the depth attachment and the blur's scratch image.
    uint64_t memory_bytes() const;
    void prepare_pipelines(const VertexFormats& formats) { casters_.prepare(formats); }

    // Records moments (and blur) for every cascade; lists[c] are the draws of cascade c.
    // Leaves moments() and depth() in ImageState::ShaderSampled.
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                const std::vector<DrawList>& lists, const CasterFaceCulling& culling) const;

private:
    void render_cascade(VkCommandBuffer cmd, const CasterScene& scene, const DrawList& draws, uint32_t cascade,
                        const CasterFaceCulling& culling) const;

    const gpu::Device& device_;
    uint32_t resolution_;
    uint32_t cascade_count_;
    gpu::Image moments_;
    gpu::Image depth_;
    gpu::UniqueSampler sampler_;
    gpu::UniquePipelineLayout caster_layout_;
    gpu::UniquePipeline far_plane_;
    CasterPipelines casters_;
    std::optional<MomentsBlur> blur_;
};

}  // namespace penumbra::passes

#pragma once
// Moments of the spot and point lights' shadow maps, for the prefiltered filters (vsm,
// evsm, msm; docs/local-lights.md). After the local shadow pass, each rendered layer of
// its depth map is converted to the moments of the occluders' normalised linear distance
// (shaders/local_moments.frag), then optionally blurred (passes/moments_blur.hpp), each
// light within the corner of its layer that it uses.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "core/glm_config.hpp"
#include "passes/moments_blur.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

// One layer to convert: its index, the texels per side its light uses, and the light's
// depth range (the perspective that rendered it).
struct LocalMomentsLayer {
    uint32_t layer = 0;
    uint32_t resolution = 0;
    float near_plane = 0.0f;
    float far_plane = 0.0f;
};

class LocalMomentsPass {
public:
    // Moments for every layer of `depth_map` (the local shadow map), read with `depth_sampler`
    // (nearest); requires a moment filter (is_moment_filter(filter.mode)).
    LocalMomentsPass(const gpu::Device& device, const gpu::Image& depth_map, VkSampler depth_sampler,
                     const FilterSettings& filter);

    const gpu::Image& moments() const { return moments_; }
    VkSampler sampler() const { return sampler_; }
    uint64_t memory_bytes() const;

    // Expects the depth map in ShaderSampled (as the local shadow pass leaves it); leaves
    // the moments in ShaderSampled. `evsm_exponents` are the clamped (positive, negative) ones.
    void record(VkCommandBuffer cmd, const std::vector<LocalMomentsLayer>& layers, glm::vec2 evsm_exponents) const;

private:
    const gpu::Device& device_;
    gpu::Image moments_;
    gpu::UniqueSampler sampler_;
    gpu::UniqueDescriptorSetLayout set_layout_;
    gpu::UniqueDescriptorPool pool_;
    VkDescriptorSet depth_set_ = VK_NULL_HANDLE;
    gpu::UniquePipelineLayout layout_;
    gpu::UniquePipeline convert_;
    std::optional<MomentsBlur> blur_;
};

}  // namespace penumbra::passes

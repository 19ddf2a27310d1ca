#pragma once
// The maps a ShadowSystem renders and their passes: the sun's cascades (a depth pass, with
// a moments conversion for the moment filters) and the spot/point lights' layered map
// (resized to what the frame's lights need, with a moments conversion for the moment filters).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/local_lights.hpp"
#include "library/retired.hpp"
#include "passes/casters.hpp"
#include "passes/local_shadow_pass.hpp"
#include "passes/moments_conversion.hpp"
#include "passes/shadow_pass.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/gpu/timestamps.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::library {

// A map as the descriptor set binds it: the depth (comparison and raw) and, for the moment
// filters, the moments with their sampler.
struct SampledMaps {
    const gpu::Image* depth = nullptr;
    const gpu::Image* moments = nullptr;
    VkSampler moments_sampler = VK_NULL_HANDLE;
};

class CascadeMaps {
public:
    CascadeMaps(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                VkDescriptorSetLayout alpha_mask_set_layout, const ShadowSettings& settings, uint32_t frames_in_flight);

    void prepare_pipelines(const passes::VertexFormats& formats);
    SampledMaps sampled() const;
    uint64_t memory_bytes() const;

    bool cached() const { return depth_pass_.cached(); }
    const passes::GpuCasterCulling* gpu_culling() const { return depth_pass_.gpu_culling(); }
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const passes::CasterScene& scene,
                const std::vector<passes::CascadeDraws>& draws, const ShadowSettings& settings,
                const passes::CasterFaceCulling& culling, bool sun_casts, uint64_t frame, gpu::GpuTimer* timer);

private:
    const gpu::Device& device_;
    passes::ShadowPass depth_pass_;
    gpu::UniqueSampler depth_sampler_;                  // nearest: the moments conversion reads raw depth
    std::optional<passes::MomentsConversion> moments_;  // vsm, evsm, msm
};

class LocalMaps {
public:
    LocalMaps(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
              VkDescriptorSetLayout alpha_mask_set_layout, const ShadowSettings& settings, RetiredObjects& retired,
              uint32_t frames_in_flight);

    void prepare_pipelines(const passes::VertexFormats& formats) { pass_.prepare_pipelines(formats); }
    // Makes the map hold `plan`'s layers at its atlas resolution (a 16 x 16 placeholder
    // without shadowed lights); a replaced map is retired.
    void fit(const LocalShadowPlan& plan, uint64_t frame);
    // Changes whenever fit() replaces the map: nothing an earlier map held can be kept.
    uint64_t generation() const { return generation_; }
    SampledMaps sampled() const;
    uint64_t memory_bytes() const;  // 0 for the placeholder
    const passes::GpuCasterCulling* gpu_culling() const { return pass_.gpu_culling(); }

    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const passes::CasterScene& scene,
                const std::vector<passes::LocalShadowLayer>& layers, const LocalShadowPlan& plan,
                const ShadowSettings& settings, uint64_t frame, gpu::GpuTimer* timer);

private:
    const gpu::Device& device_;
    FilterSettings filter_;
    RetiredObjects& retired_;
    passes::LocalShadowPass pass_;
    gpu::UniqueSampler depth_sampler_;  // nearest: the moments conversion reads raw depth
    std::unique_ptr<gpu::Image> map_;
    std::unique_ptr<passes::MomentsConversion> moments_;  // moment filters with shadowed lights only
    uint32_t layers_ = 0;                                 // 0: the placeholder
    bool placeholder_ready_ = false;                      // the placeholder cleared and readable
    uint32_t resolution_ = 0;
    uint64_t generation_ = 0;
};

}  // namespace penumbra::library

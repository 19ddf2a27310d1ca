#pragma once
// Moments from depth for the prefiltered shadow filters (vsm, evsm, msm; docs/filters.md),
// in compute: after the ordinary depth pass has rendered a layered reverse-Z depth map
// (the sun's cascades, or the spot and point lights' layers), each layer is converted to
// the moments of its occluders' distance (shaders/moments_convert.comp), then blurred by a
// separable Gaussian (shaders/moments_blur.comp) through a scratch image. A layer may use
// only its top-left `resolution` x `resolution` corner (a local light below the map's
// resolution): conversion and blur stay inside it. Compute runs on every shader core; the
// rasterised moments pass it replaces drew every caster a second time into a colour target
// and blurred in fragment shaders, 3.6x (vsm) to 5.5x (evsm, msm) the depth pass on an H100.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "core/glm_config.hpp"
#include "core/shadow_cache.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

// RG32F for VSM and 2-component EVSM, RGBA32F for 4-component EVSM and MSM,
// RGBA16_UNORM for MSM with the optimized quantization (Peters & Klein 2015).
VkFormat moments_format(const FilterSettings& filter);

// One layer to convert: its index, the texels per side it uses, and the depth mapping that
// rendered it: the light's near plane and range for a perspective layer, far_plane 0 for
// an orthographic one (the sun's cascades). The used texels start at the layer's corner,
// or for a toroidal cascade at its layer_origin, wrapping around the layer's edges.
struct MomentsLayer {
    uint32_t layer = 0;
    uint32_t resolution = 0;
    float near_plane = 0.0f;
    float far_plane = 0.0f;
    glm::uvec2 layer_origin{0};
    // Cached cascades: the used texels whose depth changed since the moments were last
    // computed (used-texel coordinates, from the layer origin); only the moments they reach
    // are computed again (needs partial_updates()). std::nullopt: the whole layer.
    std::optional<std::vector<TexelRect>> changed;
};

class MomentsConversion {
public:
    // Moments for every layer of `depth_map`, read with `depth_sampler` (nearest); requires
    // a moment filter (is_moment_filter(filter.mode)).
    // `partial_updates`: layers may be converted only where their depth changed
    // (MomentsLayer::changed); with a blur this keeps the unblurred moments in a third image.
    MomentsConversion(const gpu::Device& device, const gpu::Image& depth_map, VkSampler depth_sampler,
                      const FilterSettings& filter, bool partial_updates = false);

    const gpu::Image& moments() const { return moments_; }
    // Bilinear where the device filters the moments format linearly, else nearest.
    VkSampler sampler() const { return sampler_; }
    uint64_t memory_bytes() const;  // the moments, the blur's scratch image and the unblurred moments
    bool partial_updates() const { return partial_updates_; }

    // Expects the depth map in ShaderSampled (as the depth passes leave it); leaves the
    // moments in ShaderSampled. `evsm_exponents` are the clamped (positive, negative) ones.
    // `keep_others`: the moments of layers not listed stay as an earlier frame left them
    // (cached local shadows; nothing is recorded for an empty list), else they are undefined.
    void record(VkCommandBuffer cmd, const std::vector<MomentsLayer>& layers, glm::vec2 evsm_exponents,
                bool keep_others = false) const;

private:
    enum class Step { Convert, Horizontal, Vertical };
    void dispatch(VkCommandBuffer cmd, const MomentsLayer& layer, glm::vec2 evsm_exponents, Step step) const;
    void dispatch_region(VkCommandBuffer cmd, const MomentsLayer& layer, glm::vec2 evsm_exponents, Step step,
                         const TexelRect& region) const;

    const gpu::Device& device_;
    uint32_t blur_radius_;
    uint32_t side_;  // of the layers
    bool partial_updates_;
    gpu::Image moments_;
    std::optional<gpu::Image> scratch_;  // with a blur
    std::optional<gpu::Image> raw_;      // with a blur and partial updates: the unblurred moments
    // Whether a recorded frame has written them (their first use must not keep contents).
    mutable bool raw_initialised_ = false;
    mutable bool scratch_initialised_ = false;
    gpu::UniqueSampler sampler_;
    gpu::UniqueDescriptorSetLayout convert_layout_;
    gpu::UniqueDescriptorSetLayout blur_layout_;
    gpu::UniqueDescriptorPool pool_;
    VkDescriptorSet convert_set_ = VK_NULL_HANDLE;
    VkDescriptorSet horizontal_set_ = VK_NULL_HANDLE;  // moments -> scratch
    VkDescriptorSet vertical_set_ = VK_NULL_HANDLE;    // scratch -> moments
    gpu::UniquePipelineLayout convert_pipeline_layout_;
    gpu::UniquePipelineLayout blur_pipeline_layout_;
    gpu::UniquePipeline convert_;
    gpu::UniquePipeline blur_;
};

}  // namespace penumbra::passes

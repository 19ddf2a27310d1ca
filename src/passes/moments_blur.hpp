#pragma once
// The separable Gaussian blur of a layered moments map (shaders/moments_blur.frag), shared
// by the sun's moments pass and the local lights' moments pass: per layer, a horizontal
// pass into a scratch image and a vertical pass back. Moments are linear in the depth
// distribution, so blurring them filters the shadow (Donnelly & Lauritzen 2006). A layer
// may use only its top-left `resolution` x `resolution` corner (a local light below the
// map's resolution): taps clamp to that corner, so texels of other lights never mix in.
// Also the images and sampler every moments map needs.
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

// RG32F for VSM and 2-component EVSM, RGBA32F for 4-component EVSM and MSM,
// RGBA16_UNORM for MSM with the optimized quantization (Peters & Klein 2015).
VkFormat moments_format(const FilterSettings& filter);

// A layered colour image of `format`, rendered to and sampled, with per-layer views.
gpu::Image create_moments_image(const gpu::Device& device, VkFormat format, uint32_t resolution, uint32_t layers);

// Bilinear where the device filters `format` linearly, else nearest; clamped to the edge.
gpu::UniqueSampler create_moments_sampler(const gpu::Device& device, VkFormat format);

// A full-screen triangle (shaders/fullscreen.vert) with `fragment`, one colour target.
gpu::UniquePipeline create_fullscreen_pipeline(const gpu::Device& device, VkPipelineLayout layout,
                                               std::span<const uint32_t> fragment, VkFormat color_format,
                                               VkFormat depth_format, const FilterSettings& filter);

// Begins dynamic rendering of `resolution` x `resolution` texels into `color` (and `depth`).
void begin_layer_rendering(const gpu::Device& device, VkCommandBuffer cmd, uint32_t resolution,
                           const VkRenderingAttachmentInfo& color, const VkRenderingAttachmentInfo* depth);

// An attachment that stores its result; clear values are zero (reverse-Z far plane for depth).
VkRenderingAttachmentInfo stored_attachment(VkImageView view, VkImageLayout layout, VkAttachmentLoadOp load);

// One layer to blur and the texels per side it uses.
struct BlurLayer {
    uint32_t layer = 0;
    uint32_t resolution = 0;
};

class MomentsBlur {
public:
    // Blurs `moments` (which must outlive this object) with a kernel of `radius` texels (> 0).
    MomentsBlur(const gpu::Device& device, const gpu::Image& moments, VkSampler sampler, uint32_t radius,
                const FilterSettings& filter);

    // Expects `moments` (the image given to the constructor) in ColorAttachment, after its
    // writes; leaves it there with the blurred moments.
    void record(VkCommandBuffer cmd, const gpu::Image& moments, const std::vector<BlurLayer>& layers) const;

    uint64_t memory_bytes() const { return scratch_.memory_size; }

private:
    const gpu::Device& device_;
    void blur_direction(VkCommandBuffer cmd, VkDescriptorSet source, const gpu::Image& target,
                        const std::vector<BlurLayer>& layers, bool horizontal) const;

    uint32_t radius_;
    gpu::Image scratch_;
    gpu::UniqueDescriptorSetLayout set_layout_;
    gpu::UniqueDescriptorPool pool_;
    std::array<VkDescriptorSet, 2> sets_{};  // [0] reads the moments, [1] reads scratch_
    gpu::UniquePipelineLayout layout_;
    gpu::UniquePipeline pipeline_;
};

}  // namespace penumbra::passes

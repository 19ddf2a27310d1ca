#pragma once
// The screen-space shadow resolve (shaders/visibility_resolve.comp): a compute pass that,
// once per pixel of the caller's depth buffer, evaluates the sun's and every shadowed local
// light's visibility with the configured filter into an RGBA8 array image.
#include <vulkan/vulkan.h>

#include "passes/shader_interface.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/settings.hpp"
#include "penumbra/shadow_system.hpp"

namespace penumbra::passes {

// The image the resolve writes: Penumbra's own or the caller's (VisibilityTarget).
struct ResolveTarget {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;  // a 2D array view of every layer
    uint32_t layers = 0;
};

// The queue the resolve is recorded for: the graphics queue (its barriers reach the
// caller's fragment shaders) or a compute-only queue (async compute: compute stages only).
enum class ResolveQueue { Graphics, Compute };

class VisibilityResolvePass {
public:
    // `shadow_set_layout` is the ShadowSystem's descriptor set (set 0 of the pass); the pass's
    // own set 1 holds the screen's depth and normals and the target.
    VisibilityResolvePass(const gpu::Device& device, VkDescriptorSetLayout shadow_set_layout,
                          const FilterSettings& filter);

    VkDescriptorSetLayout screen_set_layout() const { return screen_set_layout_; }
    // Rebuilds the pipeline for another filter (its specialization constants); the layouts
    // stay. Returns the replaced pipeline, which recorded frames may still use.
    gpu::UniquePipeline respecialize(const FilterSettings& filter);
    // Writes set 1: the depth, the normals and the face normals (the depth again for those
    // absent) sampled with a nearest sampler in the given layouts, and `target` (a 2D array
    // view) as the storage image.
    void write_screen_set(VkDescriptorSet set, const ScreenInputs& screen, VkImageView target) const;

    // Dispatches one thread per pixel of `constants.width` x `constants.height`; takes
    // `target` from ShaderSampled (or unused) to ComputeStorageWrite and back to ShaderSampled
    // (on a compute queue from and to ComputeSampled).
    void record(VkCommandBuffer cmd, VkDescriptorSet shadow_set, VkDescriptorSet screen_set,
                const ResolveTarget& target, const shader::ResolvePushConstants& constants,
                ResolveQueue queue = ResolveQueue::Graphics) const;

private:
    gpu::UniquePipeline create_pipeline(const FilterSettings& filter) const;

    const gpu::Device& device_;
    gpu::UniqueDescriptorSetLayout screen_set_layout_;
    gpu::UniquePipelineLayout layout_;
    gpu::UniquePipeline pipeline_;
    gpu::UniqueSampler nearest_;
};

// The visibility target: RGBA8 layers of width x height, four slots per layer.
gpu::Image create_visibility_image(const gpu::Device& device, uint32_t width, uint32_t height, uint32_t layers);

}  // namespace penumbra::passes

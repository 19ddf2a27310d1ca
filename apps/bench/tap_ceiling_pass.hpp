#pragma once
// Sampling-rate ceiling: a full-screen pass whose every pixel takes N depth-comparison
// taps from a layered D32 shadow map through the same sampler state as the lighting
// maps (bilinear compare, clamp to edge). Timing it at a given size and N bounds what
// any filter with that many taps can cost (`penumbra bench --ceiling taps`). The pass
// owns its shadow map (cleared once, never rendered) and an RGBA8 target.
#include <vulkan/vulkan.h>

#include <cstdint>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"

namespace penumbra::bench {

struct TapCeilingDesc {
    uint32_t width = 0;  // target size in pixels
    uint32_t height = 0;
    uint32_t shadow_resolution = 2048;
    uint32_t shadow_layers = 4;
    uint32_t taps = 16;  // per pixel
};

class TapCeilingPass {
public:
    TapCeilingPass(const gpu::Device& device, const TapCeilingDesc& desc);

    // Clears the shadow map and leaves it ready for sampling; record once before any frame.
    void record_setup(VkCommandBuffer cmd) const;
    // The full-screen pass; leaves the target in COLOR_ATTACHMENT.
    void record(VkCommandBuffer cmd) const;

    uint64_t taps_per_frame() const { return uint64_t{desc_.width} * desc_.height * desc_.taps; }
    uint64_t shadow_map_bytes() const { return shadow_map_.memory_size; }

private:
    const gpu::Device& device_;
    TapCeilingDesc desc_;
    gpu::Image shadow_map_;
    gpu::Image target_;
    gpu::UniqueSampler sampler_;
    gpu::UniqueDescriptorSetLayout set_layout_;
    gpu::UniqueDescriptorPool descriptor_pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    gpu::UniquePipelineLayout pipeline_layout_;
    gpu::UniquePipeline pipeline_;
};

}  // namespace penumbra::bench

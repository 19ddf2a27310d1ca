#pragma once
// Sampling-rate ceilings: a pass whose every pixel takes N depth-comparison taps from a
// layered D32 shadow map through the same sampler state as the lighting maps (bilinear
// compare, clamp to edge), as a full-screen fragment pass (`penumbra bench --ceiling
// taps`: the units of forward shading) or a compute dispatch of one thread per pixel
// (`--ceiling compute-taps`: the units of the deferred resolve). Timing it at a given size
// and N bounds what any filter with that many taps can cost there. The pass owns its
// shadow map (cleared once, never rendered) and an RGBA8 target.
#include <vulkan/vulkan.h>

#include <cstdint>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"

namespace penumbra::bench {

enum class TapCeilingUnits {
    Fragment,  // a full-screen triangle into a colour attachment
    Compute,   // 8 x 8 workgroups into a storage image
};

struct TapCeilingDesc {
    uint32_t width = 0;  // target size in pixels
    uint32_t height = 0;
    uint32_t shadow_resolution = 2048;
    uint32_t shadow_layers = 4;
    uint32_t taps = 16;  // per pixel
    TapCeilingUnits units = TapCeilingUnits::Fragment;
};

class TapCeilingPass {
public:
    TapCeilingPass(const gpu::Device& device, const TapCeilingDesc& desc);

    // Clears the shadow map and leaves it ready for sampling; record once before any frame.
    void record_setup(VkCommandBuffer cmd) const;
    // The pass; leaves the target in COLOR_ATTACHMENT (fragment) or GENERAL (compute).
    void record(VkCommandBuffer cmd) const;

    uint64_t taps_per_frame() const { return uint64_t{desc_.width} * desc_.height * desc_.taps; }
    uint64_t shadow_map_bytes() const { return shadow_map_.memory_size; }

private:
    void record_fragment(VkCommandBuffer cmd, const void* params, uint32_t size) const;
    void record_compute(VkCommandBuffer cmd, const void* params, uint32_t size) const;

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

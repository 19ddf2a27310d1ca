#pragma once
// The ways to start a shadow-map layer, timed side by side (`penumbra bench --ceiling
// layer-start`): every frame starts all layers of a D32 layered map (the cascades'
// resolution and count) four ways, each in its own GPU scope, and leaves the map sampled
// as the shadow pass does:
//   start_render_pass_clear  dynamic rendering with loadOp CLEAR and no draw, per layer
//                            (what ShadowPass does before its casters)
//   start_clear_image        one vkCmdClearDepthStencilImage over every layer
//   start_copy_cleared       vkCmdCopyImage from a layer cleared once, per layer
//   start_clear_quarter      loadOp CLEAR over a render area of a quarter of each layer
//                            (a cascade whose casters cover only part of it)
// An empty 2048^2 layer cost 0.30 ms on an H200 inside the shadow pass; this tells what
// the clear itself costs, and which way is fastest.
#include <vulkan/vulkan.h>

#include <cstdint>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/gpu/timestamps.hpp"

namespace penumbra::bench {

class LayerStartPass {
public:
    LayerStartPass(const gpu::Device& device, uint32_t resolution, uint32_t layers);

    // Clears the copy source once; record before any frame.
    void record_setup(VkCommandBuffer cmd) const;
    // The four ways, each in its scope of `timer`.
    void record(VkCommandBuffer cmd, gpu::GpuTimer& timer) const;

    uint64_t texels_per_way() const { return uint64_t{resolution_} * resolution_ * layers_; }
    uint64_t map_bytes() const { return map_.memory_size + source_.memory_size; }

private:
    void render_pass_clear(VkCommandBuffer cmd, uint32_t extent) const;
    void clear_image(VkCommandBuffer cmd) const;
    void copy_cleared(VkCommandBuffer cmd) const;

    const gpu::Device& device_;
    uint32_t resolution_;
    uint32_t layers_;
    gpu::Image map_;
    gpu::Image source_;  // one layer, cleared once
};

}  // namespace penumbra::bench

#pragma once
// The sun's virtual shadow map, drawn: the physical page pool (one D32 2D array image whose
// layers hold 4 x 4 pages of 128^2 texels) and the pass that fills the pages the allocation listed this frame
// (passes/virtual_pages.hpp). Three steps, all on the GPU:
//   1. culling (shaders/virtual_cull.comp): every caster instance against the pages drawn
//      this frame, per clipmap level, into indexed indirect commands (the layered strategy's
//      buffers, a bucket's commands of every level together) whose instances are its pages;
//      an indirect dispatch the allocation sized, empty when no page is drawn;
//   2. clearing those pages (an indirect draw per level of one quad per page at depth 0);
//   3. drawing: one vkCmdDrawIndexedIndirectCount per bucket; the vertex shader
//      sends each instance to its page's layer and viewport (the viewport's scissor keeps it
//      in the page), with the cascades' depth bias, depth clamp, face culling and alpha test.
// Cached pages keep their texels: the pool is never cleared as a whole.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "passes/caster_culling.hpp"
#include "passes/casters.hpp"
#include "passes/virtual_pages.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/gpu/timestamps.hpp"

namespace penumbra::passes {

class VirtualShadowPass {
public:
    // `frame_set_layout` and `alpha_mask_set_layout` as the other caster passes'; the pages'
    // set layout comes from `pages`. Throws DeviceError when the device lacks the features
    // (EnabledFeatures::virtual_pages) or cannot hold the pool's layers in one image.
    VirtualShadowPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                      VkDescriptorSetLayout alpha_mask_set_layout, const VirtualPages& pages,
                      uint32_t frames_in_flight);

    void prepare_pipelines(const VertexFormats& formats) { pipelines_.prepare(formats); }

    // The culling's workgroups (x, y) for `scene` in a frame that draws pages: what
    // VirtualPages::prepare() passes on to the allocation, which sizes the dispatch.
    static glm::uvec2 cull_workgroups(const CasterScene& scene);

    // Records the three steps for the pages `pages` listed in `frame` (after its record()),
    // and the copy of the pages' counters for the host once the culling counted (so
    // VirtualPages::counters(frame) after the frame completes). `frame_set` is the caster
    // passes' set 0. On exit the pool is in VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, its
    // writes visible to fragment and compute reads.
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene, VirtualPages& pages,
                uint64_t frame, const BiasSettings& bias, const CasterFaceCulling& culling, gpu::GpuTimer* timer);

    const gpu::Image& pool() const { return pool_; }
    // Per level, the page draws and their triangles of `frame` (see GpuCasterCulling::culled).
    std::optional<std::vector<CulledLayer>> culled(uint64_t frame) const { return culling_.culled(frame); }
    uint64_t memory_bytes() const { return pool_.memory_size; }
    uint64_t buffer_bytes() const { return culling_.buffer_bytes(); }

private:
    void record_cull(VkCommandBuffer cmd, const CasterScene& scene, VirtualPages& pages, uint64_t frame);

    const gpu::Device& device_;
    GpuCasterCulling culling_;
    gpu::UniquePipelineLayout cull_layout_;
    gpu::UniquePipeline cull_pipeline_;
    gpu::UniquePipelineLayout clear_layout_;
    gpu::UniquePipeline clear_pipeline_;
    gpu::UniquePipelineLayout caster_layout_;
    CasterPipelines pipelines_;
    gpu::Image pool_;
    gpu::ImageState pool_state_ = gpu::ImageState::Undefined;
};

}  // namespace penumbra::passes

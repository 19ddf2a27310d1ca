#pragma once
// Shadow-map depth pass for the sun's cascades. Owns the layered D32 shadow map (one
// layer per cascade) and the caster pipelines of its strategy: opaque casters with no
// fragment shader, alpha-masked casters whose fragment shader discards below the mask's
// cutoff. Per-cascade strategy: one rendering pass per layer with that cascade's culled
// draws. Multiview strategy: one pass whose view mask covers every cascade; the vertex
// shader adds gl_ViewIndex to the cascade. Layered strategy: the GPU culls every caster
// against every cascade's tiles (caster_culling.hpp) and one pass over the layered map
// draws them, each command into its cascade's layer; the CPU neither culls nor records per
// caster.
//
// Per-cascade and layered passes place each cascade toroidally in its layer (Cascade::layer_origin):
// a world texel keeps its layer texel while the cascade moves, so the window wraps around
// the layer's edges and is drawn as up to four scissored tiles (core/shadow_cache.hpp's
// layer_pieces). A cached cascade (core/shadow_cache.hpp) therefore keeps its texels in
// place from frame to frame, and a frame (1) restores, from a second layered image that
// holds the static casters, the texels where dynamic casters were drawn last frame, (2)
// clears and draws the static casters only in the rectangles that need it (or the whole
// layer without a usable cache), (3) copies what the dynamic casters will cover into that
// image, and (4) draws the dynamic casters over the map.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "core/shadow_cache.hpp"
#include "passes/caster_culling.hpp"
#include "passes/casters.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/gpu/timestamps.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

// What a frame draws into one cascade. Rectangles are layer texels.
struct CascadeDraws {
    // Casters drawn into one piece of the cascade's window (core/shadow_cache.hpp's
    // LayerPiece): scissored to `rect`, with the vertex shader's tile offset.
    struct Region {
        TexelRect rect;
        uint32_t tile = 0;
        DrawList casters;
        TexelRect window;  // the same texels counted from the cascade's texel 0 (statistics)
    };
    glm::ivec2 layer_origin{0};  // Cascade::layer_origin
    // false: clear the layer and draw `regions` (every caster, or every static one with a
    // cache). true (cached): keep the layer's texels; clear each region, then draw it.
    bool reuse = false;
    glm::ivec2 shift{0};             // reuse: how many texels the window moved (statistics)
    std::vector<TexelRect> restore;  // reuse: copied from the cache first (dynamic casters were there)
    std::vector<Region> regions;     // the static casters (all casters without a cache)
    std::vector<TexelRect> store;    // copied into the cache after the static casters
    std::vector<Region> dynamic;     // drawn over the static ones (cached only)
    // reuse: the window texels (from the cascade's texel 0, not layer texels) whose depth may
    // differ from the last frame's: redrawn, under dynamic casters now or last frame, and the
    // window's edge texels after a move (the moments conversion updates only around them).
    std::vector<TexelRect> changed;
    // The dynamic casters' reach in window texels, inside one piece each (restored from the
    // cache next frame; the moments update around it).
    std::vector<TexelRect> dynamic_window;
};

// What the layered strategy's GPU culling draws this frame (the other strategies draw the
// CPU's lists).
struct GpuCullOptions {
    bool casts = true;   // false: nothing (the sun casts no shadow)
    bool cull = true;    // false: every caster into every cascade
    uint64_t frame = 0;  // tags the culling's statistics (GpuCasterCulling::culled)
};

class ShadowPass {
public:
    // `frame_set_layout` is set 0 of the caster pipelines (the frame's uniforms), and
    // `alpha_mask_set_layout` set 1. Multiview throws DeviceError without the multiview
    // feature, InputError for more cascades than the device renders views in one pass.
    // The layered strategy throws DeviceError without the GPU-driven features
    // (EnabledFeatures::gpu_driven). `cached`: also keep a cache of the static casters
    // (per-cascade and layered strategies). `frames_in_flight`: the layered strategy's
    // culling keeps replaced buffers that long.
    ShadowPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
               VkDescriptorSetLayout alpha_mask_set_layout, uint32_t resolution, uint32_t cascade_count,
               ShadowStrategy strategy, bool cached, uint32_t frames_in_flight = 2);

    const gpu::Image& shadow_map() const { return shadow_map_; }
    uint32_t cascade_count() const { return cascade_count_; }
    bool cached() const { return cache_ != nullptr; }
    uint64_t memory_bytes() const { return shadow_map_.memory_size + (cache_ ? cache_->memory_size : 0u); }
    void prepare_pipelines(const VertexFormats& formats) { pipelines_.prepare(formats); }

    // Records the depth rendering of every cascade and leaves the shadow map in
    // ImageState::ShaderSampled. draws[c] is cascade c's; a reuse needs cached() and the
    // previous frame's map and cache, recorded earlier on the same queue. With a timer,
    // each cascade's rendering is a scope "shadow_cascade_<c>" (multiview: one,
    // "shadow_multiview"; layered: "shadow_cull" and "shadow_layered"), and the cache's
    // copies and dynamic casters "shadow_cache_restore", "shadow_cache_store" and
    // "shadow_dynamic". The layered strategy ignores `draws`' caster lists: the GPU culls
    // every caster into the regions' tiles, as `gpu_culling` says.
    void record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                const std::vector<CascadeDraws>& draws, const BiasSettings& bias, const CasterFaceCulling& culling,
                gpu::GpuTimer* timer = nullptr, GpuCullOptions gpu_culling = {});

    // The layered strategy's culling (nullptr for the others).
    const GpuCasterCulling* gpu_culling() const { return gpu_culling_.get(); }

private:
    void begin_rendering(VkCommandBuffer cmd, VkImageView view, uint32_t view_mask, const BiasSettings& bias,
                         VkAttachmentLoadOp load, uint32_t layers = 1) const;
    void record_multiview(VkCommandBuffer cmd, const CasterScene& scene, const std::vector<CascadeDraws>& draws,
                          const BiasSettings& bias, const CasterFaceCulling& culling, gpu::GpuTimer* timer) const;
    void record_gpu_culling(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                            const std::vector<CascadeDraws>& draws, gpu::GpuTimer* timer, GpuCullOptions options);
    void record_layered_static(VkCommandBuffer cmd, const CasterScene& scene, const std::vector<CascadeDraws>& draws,
                               const BiasSettings& bias, const CasterFaceCulling& culling, gpu::GpuTimer* timer) const;
    void record_layered_dynamic(VkCommandBuffer cmd, const CasterScene& scene, const std::vector<CascadeDraws>& draws,
                                const BiasSettings& bias, const CasterFaceCulling& culling, gpu::GpuTimer* timer) const;
    void record_regions(VkCommandBuffer cmd, const CasterScene& scene, const std::vector<CascadeDraws::Region>& regions,
                        uint32_t cascade, bool clear, const CasterFaceCulling& culling) const;
    void record_static(VkCommandBuffer cmd, const CasterScene& scene, const std::vector<CascadeDraws>& draws,
                       const BiasSettings& bias, const CasterFaceCulling& culling, gpu::GpuTimer* timer) const;
    void copy_cache(VkCommandBuffer cmd, const std::vector<CascadeDraws>& draws, bool restore);
    void record_dynamic(VkCommandBuffer cmd, const CasterScene& scene, const std::vector<CascadeDraws>& draws,
                        const BiasSettings& bias, const CasterFaceCulling& culling, gpu::GpuTimer* timer) const;

    const gpu::Device& device_;
    uint32_t resolution_;
    uint32_t cascade_count_;
    ShadowStrategy strategy_;
    gpu::Image shadow_map_;
    std::unique_ptr<gpu::Image> cache_;  // the static casters of each cascade (cached only)
    gpu::ImageState cache_state_ = gpu::ImageState::Undefined;
    std::unique_ptr<GpuCasterCulling> gpu_culling_;  // layered strategy only
    gpu::UniquePipelineLayout pipeline_layout_;
    CasterPipelines pipelines_;
};

}  // namespace penumbra::passes

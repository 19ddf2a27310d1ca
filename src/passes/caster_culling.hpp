#pragma once
// GPU-driven caster culling for the layered strategy: the caster draws, grouped into
// buckets of one pipeline state (CasterBucket), live in device buffers uploaded when the
// scene changes; each frame a compute pass (shaders/caster_cull.comp) tests every draw
// against every layer (the sun's cascades, or the spot and point lights' layers), as the
// CPU's culling does, and writes indexed indirect commands and counts per layer and
// bucket; the passes then draw each layer's buckets with one vkCmdDrawIndexedIndirectCount
// each (the cascades in one layered pass, the vertex shader sending each command to its
// layer). The CPU records a few draws per layer however many casters the scene has.
// Commands take room for every draw in every layer (28 bytes each).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/shadow_cache.hpp"
#include "passes/casters.hpp"
#include "passes/shader_interface.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"

namespace penumbra::passes {

// What one layer's culling selected, counted on the GPU.
struct CulledLayer {
    uint32_t draws = 0;
    uint64_t triangles = 0;
};

// What the GPU's culling wrote, read back (tests compare it with the CPU's culling).
struct CulledDraws {
    // Per layer, the CasterScene::draws indices the GPU selected, sorted.
    std::vector<std::vector<uint32_t>> draws_per_layer;
};

class GpuCasterCulling;

// The layered strategy's culling when `wanted` (DeviceError naming the features GPU-driven
// culling needs when `device` lacks one), else nullptr. `frame_set_layout` and
// `frames_in_flight` as GpuCasterCulling's.
std::unique_ptr<GpuCasterCulling> create_gpu_culling(const gpu::Device& device, bool wanted,
                                                     VkDescriptorSetLayout frame_set_layout, uint32_t frames_in_flight);

// The pipeline layout of the caster passes: set 0 the frame's uniforms, set 1 the alpha
// mask and, with `gpu_culling`, set 2 its culled draws; the caster push constants.
gpu::UniquePipelineLayout create_caster_pipeline_layout(const gpu::Device& device,
                                                        VkDescriptorSetLayout frame_set_layout,
                                                        VkDescriptorSetLayout alpha_mask_set_layout,
                                                        const GpuCasterCulling* gpu_culling);

// What one culled draw is: a caster instance, or one cluster of its mesh (CasterMesh::clusters;
// the virtual shadow map draws each cluster only into the pages under it).
enum class CullUnit { Instances, Clusters };

// The culled draws of `scene` by `unit`: GpuCasterCulling::draw_count() once it uploaded `scene`.
uint32_t cull_unit_total(const CasterScene& scene, CullUnit unit);

// Throws InputError when `draws` casters in `layers` layers need more indirect commands than
// the GPU culling makes room for (2^26, or what one storage buffer of the device holds),
// DeviceError when the draws do not fit one storage buffer or one indirect draw
// (maxStorageBufferRange, maxDrawIndirectCount); the messages name who culls (`unit`).
// ShadowSystem::prepare() checks the layered strategy before anything is recorded.
void check_gpu_culling_room(const gpu::Device& device, size_t draws, uint32_t layers,
                            CullUnit unit = CullUnit::Instances);

// What a culling dispatch tests the draws against.
enum class CullLayers : uint32_t {
    // Layer 4 c + t: tile t of cascade c of PenumbraShadowUniforms::cascades (CascadeTiles)
    CascadeTiles = PENUMBRA_CULL_CASCADE_TILES,
    LocalLayers = PENUMBRA_CULL_LOCAL_LAYERS  // PenumbraLocalShadows' lights and layers
};

// One tile of a toroidal cascade (core/shadow_cache.hpp layer_pieces) as the culling sees
// it, in window texels: a static caster goes into it when its footprint (caster_footprint)
// meets one of `rects`, a dynamic one when it meets `piece`.
struct CullTileRects {
    TexelRect piece;               // the tile's part of the window (empty: none)
    std::vector<TexelRect> rects;  // where the tile's static casters are drawn this frame
};

// The cascades' tiles a CullLayers::CascadeTiles dispatch culls into: 4 per cascade, at most
// PENUMBRA_MAX_CULL_RECTS rectangles in all.
struct CascadeTiles {
    uint32_t resolution = 0;  // the cascades' texels per side
    std::vector<CullTileRects> tiles;
};

// Which of a layer's buckets a draw records (the cascades' cache draws the static casters,
// then the dynamic ones over them).
enum class BucketKind { All, Static, Dynamic };

class GpuCasterCulling {
public:
    // `frame_set_layout` is set 0 of the culling dispatch (the shadow uniforms and the local
    // shadows); `frames_in_flight`: how many frames may run at once (replaced buffers live
    // that long).
    GpuCasterCulling(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout, uint32_t frames_in_flight,
                     CullUnit unit = CullUnit::Instances);

    // Set PENUMBRA_SET_CASTER_DRAWS of the layered caster pipelines (and of the dispatch).
    VkDescriptorSetLayout draws_set_layout() const { return draws_set_layout_; }

    // Uploads `scene`'s draws when its version or the layer count changed (throws as
    // check_gpu_culling_room()), then records the culling of every draw against the layers
    // `enabled` lists (layers [0, enabled.size()); every draw into every enabled layer when
    // `cull` is off), and makes the commands ready for the indirect draws. `frame` tags the
    // layers' statistics, which are copied to the host (culled()). CullLayers::CascadeTiles
    // needs `tiles` (one per layer).
    void record_cull(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene, CullLayers layers,
                     const std::vector<bool>& enabled, bool cull, uint64_t frame = 0,
                     const CascadeTiles* tiles = nullptr);

    // For another culling dispatch that writes the same commands (the virtual shadow map's
    // pages, layer = clipmap level): uploads `scene` as record_cull() does and clears the
    // counts; false when there is nothing to draw (no bucket or no layer). Then bind
    // draws_set() at the dispatch's set, dispatch, and call finish_commands(): the commands
    // ready for the indirect draws and every compute write visible to copies, the layers'
    // statistics copied for culled(frame) (the caller records gpu::transfer_to_host_barrier()
    // after its own copies).
    bool begin_commands(VkCommandBuffer cmd, const CasterScene& scene, uint32_t layer_count);
    void finish_commands(VkCommandBuffer cmd, uint64_t frame);
    VkDescriptorSet draws_set() const { return buffers_ ? buffers_->set : VK_NULL_HANDLE; }
    uint32_t draw_count() const { return draw_count_; }  // culled draws: instances or clusters

    // Per layer, the draws and triangles the culling recorded for `frame` selected; nullopt
    // once a later frame's culling reused its slot (after frames in flight + 1 frames), or
    // when none was recorded for it. Read only after that frame's commands completed.
    std::optional<std::vector<CulledLayer>> culled(uint64_t frame) const;

    // Records layer `layer`'s culled draws into the current rendering: one indirect draw per
    // bucket. `pipelines` were made with PENUMBRA_GPU_DRIVEN vertex shaders and a layout whose
    // set PENUMBRA_SET_CASTER_DRAWS is draws_set_layout().
    void record_draws(VkCommandBuffer cmd, const CasterPipelines& pipelines, const CasterScene& scene,
                      const CasterFaceCulling& culling, uint32_t layer, BucketKind kind = BucketKind::All) const;
    // The same for a culling that keeps a bucket's commands of every layer together (from
    // the bucket's first command times the layer count on) with one count per bucket: one
    // indirect draw per bucket draws every layer's (the virtual shadow map's levels, whose
    // vertex shader finds its page per instance).
    void record_draws_of_every_layer(VkCommandBuffer cmd, const CasterPipelines& pipelines, const CasterScene& scene,
                                     const CasterFaceCulling& culling) const;

    const std::vector<CasterBucket>& buckets() const { return buckets_; }
    // The device and staging buffers it holds now (replaced ones still in flight left out).
    uint64_t buffer_bytes() const;

    // Copies what the last recorded culling wrote to the host (a one-time submission after
    // the frame's commands completed; tests).
    CulledDraws read_back(const gpu::OneTimeCommands& commands) const;

private:
    // The device buffers, sized for a number of draws and commands; replaced (not resized)
    // when the scene outgrows them, since frames in flight may still read the old ones.
    struct Buffers {
        gpu::Buffer instances;  // CullInstance per draw
        gpu::Buffer buckets;    // first command per bucket
        gpu::Buffer records;    // CullRecord per command
        gpu::Buffer commands;   // VkDrawIndexedIndirectCommand per command
        gpu::Buffer counts;     // per layer and bucket, then two statistics per layer
        gpu::UniqueDescriptorPool pool;
        VkDescriptorSet set = VK_NULL_HANDLE;
        uint32_t draw_capacity = 0;
        uint32_t command_capacity = 0;
        uint32_t count_capacity = 0;  // layers x buckets
    };

    void upload(VkCommandBuffer cmd, const CasterScene& scene, uint32_t layer_count);
    bool begin_commands(VkCommandBuffer cmd, const CasterScene& scene, uint32_t layer_count, const CascadeTiles* tiles);
    void write_tiles(VkCommandBuffer cmd, const CascadeTiles& tiles, uint32_t layer_count) const;
    void ensure_capacity(uint32_t draws, uint32_t commands, uint32_t counts);

    const gpu::Device& device_;
    uint32_t frames_in_flight_;
    CullUnit unit_;
    gpu::UniqueDescriptorSetLayout draws_set_layout_;
    gpu::UniquePipelineLayout layout_;
    gpu::UniquePipeline pipeline_;
    std::unique_ptr<Buffers> buffers_;
    // CullTiles (PENUMBRA_BINDING_CULL_TILES): written by each cascade culling before it runs.
    gpu::Buffer tiles_;
    // Replaced buffers, with the number of record_cull() calls after which they are unused.
    std::vector<std::pair<uint64_t, std::unique_ptr<Buffers>>> replaced_;
    std::vector<gpu::Buffer> staging_;  // one per frame in flight
    // The layers' statistics copied for the host, one slot per frame in flight and one more
    // (a frame's slot stays until the frames in flight after it have been prepared).
    struct Statistics {
        gpu::Buffer buffer;
        uint64_t frame = ~uint64_t{0};
        uint32_t layers = 0;
    };
    std::vector<Statistics> statistics_;
    uint64_t records_ = 0;               // record_cull() calls so far
    std::vector<CasterBucket> buckets_;  // static ones first
    uint32_t first_dynamic_bucket_ = 0;
    uint32_t draw_count_ = 0;
    size_t uploaded_draws_ = 0;  // the scene's draws when it was uploaded
    uint32_t layer_count_ = 0;
    uint64_t uploaded_version_ = ~uint64_t{0};
};

}  // namespace penumbra::passes

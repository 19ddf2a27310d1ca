#pragma once
// What every caster pass draws, and how: the meshes (vertex streams in buffers the caller
// or the library owns, any supported vertex format), the draws (a mesh placed in the
// world, with its flags), the pipelines of one pass for each vertex format in use, and the
// recording of a draw list into one layer. The passes (cascades, moments, spot/point
// lights) differ only in their target and shaders.
#include <vulkan/vulkan.h>

#include <compare>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "core/glm_config.hpp"
#include "core/mesh_clusters.hpp"
#include "core/shadow_inputs.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

// One vertex stream: `format` at `offset`, every `stride` bytes.
struct VertexStream {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    uint32_t stride = 0;
    VkFormat format = VK_FORMAT_UNDEFINED;
    auto operator<=>(const VertexStream&) const = default;
};

struct CasterMesh {
    VertexStream positions;
    VertexStream uvs;  // buffer VK_NULL_HANDLE: the mesh has no alpha mask
    VkBuffer index_buffer = VK_NULL_HANDLE;
    VkDeviceSize index_offset = 0;
    VkIndexType index_type = VK_INDEX_TYPE_UINT32;
    uint32_t index_count = 0;
    int32_t vertex_offset = 0;
    VkDescriptorSet alpha_mask_set = VK_NULL_HANDLE;  // set PENUMBRA_SET_ALPHA_MASK of masked draws
    float alpha_cutoff = 0.5f;
    float alpha_scale = 1.0f;
    // Runs of its triangles with their own bounds (index_count's whole list, in order;
    // first_index relative to the mesh's first index); empty: the mesh is one cluster.
    std::vector<core::MeshCluster> clusters;
};

struct CasterDraw {
    uint32_t mesh = 0;  // index into CasterScene::meshes
    glm::mat4 model{1.0f};
    core::Aabb world_bounds;
    bool masked = false;        // alpha-tested with its mesh's mask
    bool double_sided = false;  // never face-culled
    bool mirrored = false;      // the model matrix flips the winding (negative determinant)
    bool dynamic = false;       // drawn every frame over cached static casters (kInstanceDynamic)
};

struct CasterScene {
    std::vector<CasterMesh> meshes;
    std::vector<CasterDraw> draws;
    // The indices of the dynamic draws, in order (library::Geometry lists them with the
    // draws): what a frame does for the dynamic casters visits only these.
    std::vector<uint32_t> dynamic_draws;
    // Changes whenever meshes or draws change (GPU culling uploads the draws again).
    uint64_t version = 0;
};

// Indices into CasterScene::draws to render into one layer.
using DrawList = std::vector<uint32_t>;

// The vertex formats a pipeline is built for (uv: VK_FORMAT_UNDEFINED for opaque casters).
struct VertexFormats {
    VkFormat position = VK_FORMAT_UNDEFINED;
    VkFormat uv = VK_FORMAT_UNDEFINED;
    auto operator<=>(const VertexFormats&) const = default;
};

VertexFormats vertex_formats(const CasterMesh& mesh, bool masked);

// How one caster pass's pipelines are made; the vertex formats vary.
struct CasterPipelineTemplate {
    std::span<const uint32_t> opaque_vertex;
    std::span<const uint32_t> masked_vertex;
    std::span<const uint32_t> opaque_fragment;  // empty: depth only
    std::span<const uint32_t> masked_fragment;
    std::vector<gpu::SpecializationValue> fragment_specialization;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    std::vector<VkFormat> color_formats;
    VkFormat depth_format = VK_FORMAT_D32_SFLOAT;
    bool depth_bias = false;
    bool depth_clamp = false;
    uint32_t view_mask = 0;
    uint32_t viewport_count = 1;
};

// The pipelines of one pass, one per vertex format combination, created on first use
// (ShadowSystem asks for a mesh's formats when the mesh is added, not while recording).
class CasterPipelines {
public:
    CasterPipelines(const gpu::Device& device, CasterPipelineTemplate pipeline_template);

    void prepare(const VertexFormats& formats);
    VkPipeline get(const VertexFormats& formats) const;
    VkPipelineLayout layout() const { return template_.layout; }

private:
    const gpu::Device& device_;
    CasterPipelineTemplate template_;
    std::map<VertexFormats, gpu::UniquePipeline> pipelines_;
};

// The culling of casters' faces seen from the light (Settings::shadow.caster_culling).
struct CasterFaceCulling {
    CasterCulling mode = CasterCulling::None;
    // The winding of a triangle that faces the light, for a draw without mirroring, in this
    // pass's clip space (front_face_toward_light()).
    VkFrontFace facing_light = VK_FRONT_FACE_COUNTER_CLOCKWISE;
};

// Records `list` into the current rendering: per draw its pipeline, vertex and index
// buffers, alpha mask, culling and push constants (`layer`: the cascade or the local
// layer the vertex shader projects with; `tile`: a toroidal cascade's tile,
// CasterPushConstants::tile). Opaque draws first, then masked ones.
void record_caster_draws(const gpu::Device& device, VkCommandBuffer cmd, const CasterPipelines& pipelines,
                         const CasterScene& scene, const DrawList& list, uint32_t layer,
                         const CasterFaceCulling& culling, uint32_t tile = 0);

// A group of draws that share their pipeline, vertex and index buffers, alpha mask, face
// culling and winding (they differ in transform, first index and vertex offset): the
// layered strategy draws each bucket with one indirect draw whose commands the GPU's
// culling wrote (caster_culling.hpp).
struct CasterBucket {
    uint32_t draw = 0;           // a draw of the bucket (index into CasterScene::draws): its state
    uint32_t first_command = 0;  // where its commands start within a layer's commands
    uint32_t capacity = 0;       // room for that many commands per layer (its draws)
};

// Records one vkCmdDrawIndexedIndirectCount per bucket: `commands` holds
// VkDrawIndexedIndirectCommands, a bucket's from `first_command` plus its own first times
// `layers_per_bucket` (room for its capacity that many times: the commands of several
// layers kept together), and `counts` one uint32_t count per bucket from `first_count`.
void record_indirect_caster_draws(const gpu::Device& device, VkCommandBuffer cmd, const CasterPipelines& pipelines,
                                  const CasterScene& scene, std::span<const CasterBucket> buckets, VkBuffer commands,
                                  uint32_t first_command, VkBuffer counts, uint32_t first_count,
                                  const CasterFaceCulling& culling, uint32_t layers_per_bucket = 1);

void set_viewport_and_scissor(const gpu::Device& device, VkCommandBuffer cmd, uint32_t width, uint32_t height);

// The layered D32 reverse-Z depth map of the caster passes (depth attachment, sampled,
// copied out by debug views), with `extra_usage` (a cached map is also copied into).
gpu::Image create_depth_map(const gpu::Device& device, uint32_t resolution, uint32_t layers,
                            VkImageUsageFlags extra_usage = 0);

// The depth bias a shadow pass gives its casters, as the filters read it (the
// receiver-plane bias adds only what this one does not cover): the slope factor and the
// largest bias in reverse-Z depth, FLT_MAX where the bias is unclamped (the device lacks
// depthBiasClamp, or the clamp is 0, which Vulkan reads as no clamp).
struct CasterDepthBias {
    float slope = 0.0f;
    float clamp = 0.0f;
};
CasterDepthBias caster_depth_bias(const gpu::Device& device, const penumbra::BiasSettings& bias);

// Sets the depth bias of a reverse-Z shadow pass.
void set_shadow_depth_bias(const gpu::Device& device, VkCommandBuffer cmd, const penumbra::BiasSettings& bias);

// The set layout of PENUMBRA_SET_ALPHA_MASK: one combined image sampler for fragment shaders.
gpu::UniqueDescriptorSetLayout create_alpha_mask_set_layout(const gpu::Device& device);

VkPushConstantRange caster_push_constant_range();

}  // namespace penumbra::passes

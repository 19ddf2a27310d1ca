#include "passes/caster_culling.hpp"

#include <algorithm>
#include <array>
#include <compare>
#include <cstring>
#include <limits>
#include <map>
#include <span>
#include <string>

#include "passes/shader_interface.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra/gpu/debug_names.hpp"
#include "penumbra/gpu/one_time_commands.hpp"
#include "penumbra_shaders.hpp"

namespace penumbra::passes {
namespace {

constexpr uint32_t kWorkgroupSize = 64;  // caster_cull.comp's local_size_x
// The draws set's storage buffers: instances, bucket firsts, records, commands, counts, tiles.
constexpr uint32_t kCullBindings[] = {PENUMBRA_BINDING_CULL_INSTANCES, PENUMBRA_BINDING_CULL_BUCKETS,
                                      PENUMBRA_BINDING_CULL_RECORDS,   PENUMBRA_BINDING_CULL_COMMANDS,
                                      PENUMBRA_BINDING_CULL_COUNTS,    PENUMBRA_BINDING_CULL_TILES};
// CullTiles: the tiles, then the rectangles.
constexpr VkDeviceSize kTileBytes = sizeof(shader::CullTile) * PENUMBRA_MAX_CULL_TILES;
constexpr VkDeviceSize kTilesBufferBytes = kTileBytes + sizeof(glm::ivec4) * PENUMBRA_MAX_CULL_RECTS;
static_assert(kTilesBufferBytes <= 65536, "written with vkCmdUpdateBuffer");
// The most commands (every casting instance in every layer) the culled draws take room for:
// 1.9 GB of commands and records, and within the shader's 32-bit command indices; less
// where the device's storage buffers are smaller (maxStorageBufferRange: 128 MiB on lavapipe).
constexpr uint64_t kMaxCommands = uint64_t{1} << 26;

// Layers one dispatch culls at most: CullPushConstants::layer_mask's bits.
constexpr uint32_t kMaxCulledLayers = 8 * sizeof(shader::CullPushConstants::layer_mask);

uint64_t max_commands(const gpu::Device& device) {
    const uint64_t range = device.properties().limits.maxStorageBufferRange;
    return std::min<uint64_t>(kMaxCommands, range / sizeof(VkDrawIndexedIndirectCommand));
}

uint64_t max_draws(const gpu::Device& device) {
    return device.properties().limits.maxStorageBufferRange / sizeof(shader::CullInstance);
}

// What draws of one bucket share (record_indirect_caster_draws binds it once). Static
// buckets sort first (a cached cascade draws them before the dynamic ones), then opaque
// ones, as the per-draw recording orders them.
struct BucketKey {
    bool dynamic = false;
    bool masked = false;
    VertexStream positions;
    VertexStream uvs;  // masked only
    VkBuffer index_buffer = VK_NULL_HANDLE;
    VkIndexType index_type = VK_INDEX_TYPE_UINT32;
    VkDescriptorSet alpha_mask = VK_NULL_HANDLE;
    float alpha_cutoff = 0.0f;
    float alpha_scale = 0.0f;
    bool double_sided = false;
    bool mirrored = false;
    auto operator<=>(const BucketKey&) const = default;
};

// `split_dynamic`: dynamic draws get buckets of their own (the cascades' cache draws them
// after the static ones; the virtual shadow map draws both in the same pages at once).
BucketKey bucket_key(const CasterScene& scene, const CasterDraw& draw, bool split_dynamic) {
    const CasterMesh& mesh = scene.meshes[draw.mesh];
    BucketKey key;
    key.dynamic = split_dynamic && draw.dynamic;
    key.masked = draw.masked;
    key.positions = mesh.positions;
    if (draw.masked) {
        key.uvs = mesh.uvs;
        key.alpha_mask = mesh.alpha_mask_set;
        key.alpha_cutoff = mesh.alpha_cutoff;
        key.alpha_scale = mesh.alpha_scale;
    }
    key.index_buffer = mesh.index_buffer;
    key.index_type = mesh.index_type;
    key.double_sided = draw.double_sided;
    key.mirrored = draw.mirrored;
    return key;
}

shader::CullInstance cull_instance(const CasterScene& scene, const CasterDraw& draw, uint32_t bucket) {
    const CasterMesh& mesh = scene.meshes[draw.mesh];
    const VkDeviceSize index_size = mesh.index_type == VK_INDEX_TYPE_UINT16 ? 2 : 4;
    shader::CullInstance instance{};
    instance.model = draw.model;
    instance.bounds_min = glm::vec4(draw.world_bounds.min, 0.0f);
    instance.bounds_max = glm::vec4(draw.world_bounds.max, 0.0f);
    instance.bucket = bucket;
    instance.index_count = mesh.index_count;
    instance.first_index = static_cast<uint32_t>(mesh.index_offset / index_size);
    instance.vertex_offset = mesh.vertex_offset;
    return instance;
}

// How many culled draws an instance of `mesh` is: one, or one per cluster of it.
uint32_t cull_unit_count(const CasterMesh& mesh, CullUnit unit) {
    const bool split = unit == CullUnit::Clusters && mesh.clusters.size() >= 2;
    return split ? static_cast<uint32_t>(mesh.clusters.size()) : 1u;
}

}  // namespace

uint32_t cull_unit_total(const CasterScene& scene, CullUnit unit) {
    uint64_t total = 0;
    for (const CasterDraw& draw : scene.draws) total += cull_unit_count(scene.meshes[draw.mesh], unit);
    return static_cast<uint32_t>(std::min<uint64_t>(total, std::numeric_limits<uint32_t>::max()));
}

namespace {

// Appends the culled draws of `draw` (cull_unit_count() of them): the instance, or one per
// cluster of its mesh (its index range, and its bounds in the world, within the instance's).
void append_cull_units(std::vector<shader::CullInstance>& units, const CasterScene& scene, const CasterDraw& draw,
                       uint32_t bucket, CullUnit unit) {
    const shader::CullInstance whole = cull_instance(scene, draw, bucket);
    const CasterMesh& mesh = scene.meshes[draw.mesh];
    if (cull_unit_count(mesh, unit) == 1) {
        units.push_back(whole);
        return;
    }
    for (const core::MeshCluster& cluster : mesh.clusters) {
        shader::CullInstance part = whole;
        const core::Aabb bounds = core::transform_aabb(cluster.bounds, draw.model);
        part.bounds_min = glm::vec4(glm::max(bounds.min, draw.world_bounds.min), 0.0f);
        part.bounds_max = glm::vec4(glm::min(bounds.max, draw.world_bounds.max), 0.0f);
        part.first_index = whole.first_index + cluster.first_index;
        part.index_count = cluster.index_count;
        units.push_back(part);
    }
}

gpu::UniqueDescriptorSetLayout create_draws_set_layout(const gpu::Device& device) {
    constexpr VkShaderStageFlags kStages = VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT;
    std::array<VkDescriptorSetLayoutBinding, std::size(kCullBindings)> bindings{};
    for (size_t i = 0; i < bindings.size(); ++i) {
        bindings[i] = {kCullBindings[i], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kStages, nullptr};
    }
    return gpu::create_descriptor_set_layout(device, bindings);
}

gpu::UniquePipelineLayout create_cull_layout(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                                             VkDescriptorSetLayout draws_set_layout) {
    static_assert(PENUMBRA_SET_CASTER_FRAME == 0 && PENUMBRA_SET_CULL_DRAWS == 1);
    const VkDescriptorSetLayout sets[] = {frame_set_layout, draws_set_layout};
    const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(shader::CullPushConstants)};
    return gpu::create_pipeline_layout(device, sets, {&push, 1});
}

void write(void* destination, size_t offset, const void* source, size_t bytes) {
    std::memcpy(static_cast<std::byte*>(destination) + offset, source, bytes);
}

}  // namespace

std::unique_ptr<GpuCasterCulling> create_gpu_culling(const gpu::Device& device, bool wanted,
                                                     VkDescriptorSetLayout frame_set_layout,
                                                     uint32_t frames_in_flight) {
    if (!wanted) return nullptr;
    if (!device.features().gpu_driven) {
        throw DeviceError(
            "shadow strategy layered: the device was not created with the features GPU-driven culling needs "
            "(VkPhysicalDeviceFeatures::multiDrawIndirect and drawIndirectFirstInstance, "
            "VkPhysicalDeviceVulkan12Features::drawIndirectCount and shaderOutputLayer)");
    }
    return std::make_unique<GpuCasterCulling>(device, frame_set_layout, frames_in_flight);
}

gpu::UniquePipelineLayout create_caster_pipeline_layout(const gpu::Device& device,
                                                        VkDescriptorSetLayout frame_set_layout,
                                                        VkDescriptorSetLayout alpha_mask_set_layout,
                                                        const GpuCasterCulling* gpu_culling) {
    static_assert(PENUMBRA_SET_CASTER_FRAME == 0 && PENUMBRA_SET_ALPHA_MASK == 1 && PENUMBRA_SET_CASTER_DRAWS == 2);
    std::vector<VkDescriptorSetLayout> set_layouts{frame_set_layout, alpha_mask_set_layout};
    if (gpu_culling) set_layouts.push_back(gpu_culling->draws_set_layout());
    const VkPushConstantRange push_range = caster_push_constant_range();
    return gpu::create_pipeline_layout(device, set_layouts, {&push_range, 1});
}

void check_gpu_culling_room(const gpu::Device& device, size_t draws, uint32_t layers, CullUnit unit) {
    // Who culls, what it culls, and what to do instead, for the messages.
    const bool clusters = unit == CullUnit::Clusters;
    const std::string who = clusters ? "virtual shadow map: " : "shadow strategy layered: ";
    const std::string what = clusters ? " caster clusters" : " casting instances";
    const std::string layer_name = clusters ? " levels" : " layers";
    const std::string instead = clusters ? "; use the cascades" : "; use the per-cascade strategy";
    const uint64_t commands = uint64_t{draws} * layers;
    if (commands > max_commands(device)) {
        throw InputError(who + std::to_string(draws) + what + " in " + std::to_string(layers) + layer_name + " need " +
                         std::to_string(commands) + " indirect commands, more than the " +
                         std::to_string(max_commands(device)) + " the GPU culling makes room for on this device" +
                         instead);
    }
    if (draws > max_draws(device)) {
        throw DeviceError(who + std::to_string(draws) + what +
                          " do not fit one storage buffer of this device (maxStorageBufferRange " +
                          std::to_string(device.properties().limits.maxStorageBufferRange) + ")" + instead);
    }
    // A bucket holds at most every draw (the virtual shadow map's: in every level at once):
    // one indirect draw must be able to draw them all.
    const uint32_t limit = device.properties().limits.maxDrawIndirectCount;
    const uint64_t per_indirect_draw = clusters ? commands : draws;
    if (per_indirect_draw > limit) {
        throw DeviceError(who + std::to_string(per_indirect_draw) + (clusters ? " cluster draws" : what) +
                          ", more than the device draws in one indirect draw (maxDrawIndirectCount " +
                          std::to_string(limit) + ")" + instead);
    }
}

GpuCasterCulling::GpuCasterCulling(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                                   uint32_t frames_in_flight, CullUnit unit)
    : device_(device),
      frames_in_flight_(std::max(frames_in_flight, 1u)),
      unit_(unit),
      draws_set_layout_(create_draws_set_layout(device)),
      layout_(create_cull_layout(device, frame_set_layout, draws_set_layout_)),
      pipeline_(gpu::create_compute_pipeline(device, {VK_SHADER_STAGE_COMPUTE_BIT, shaders::caster_cull_comp(), {}},
                                             layout_)),
      tiles_(gpu::create_buffer(device, kTilesBufferBytes,
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                gpu::MemoryKind::DeviceLocal)),
      staging_(frames_in_flight_),
      statistics_(frames_in_flight_ + 1) {}

void GpuCasterCulling::ensure_capacity(uint32_t draws, uint32_t commands, uint32_t counts) {
    const gpu::ObjectNames names(device_, "caster culling");
    if (buffers_ && buffers_->draw_capacity >= draws && buffers_->command_capacity >= commands &&
        buffers_->count_capacity >= counts) {
        return;
    }
    // Frames in flight may still read the old buffers: kept until they are complete.
    if (buffers_) replaced_.emplace_back(records_ + frames_in_flight_, std::move(buffers_));
    auto buffers = std::make_unique<Buffers>();
    // Grown with headroom (within what one storage buffer holds) so that a scene that keeps
    // growing does not replace them each frame.
    const auto grown = [](uint32_t needed, uint64_t most) {
        return static_cast<uint32_t>(std::min<uint64_t>(std::max<uint64_t>(uint64_t{needed} * 3 / 2, 64u), most));
    };
    buffers->draw_capacity = grown(draws, max_draws(device_));
    buffers->command_capacity = grown(commands, max_commands(device_));
    buffers->count_capacity = std::max(counts + counts / 2, 16u);
    constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    constexpr VkBufferUsageFlags kCopied = VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    const auto create = [&](VkDeviceSize size, VkBufferUsageFlags usage) {
        return gpu::create_buffer(device_, size, kStorage | kCopied | usage, gpu::MemoryKind::DeviceLocal);
    };
    buffers->instances = create(VkDeviceSize{buffers->draw_capacity} * sizeof(shader::CullInstance), 0);
    // Buckets are at most their counts (one per bucket and layer).
    buffers->buckets = create(VkDeviceSize{buffers->count_capacity} * sizeof(uint32_t), 0);
    buffers->records = create(VkDeviceSize{buffers->command_capacity} * sizeof(shader::CullRecord), 0);
    buffers->commands = create(VkDeviceSize{buffers->command_capacity} * sizeof(VkDrawIndexedIndirectCommand),
                               VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    buffers->counts =
        // The counts, then two statistics per layer.
        create(VkDeviceSize{buffers->count_capacity + 2 * kMaxCulledLayers} * sizeof(uint32_t),
               VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, std::size(kCullBindings)};
    buffers->pool = gpu::create_descriptor_pool(device_, 1, {&size, 1});
    buffers->set = gpu::allocate_descriptor_set(device_, buffers->pool, draws_set_layout_);
    // In the order of kCullBindings.
    const gpu::Buffer* bound[] = {&buffers->instances, &buffers->buckets, &buffers->records,
                                  &buffers->commands,  &buffers->counts,  &tiles_};
    for (size_t i = 0; i < std::size(bound); ++i) {
        gpu::write_storage_buffer(device_, buffers->set, kCullBindings[i], bound[i]->get(), bound[i]->size);
    }
    buffers_ = std::move(buffers);
}

// Groups the draws into buckets (each with room for its draws in every layer) and copies
// them, through this frame's staging buffer, into the device buffers.
void GpuCasterCulling::upload(VkCommandBuffer cmd, const CasterScene& scene, uint32_t layer_count) {
    const gpu::ObjectNames names(device_, "caster culling");
    std::map<BucketKey, uint32_t> bucket_of;
    std::vector<uint32_t> draws_in_bucket;
    buckets_.clear();
    std::vector<uint32_t> draw_bucket(scene.draws.size());
    for (uint32_t d = 0; d < scene.draws.size(); ++d) {
        const auto [found, inserted] = bucket_of.try_emplace(
            bucket_key(scene, scene.draws[d], unit_ == CullUnit::Instances), static_cast<uint32_t>(bucket_of.size()));
        if (inserted) {
            buckets_.push_back({d, 0, 0});
            draws_in_bucket.push_back(0);
        }
        draw_bucket[d] = found->second;
        draws_in_bucket[found->second] += cull_unit_count(scene.meshes[scene.draws[d].mesh], unit_);
    }
    // Buckets in key order (opaque first), each with its commands after the previous one's
    // within a layer's commands (a layer has room for every draw).
    std::vector<CasterBucket> ordered;
    std::vector<uint32_t> new_index(buckets_.size());
    uint32_t first_command = 0;
    first_dynamic_bucket_ = static_cast<uint32_t>(bucket_of.size());
    for (const auto& [key, bucket] : bucket_of) {
        if (key.dynamic && first_dynamic_bucket_ == bucket_of.size())
            first_dynamic_bucket_ = static_cast<uint32_t>(ordered.size());
        new_index[bucket] = static_cast<uint32_t>(ordered.size());
        ordered.push_back({buckets_[bucket].draw, first_command, draws_in_bucket[bucket]});
        first_command += draws_in_bucket[bucket];
    }
    buckets_ = std::move(ordered);
    for (uint32_t& bucket : draw_bucket) bucket = new_index[bucket];

    std::vector<shader::CullInstance> units;
    units.reserve(scene.draws.size());
    for (uint32_t d = 0; d < scene.draws.size(); ++d) {
        append_cull_units(units, scene, scene.draws[d], draw_bucket[d], unit_);
    }
    const auto draws = static_cast<uint32_t>(units.size());
    const auto bucket_count = static_cast<uint32_t>(buckets_.size());
    check_gpu_culling_room(device_, draws, layer_count, unit_);
    ensure_capacity(draws, draws * layer_count, bucket_count * layer_count);
    const VkDeviceSize instance_bytes = VkDeviceSize{draws} * sizeof(shader::CullInstance);
    const VkDeviceSize bucket_bytes = VkDeviceSize{bucket_count} * sizeof(uint32_t);
    // The staging buffer of this frame in flight: the frame that used it last is complete.
    gpu::Buffer& staging = staging_[records_ % frames_in_flight_];
    if (staging.size < instance_bytes + bucket_bytes) {
        staging = gpu::create_buffer(device_, instance_bytes + bucket_bytes + instance_bytes / 2,
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryKind::HostUpload);
    }
    if (draws > 0) write(staging.mapped, 0, units.data(), instance_bytes);
    for (uint32_t b = 0; b < bucket_count; ++b) {
        write(staging.mapped, instance_bytes + b * sizeof(uint32_t), &buckets_[b].first_command, sizeof(uint32_t));
    }
    if (draws > 0) {
        const VkBufferCopy instances{0, 0, instance_bytes};
        const VkBufferCopy firsts{instance_bytes, 0, bucket_bytes};
        device_->vkCmdCopyBuffer(cmd, staging.get(), buffers_->instances.get(), 1, &instances);
        device_->vkCmdCopyBuffer(cmd, staging.get(), buffers_->buckets.get(), 1, &firsts);
    }
    draw_count_ = draws;
    uploaded_draws_ = scene.draws.size();
    layer_count_ = layer_count;
    uploaded_version_ = scene.version;
}

void GpuCasterCulling::record_cull(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                                   CullLayers layers, const std::vector<bool>& enabled, bool cull, uint64_t frame,
                                   const CascadeTiles* tiles) {
    const auto layer_count = static_cast<uint32_t>(enabled.size());
    if (layer_count > kMaxCulledLayers) {
        throw UsageError("GpuCasterCulling::record_cull: " + std::to_string(layer_count) + " layers, more than " +
                         std::to_string(kMaxCulledLayers));
    }
    const bool cascades = layers == CullLayers::CascadeTiles;
    if (cascades && (!tiles || tiles->tiles.size() != layer_count || layer_count > PENUMBRA_MAX_CULL_TILES)) {
        throw UsageError("GpuCasterCulling::record_cull: the cascades' culling needs a CullTileRects per layer, " +
                         std::to_string(layer_count) + " layers (at most " + std::to_string(PENUMBRA_MAX_CULL_TILES) +
                         ")");
    }
    if (!begin_commands(cmd, scene, layer_count, cascades ? tiles : nullptr)) return;
    const auto bucket_count = static_cast<uint32_t>(buckets_.size());
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    const VkDescriptorSet sets[] = {frame_set, buffers_->set};
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 2, sets, 0, nullptr);
    shader::CullPushConstants constants{};
    constants.instance_count = draw_count_;
    constants.layer_count = layer_count_;
    constants.cull = cull ? 1u : 0u;
    constants.mode = static_cast<uint32_t>(layers);
    constants.bucket_count = bucket_count;
    constants.first_dynamic_bucket = first_dynamic_bucket_;
    constants.resolution = cascades ? tiles->resolution : 0u;
    for (uint32_t layer = 0; layer < layer_count_; ++layer) {
        if (enabled[layer]) constants.layer_mask[layer / 128][static_cast<int>((layer / 32) % 4)] |= 1u << (layer % 32);
    }
    device_->vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
    device_->vkCmdDispatch(cmd, (draw_count_ + kWorkgroupSize - 1) / kWorkgroupSize, 1, 1);
    finish_commands(cmd, frame);
    gpu::transfer_to_host_barrier(device_, cmd);
}

bool GpuCasterCulling::begin_commands(VkCommandBuffer cmd, const CasterScene& scene, uint32_t layer_count) {
    return begin_commands(cmd, scene, layer_count, nullptr);
}

// Each tile's piece and the range of its rectangles, then every tile's rectangles in order.
void GpuCasterCulling::write_tiles(VkCommandBuffer cmd, const CascadeTiles& tiles, uint32_t layer_count) const {
    std::vector<shader::CullTile> headers(layer_count);
    std::vector<glm::ivec4> rects;
    const auto packed = [](const TexelRect& rect) { return glm::ivec4(rect.min, rect.max); };
    for (uint32_t layer = 0; layer < layer_count; ++layer) {
        const CullTileRects& tile = tiles.tiles[layer];
        headers[layer].piece = packed(tile.piece);
        headers[layer].rects = glm::uvec4(rects.size(), tile.rects.size(), 0u, 0u);
        for (const TexelRect& rect : tile.rects) rects.push_back(packed(rect));
    }
    if (rects.size() > PENUMBRA_MAX_CULL_RECTS) {
        throw UsageError("GpuCasterCulling::record_cull: " + std::to_string(rects.size()) +
                         " tile rectangles, more than " + std::to_string(PENUMBRA_MAX_CULL_RECTS));
    }
    if (!headers.empty()) {
        device_->vkCmdUpdateBuffer(cmd, tiles_.get(), 0, headers.size() * sizeof(shader::CullTile), headers.data());
    }
    if (!rects.empty()) {
        device_->vkCmdUpdateBuffer(cmd, tiles_.get(), kTileBytes, rects.size() * sizeof(glm::ivec4), rects.data());
    }
}

bool GpuCasterCulling::begin_commands(VkCommandBuffer cmd, const CasterScene& scene, uint32_t layer_count,
                                      const CascadeTiles* tiles) {
    if (layer_count > kMaxCulledLayers) {
        throw UsageError("GpuCasterCulling::begin_commands: " + std::to_string(layer_count) + " layers, more than " +
                         std::to_string(kMaxCulledLayers));
    }
    ++records_;
    std::erase_if(replaced_, [&](const auto& entry) { return entry.first <= records_; });
    // The previous frame's draws and dispatch read what this one overwrites.
    gpu::memory_barrier(device_, cmd,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                            VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,
                        VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    if (scene.version != uploaded_version_ || layer_count != layer_count_ || scene.draws.size() != uploaded_draws_) {
        upload(cmd, scene, layer_count);
    }
    const auto bucket_count = static_cast<uint32_t>(buckets_.size());
    if (bucket_count == 0 || layer_count_ == 0) return false;
    const VkDeviceSize statistics_offset = VkDeviceSize{bucket_count} * layer_count_ * sizeof(uint32_t);
    const VkDeviceSize statistics_bytes = VkDeviceSize{2} * layer_count_ * sizeof(uint32_t);
    device_->vkCmdFillBuffer(cmd, buffers_->counts.get(), 0, statistics_offset + statistics_bytes, 0);
    if (tiles) write_tiles(cmd, *tiles, layer_count_);
    gpu::memory_barrier(device_, cmd, VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT,
                        VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    return true;
}

void GpuCasterCulling::finish_commands(VkCommandBuffer cmd, uint64_t frame) {
    const gpu::ObjectNames names(device_, "caster culling");
    const auto bucket_count = static_cast<uint32_t>(buckets_.size());
    const VkDeviceSize statistics_offset = VkDeviceSize{bucket_count} * layer_count_ * sizeof(uint32_t);
    const VkDeviceSize statistics_bytes = VkDeviceSize{2} * layer_count_ * sizeof(uint32_t);
    gpu::memory_barrier(
        device_, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
        VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
    // The statistics for the host: this frame's slot was last used frames in flight + 1
    // frames ago, complete since.
    Statistics& slot = statistics_[frame % statistics_.size()];
    if (!slot.buffer.mapped) {
        slot.buffer = gpu::create_buffer(device_, VkDeviceSize{2} * kMaxCulledLayers * sizeof(uint32_t),
                                         VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryKind::HostReadback);
    }
    const VkBufferCopy region{statistics_offset, 0, statistics_bytes};
    device_->vkCmdCopyBuffer(cmd, buffers_->counts.get(), slot.buffer.get(), 1, &region);
    slot.frame = frame;
    slot.layers = layer_count_;
}

std::optional<std::vector<CulledLayer>> GpuCasterCulling::culled(uint64_t frame) const {
    const Statistics& slot = statistics_[frame % statistics_.size()];
    if (slot.frame != frame || !slot.buffer.mapped) return std::nullopt;
    std::vector<uint32_t> values(size_t{2} * slot.layers);
    std::memcpy(values.data(), slot.buffer.mapped, values.size() * sizeof(uint32_t));
    std::vector<CulledLayer> layers(slot.layers);
    for (uint32_t layer = 0; layer < slot.layers; ++layer) layers[layer] = {values[2 * layer], values[2 * layer + 1]};
    return layers;
}

void GpuCasterCulling::record_draws(VkCommandBuffer cmd, const CasterPipelines& pipelines, const CasterScene& scene,
                                    const CasterFaceCulling& culling, uint32_t layer, BucketKind kind) const {
    if (buckets_.empty() || layer >= layer_count_) return;
    const auto bucket_count = static_cast<uint32_t>(buckets_.size());
    const uint32_t first = kind == BucketKind::Dynamic ? first_dynamic_bucket_ : 0u;
    const uint32_t end = kind == BucketKind::Static ? first_dynamic_bucket_ : bucket_count;
    if (first >= end) return;
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines.layout(),
                                     PENUMBRA_SET_CASTER_DRAWS, 1, &buffers_->set, 0, nullptr);
    record_indirect_caster_draws(device_, cmd, pipelines, scene, std::span(buckets_).subspan(first, end - first),
                                 buffers_->commands.get(), layer * draw_count_, buffers_->counts.get(),
                                 layer * bucket_count + first, culling);
}

void GpuCasterCulling::record_draws_of_every_layer(VkCommandBuffer cmd, const CasterPipelines& pipelines,
                                                   const CasterScene& scene, const CasterFaceCulling& culling) const {
    if (buckets_.empty() || layer_count_ == 0) return;
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines.layout(),
                                     PENUMBRA_SET_CASTER_DRAWS, 1, &buffers_->set, 0, nullptr);
    record_indirect_caster_draws(device_, cmd, pipelines, scene, buckets_, buffers_->commands.get(), 0,
                                 buffers_->counts.get(), 0, culling, layer_count_);
}

uint64_t GpuCasterCulling::buffer_bytes() const {
    uint64_t bytes = tiles_.size;
    for (const gpu::Buffer& staging : staging_) bytes += staging.size;
    if (!buffers_) return bytes;
    for (const gpu::Buffer* buffer :
         {&buffers_->instances, &buffers_->buckets, &buffers_->records, &buffers_->commands, &buffers_->counts}) {
        bytes += buffer->size;
    }
    return bytes;
}

CulledDraws GpuCasterCulling::read_back(const gpu::OneTimeCommands& commands) const {
    const gpu::ObjectNames names(device_, "caster culling readback");
    CulledDraws result;
    result.draws_per_layer.resize(layer_count_);
    const auto bucket_count = static_cast<uint32_t>(buckets_.size());
    if (bucket_count == 0 || layer_count_ == 0) return result;
    const VkDeviceSize count_bytes = VkDeviceSize{bucket_count} * layer_count_ * sizeof(uint32_t);
    const VkDeviceSize record_bytes = buffers_->records.size;
    const gpu::Buffer readback = gpu::create_buffer(device_, count_bytes + record_bytes,
                                                    VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryKind::HostReadback);
    commands.submit_and_wait([&](VkCommandBuffer cmd) {
        const VkBufferCopy counts{0, 0, count_bytes};
        const VkBufferCopy records{0, count_bytes, record_bytes};
        device_->vkCmdCopyBuffer(cmd, buffers_->counts.get(), readback.get(), 1, &counts);
        device_->vkCmdCopyBuffer(cmd, buffers_->records.get(), readback.get(), 1, &records);
        gpu::transfer_to_host_barrier(device_, cmd);
    });
    const auto* bytes = static_cast<const std::byte*>(readback.mapped);
    for (uint32_t layer = 0; layer < layer_count_; ++layer) {
        for (uint32_t b = 0; b < bucket_count; ++b) {
            uint32_t count = 0;
            std::memcpy(&count, bytes + (size_t{layer} * bucket_count + b) * sizeof(uint32_t), sizeof(count));
            count = std::min(count, buckets_[b].capacity);
            for (uint32_t c = 0; c < count; ++c) {
                const size_t command = size_t{layer} * draw_count_ + buckets_[b].first_command + c;
                shader::CullRecord record{};
                std::memcpy(&record, bytes + count_bytes + command * sizeof(record), sizeof(record));
                // A record naming another layer in this layer's region is a bug the tests must see.
                result.draws_per_layer[layer].push_back(record.layer == layer ? record.instance : ~0u);
            }
        }
    }
    for (std::vector<uint32_t>& draws : result.draws_per_layer) std::sort(draws.begin(), draws.end());
    return result;
}

}  // namespace penumbra::passes

#include "library/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "core/mesh_clusters.hpp"
#include "library/conversions.hpp"
#include "library/instance_checks.hpp"
#include "passes/shader_interface.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra/gpu/check.hpp"
#include "penumbra/gpu/debug_names.hpp"

namespace penumbra::library {
namespace {

constexpr uint32_t kAlphaMasksPerPool = 64;

const std::vector<VkFormat>& position_formats() {
    static const std::vector<VkFormat> formats{VK_FORMAT_R32G32B32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT,
                                               VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R16G16B16A16_SNORM,
                                               VK_FORMAT_R16G16B16A16_UNORM};
    return formats;
}

const std::vector<VkFormat>& uv_formats() {
    static const std::vector<VkFormat> formats{VK_FORMAT_R32G32_SFLOAT, VK_FORMAT_R16G16_SFLOAT, VK_FORMAT_R16G16_UNORM,
                                               VK_FORMAT_R16G16_SNORM};
    return formats;
}

uint32_t format_bytes(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R32G32B32_SFLOAT:
            return 12;
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            return 16;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R16G16B16A16_SNORM:
        case VK_FORMAT_R16G16B16A16_UNORM:
        case VK_FORMAT_R32G32_SFLOAT:
            return 8;
        default:
            return 4;  // the two-component 16-bit UV formats
    }
}

[[noreturn]] void reject(const char* call, const std::string& field, const std::string& problem) {
    throw InputError(std::string("ShadowSystem::") + call + ": " + field + ": " + problem);
}

void check_stream(const gpu::Device& device, const VertexStream& stream, const std::vector<VkFormat>& allowed,
                  const char* call, const std::string& name) {
    if (stream.buffer == VK_NULL_HANDLE) reject(call, name + ".buffer", "is VK_NULL_HANDLE");
    if (std::find(allowed.begin(), allowed.end(), stream.format) == allowed.end()) {
        reject(call, name + ".format",
               gpu::format_name(stream.format) + " is not supported (docs/library.md lists the vertex formats)");
    }
    VkFormatProperties properties{};
    device->vkGetPhysicalDeviceFormatProperties(device.physical_device(), stream.format, &properties);
    if (!(properties.bufferFeatures & VK_FORMAT_FEATURE_VERTEX_BUFFER_BIT)) {
        reject(call, name + ".format",
               gpu::format_name(stream.format) + " cannot be a vertex attribute on this device");
    }
    if (stream.stride < format_bytes(stream.format)) {
        reject(call, name + ".stride",
               std::to_string(stream.stride) + " is smaller than one element (" +
                   std::to_string(format_bytes(stream.format)) + " bytes)");
    }
}

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void check_bounds(const Bounds& bounds, const char* call, const std::string& field = "bounds") {
    if (!finite(bounds.min) || !finite(bounds.max)) reject(call, field, "must be finite");
    if (bounds.min.x > bounds.max.x || bounds.min.y > bounds.max.y || bounds.min.z > bounds.max.z) {
        reject(call, field, "min exceeds max on an axis");
    }
}

// Runs of triangles that cover the index list in order.
std::vector<core::MeshCluster> checked_clusters(std::span<const MeshCluster> clusters, uint32_t index_count,
                                                const char* call) {
    std::vector<core::MeshCluster> result;
    uint32_t next = 0;
    for (size_t c = 0; c < clusters.size(); ++c) {
        const MeshCluster& cluster = clusters[c];
        const std::string field = "clusters[" + std::to_string(c) + "]";
        if (cluster.first_index != next) {
            reject(call, field + ".first_index",
                   std::to_string(cluster.first_index) + " is not " + std::to_string(next) +
                       ", where the previous cluster ends (clusters cover the indices in order)");
        }
        if (cluster.index_count == 0 || cluster.index_count % 3 != 0 || cluster.index_count > index_count - next) {
            reject(call, field + ".index_count",
                   std::to_string(cluster.index_count) + " is not a positive multiple of 3 within index_count " +
                       std::to_string(index_count));
        }
        check_bounds(cluster.bounds, call, field + ".bounds");
        result.push_back({cluster.first_index, cluster.index_count, to_aabb(cluster.bounds)});
        next += cluster.index_count;
    }
    if (!clusters.empty() && next != index_count) {
        reject(call, "clusters",
               "end at index " + std::to_string(next) + ", not at index_count " + std::to_string(index_count));
    }
    return result;
}

// "field: problem" of a list that is not triangles of `positions`; empty when it is.
std::string triangle_index_problem(std::span<const uint32_t> indices, size_t positions) {
    if (indices.size() % 3 != 0) return "indices: " + std::to_string(indices.size()) + " is not a multiple of 3";
    for (size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= positions) {
            return "indices[" + std::to_string(i) + "]: " + std::to_string(indices[i]) + " is out of range (" +
                   std::to_string(positions) + " positions)";
        }
    }
    return "";
}

std::vector<glm::vec3> glm_positions(std::span<const Vec3> positions) {
    std::vector<glm::vec3> result(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) result[i] = to_glm(positions[i]);
    return result;
}

void check_alpha_mask(const AlphaMaskDesc& mask, const char* call) {
    if (mask.view == VK_NULL_HANDLE) reject(call, "alpha_mask.view", "is VK_NULL_HANDLE");
    if (mask.sampler == VK_NULL_HANDLE) reject(call, "alpha_mask.sampler", "is VK_NULL_HANDLE");
    if (!(mask.cutoff > 0.0f && mask.cutoff <= 1.0f)) {
        reject(call, "alpha_mask.cutoff", std::to_string(mask.cutoff) + " is outside (0, 1]");
    }
    if (!(mask.alpha_scale >= 0.0f && mask.alpha_scale <= 1.0f)) {
        reject(call, "alpha_mask.alpha_scale", std::to_string(mask.alpha_scale) + " is outside [0, 1]");
    }
}

void check_indices(VkIndexType type, VkDeviceSize offset, uint32_t count, const char* call) {
    if (type != VK_INDEX_TYPE_UINT16 && type != VK_INDEX_TYPE_UINT32) {
        reject(call, "index_type", "must be VK_INDEX_TYPE_UINT16 or VK_INDEX_TYPE_UINT32");
    }
    const VkDeviceSize size = type == VK_INDEX_TYPE_UINT16 ? 2 : 4;
    if (offset % size != 0)
        reject(call, "index_offset", std::to_string(offset) + " is not a multiple of the index size");
    if (count == 0 || count % 3 != 0) {
        reject(call, "index_count", std::to_string(count) + " is not a positive multiple of 3 (a triangle list)");
    }
}

core::Aabb bounds_of(std::span<const Vec3> positions) {
    core::Aabb bounds;
    for (const Vec3& position : positions) bounds.expand(to_glm(position));
    return bounds;
}

template <typename T>
std::span<const std::byte> bytes_of(std::span<const T> values) {
    return std::as_bytes(values);
}

}  // namespace

Geometry::Geometry(const gpu::Device& device, RetiredObjects& retired, VkDescriptorSetLayout alpha_mask_set_layout,
                   std::function<void(const passes::VertexFormats&)> prepare_pipelines)
    : device_(device),
      retired_(retired),
      alpha_mask_set_layout_(alpha_mask_set_layout),
      prepare_pipelines_(std::move(prepare_pipelines)) {}

MeshId Geometry::add_mesh(const MeshDesc& desc) {
    const char* call = "add_mesh";
    check_stream(device_, desc.positions, position_formats(), call, "positions");
    if (desc.index_buffer == VK_NULL_HANDLE) reject(call, "index_buffer", "is VK_NULL_HANDLE");
    check_indices(desc.index_type, desc.index_offset, desc.index_count, call);
    check_bounds(desc.bounds, call);
    check_bounds_magnitude(desc.bounds, call);
    if (desc.alpha_mask) {
        check_alpha_mask(*desc.alpha_mask, call);
        if (!desc.uvs) reject(call, "uvs", "are required with an alpha mask");
        check_stream(device_, *desc.uvs, uv_formats(), call, "uvs");
    }
    Mesh mesh;
    mesh.caster.positions = {desc.positions.buffer, desc.positions.offset, desc.positions.stride,
                             desc.positions.format};
    if (desc.alpha_mask) mesh.caster.uvs = {desc.uvs->buffer, desc.uvs->offset, desc.uvs->stride, desc.uvs->format};
    mesh.caster.index_buffer = desc.index_buffer;
    mesh.caster.index_offset = desc.index_offset;
    mesh.caster.index_type = desc.index_type;
    mesh.caster.index_count = desc.index_count;
    mesh.caster.vertex_offset = desc.vertex_offset;
    mesh.bounds = to_aabb(desc.bounds);
    mesh.caster.clusters = checked_clusters(desc.clusters, desc.index_count, call);
    if (desc.alpha_mask) attach_alpha_mask(mesh, *desc.alpha_mask);
    return insert_mesh(std::move(mesh));
}

MeshId Geometry::add_mesh(const MeshData& data) {
    const char* call = "add_mesh";
    if (data.positions.empty()) reject(call, "positions", "is empty");
    if (data.indices.empty() || data.indices.size() % 3 != 0) {
        reject(call, "indices", std::to_string(data.indices.size()) + " is not a positive multiple of 3");
    }
    if (const std::string problem = triangle_index_problem(data.indices, data.positions.size()); !problem.empty()) {
        throw InputError(std::string("ShadowSystem::") + call + ": " + problem);
    }
    check_positions(data.positions, call);
    if (!data.uvs.empty() && data.uvs.size() != data.positions.size()) {
        reject(call, "uvs",
               std::to_string(data.uvs.size()) + " given for " + std::to_string(data.positions.size()) + " positions");
    }
    if (data.alpha_mask) {
        check_alpha_mask(*data.alpha_mask, call);
        if (data.uvs.empty()) reject(call, "uvs", "are required with an alpha mask");
    }
    Mesh mesh;
    const VkBufferUsageFlags vertex = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    mesh.caster.positions = {upload(bytes_of(data.positions), vertex, mesh), 0, sizeof(Vec3),
                             VK_FORMAT_R32G32B32_SFLOAT};
    if (data.alpha_mask) {
        mesh.caster.uvs = {upload(bytes_of(data.uvs), vertex, mesh), 0, sizeof(Vec2), VK_FORMAT_R32G32_SFLOAT};
    }
    std::vector<uint32_t> indices(data.indices.begin(), data.indices.end());
    mesh.caster.clusters = core::cluster_triangles(glm_positions(data.positions), indices);
    mesh.caster.index_buffer =
        upload(bytes_of(std::span<const uint32_t>(indices)), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, mesh);
    mesh.caster.index_type = VK_INDEX_TYPE_UINT32;
    mesh.caster.index_count = static_cast<uint32_t>(data.indices.size());
    mesh.bounds = bounds_of(data.positions);
    if (data.alpha_mask) attach_alpha_mask(mesh, *data.alpha_mask);
    return insert_mesh(std::move(mesh));
}

void Geometry::for_each_vertex_format(const std::function<void(const passes::VertexFormats&)>& visit) const {
    for (const auto& [id, mesh] : meshes_) {
        visit(passes::vertex_formats(mesh.caster, false));
        if (mesh.alpha_mask_set != VK_NULL_HANDLE) visit(passes::vertex_formats(mesh.caster, true));
    }
}

MeshId Geometry::insert_mesh(Mesh mesh) {
    prepare_pipelines_(passes::vertex_formats(mesh.caster, false));
    if (mesh.alpha_mask_set != VK_NULL_HANDLE) prepare_pipelines_(passes::vertex_formats(mesh.caster, true));
    const uint32_t id = next_mesh_id_++;
    meshes_.emplace(id, std::move(mesh));
    ++changes_;
    return MeshId{id};
}

VkBuffer Geometry::upload(std::span<const std::byte> bytes, VkBufferUsageFlags usage, Mesh& mesh) {
    const gpu::ObjectNames names(device_, "mesh buffers");
    gpu::Buffer staging =
        gpu::create_buffer(device_, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryKind::HostUpload);
    std::memcpy(staging.mapped, bytes.data(), bytes.size());
    gpu::Buffer buffer = gpu::create_buffer(device_, bytes.size(), usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                            gpu::MemoryKind::DeviceLocal);
    const VkBuffer handle = buffer.get();
    uploads_.push_back({std::move(staging), handle, bytes.size()});
    mesh.owned.push_back(std::move(buffer));
    return handle;
}

void Geometry::attach_alpha_mask(Mesh& mesh, const AlphaMaskDesc& mask) {
    const gpu::ObjectNames names(device_, "alpha masks");
    if (alpha_mask_pools_.empty() || alpha_masks_in_last_pool_ == kAlphaMasksPerPool) {
        const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kAlphaMasksPerPool};
        alpha_mask_pools_.push_back(gpu::create_descriptor_pool(device_, kAlphaMasksPerPool, {&size, 1},
                                                                VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT));
        alpha_masks_in_last_pool_ = 0;
    }
    mesh.alpha_mask_pool = alpha_mask_pools_.back();
    mesh.alpha_mask_set = gpu::allocate_descriptor_set(device_, mesh.alpha_mask_pool, alpha_mask_set_layout_);
    ++alpha_masks_in_last_pool_;
    gpu::write_combined_image_sampler(device_, mesh.alpha_mask_set, PENUMBRA_BINDING_ALPHA_MASK, mask.view,
                                      mask.sampler);
    mesh.caster.alpha_mask_set = mesh.alpha_mask_set;
    mesh.caster.alpha_cutoff = mask.cutoff;
    mesh.caster.alpha_scale = mask.alpha_scale;
}

Geometry::Mesh& Geometry::find_mesh(MeshId mesh, const char* call) {
    const auto found = meshes_.find(mesh.value);
    if (found == meshes_.end()) {
        throw UsageError(std::string("ShadowSystem::") + call + ": mesh " + std::to_string(mesh.value) +
                         " does not exist (never added, or removed)");
    }
    return found->second;
}

// A removed mesh's set goes back to its pool once no frame in flight can bind it.
struct FreedDescriptorSet {
    const gpu::Device* device;
    VkDescriptorPool pool;
    VkDescriptorSet set;
    FreedDescriptorSet(const gpu::Device& owner, VkDescriptorPool from, VkDescriptorSet freed)
        : device(&owner), pool(from), set(freed) {}
    FreedDescriptorSet(FreedDescriptorSet&& other) noexcept
        : device(other.device), pool(other.pool), set(std::exchange(other.set, VK_NULL_HANDLE)) {}
    FreedDescriptorSet(const FreedDescriptorSet&) = delete;
    FreedDescriptorSet& operator=(const FreedDescriptorSet&) = delete;
    FreedDescriptorSet& operator=(FreedDescriptorSet&&) = delete;
    ~FreedDescriptorSet() {
        if (set != VK_NULL_HANDLE) (*device)->vkFreeDescriptorSets(*device, pool, 1, &set);
    }
};

void Geometry::remove_mesh(MeshId id, uint64_t frame) {
    Mesh& mesh = find_mesh(id, "remove_mesh");
    if (mesh.instances > 0) {
        throw UsageError("ShadowSystem::remove_mesh: mesh " + std::to_string(id.value) + " is still used by " +
                         std::to_string(mesh.instances) + " instance(s); remove them first");
    }
    // Uploads not yet recorded would copy into the buffers retired below: they go too
    // (their staging buffers were never used by a submission).
    std::erase_if(uploads_, [&](const Upload& upload) {
        return std::any_of(mesh.owned.begin(), mesh.owned.end(),
                           [&](const gpu::Buffer& buffer) { return buffer.get() == upload.destination; });
    });
    for (gpu::Buffer& buffer : mesh.owned) retired_.retire(std::move(buffer), frame);
    if (mesh.alpha_mask_set != VK_NULL_HANDLE) {
        retired_.retire(FreedDescriptorSet(device_, mesh.alpha_mask_pool, mesh.alpha_mask_set), frame);
    }
    meshes_.erase(id.value);
    ++changes_;
}

InstanceId Geometry::add_instance(const InstanceDesc& desc) {
    Mesh& mesh = find_mesh(desc.mesh, "add_instance");
    const core::Aabb world_bounds = checked_world_bounds(desc.world, mesh.bounds, "add_instance");
    check_instance_flags(desc.flags, "add_instance");
    const Instance instance{next_instance_id_++, desc.mesh.value, to_glm(desc.world), desc.flags, world_bounds};
    note_static_change(instance);
    ++mesh.instances;
    instance_index_.emplace(instance.id, static_cast<uint32_t>(instances_.size()));
    instances_.push_back(instance);
    ++changes_;
    return InstanceId{instance.id};
}

Geometry::Instance& Geometry::find_instance(InstanceId instance, const char* call) {
    const auto found = instance_index_.find(instance.value);
    if (found == instance_index_.end()) {
        throw UsageError(std::string("ShadowSystem::") + call + ": instance " + std::to_string(instance.value) +
                         " does not exist (never added, or removed)");
    }
    return instances_[found->second];
}

void Geometry::note_static_change(const Instance& instance) {
    const bool static_caster = (instance.flags & kInstanceCastsShadows) && !(instance.flags & kInstanceDynamic);
    if (static_caster) static_changes_.push_back(instance.world_bounds);
}

std::span<const core::Aabb> Geometry::static_changes_since(uint64_t position) const {
    const uint64_t first = std::clamp(position, forgotten_static_changes_, static_change_end());
    return std::span<const core::Aabb>(static_changes_).subspan(first - forgotten_static_changes_);
}

void Geometry::forget_static_changes_before(uint64_t position) {
    const uint64_t count = std::min(position, static_change_end()) - std::min(position, forgotten_static_changes_);
    static_changes_.erase(static_changes_.begin(), static_changes_.begin() + static_cast<std::ptrdiff_t>(count));
    forgotten_static_changes_ += count;
}

void Geometry::set_instance_transform(InstanceId id, const Mat4& world) {
    Instance& instance = find_instance(id, "set_instance_transform");
    const auto world_bounds = checked_world_bounds(world, meshes_.at(instance.mesh).bounds, "set_instance_transform");
    // The same matrix again (an engine that uploads every transform every frame) changes
    // nothing: the cached depths of a static caster stay, and the scene is not rebuilt.
    const glm::mat4 transform = to_glm(world);
    if (transform == instance.world) return;
    note_static_change(instance);
    instance.world = transform;
    instance.world_bounds = world_bounds;
    note_static_change(instance);
    ++changes_;
}

void Geometry::set_instance_flags(InstanceId id, uint32_t flags) {
    Instance& instance = find_instance(id, "set_instance_flags");
    check_instance_flags(flags, "set_instance_flags");
    if (flags == instance.flags) return;
    note_static_change(instance);  // what it was (a static caster's depths go)
    instance.flags = flags;
    note_static_change(instance);  // and what it is
    ++changes_;
}

void Geometry::remove_instance(InstanceId id) {
    Instance& instance = find_instance(id, "remove_instance");
    note_static_change(instance);
    meshes_.at(instance.mesh).instances -= 1;
    const uint32_t index = instance_index_.at(id.value);
    if (index + 1 != instances_.size()) {
        instances_[index] = instances_.back();
        instance_index_[instances_[index].id] = index;
    }
    instances_.pop_back();
    instance_index_.erase(id.value);
    ++changes_;
}

const passes::CasterScene& Geometry::build_scene() {
    scene_.meshes.clear();
    scene_.draws.clear();
    scene_.dynamic_draws.clear();
    world_bounds_ = core::Aabb{};
    static_bounds_ = core::Aabb{};
    for (auto& [id, mesh] : meshes_) {
        mesh.scene_index = static_cast<uint32_t>(scene_.meshes.size());
        scene_.meshes.push_back(mesh.caster);
    }
    for (const Instance& instance : instances_) {
        world_bounds_.expand(instance.world_bounds);
        if (!(instance.flags & kInstanceDynamic)) static_bounds_.expand(instance.world_bounds);
        if (!(instance.flags & kInstanceCastsShadows)) continue;
        const Mesh& mesh = meshes_.at(instance.mesh);
        passes::CasterDraw draw;
        draw.mesh = mesh.scene_index;
        draw.model = instance.world;
        draw.world_bounds = instance.world_bounds;
        draw.masked = (instance.flags & kInstanceAlphaMasked) && mesh.alpha_mask_set != VK_NULL_HANDLE;
        draw.double_sided = (instance.flags & kInstanceDoubleSided) != 0;
        draw.mirrored = glm::determinant(glm::mat3(instance.world)) < 0.0f;
        draw.dynamic = (instance.flags & kInstanceDynamic) != 0;
        if (draw.dynamic) scene_.dynamic_draws.push_back(static_cast<uint32_t>(scene_.draws.size()));
        scene_.draws.push_back(draw);
    }
    scene_.version = changes_;
    return scene_;
}

void Geometry::record_uploads(VkCommandBuffer cmd, uint64_t frame) {
    if (uploads_.empty()) return;
    for (Upload& upload : uploads_) {
        const VkBufferCopy region{0, 0, upload.size};
        device_->vkCmdCopyBuffer(cmd, upload.staging.get(), upload.destination, 1, &region);
        retired_.retire(std::move(upload.staging), frame);
    }
    uploads_.clear();
    gpu::memory_barrier(device_, cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT,
                        VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT);
}

uint64_t Geometry::buffer_bytes() const {
    uint64_t bytes = 0;
    for (const auto& [id, mesh] : meshes_) {
        for (const gpu::Buffer& buffer : mesh.owned) bytes += buffer.size;
    }
    return bytes;
}

}  // namespace penumbra::library

namespace penumbra {

std::vector<MeshCluster> build_mesh_clusters(std::span<const Vec3> positions, std::span<uint32_t> indices) {
    if (const std::string problem = library::triangle_index_problem(indices, positions.size()); !problem.empty()) {
        throw InputError("build_mesh_clusters: " + problem);
    }
    std::vector<MeshCluster> clusters;
    for (const core::MeshCluster& cluster : core::cluster_triangles(library::glm_positions(positions), indices)) {
        clusters.push_back({cluster.first_index,
                            cluster.index_count,
                            {library::to_public(cluster.bounds.min), library::to_public(cluster.bounds.max)}});
    }
    return clusters;
}

}  // namespace penumbra

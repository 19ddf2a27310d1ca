#pragma once
// A ShadowSystem's meshes and instances: the caller's vertex streams (or buffers Penumbra
// uploads CPU arrays into), alpha masks, instance transforms and flags, and the caster
// scene the passes draw, rebuilt for each frame from the current instances.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/shadow_inputs.hpp"
#include "library/retired.hpp"
#include "passes/casters.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/shadow_system.hpp"

namespace penumbra::library {

class Geometry {
public:
    // `prepare_pipelines` is called for every vertex format combination a new mesh brings.
    Geometry(const gpu::Device& device, RetiredObjects& retired, VkDescriptorSetLayout alpha_mask_set_layout,
             std::function<void(const passes::VertexFormats&)> prepare_pipelines);

    MeshId add_mesh(const MeshDesc& mesh);
    MeshId add_mesh(const MeshData& mesh);
    void remove_mesh(MeshId mesh, uint64_t frame);
    InstanceId add_instance(const InstanceDesc& instance);
    void set_instance_transform(InstanceId instance, const Mat4& world);
    void set_instance_flags(InstanceId instance, uint32_t flags);
    void remove_instance(InstanceId instance);

    // The casting instances as draws, and the world bounds of the instances (casting or not:
    // receivers bound the cascades' depth range too).
    const passes::CasterScene& build_scene();
    const passes::CasterScene& scene() const { return scene_; }  // as the last build_scene() made it
    const core::Aabb& world_bounds() const { return world_bounds_; }
    // The bounds that set the cascades' depth range: the static instances' (not
    // kInstanceDynamic), or every instance's when all are dynamic. Instances that move every
    // frame would otherwise change the depth mapping, and with it every cached texel.
    const core::Aabb& depth_range_bounds() const { return static_bounds_.empty() ? world_bounds_ : static_bounds_; }
    // World bounds, old and new, of every static caster (casting, not kInstanceDynamic)
    // added, moved, changed or removed, as a log: a cached map that has drawn the changes
    // up to position P finds the texels it holds stale in static_changes_since(P).
    // static_change_end() is the position after the newest change.
    uint64_t static_change_end() const { return forgotten_static_changes_ + static_changes_.size(); }
    std::span<const core::Aabb> static_changes_since(uint64_t position) const;
    // Forgets the changes before `position` (every cached map has drawn them).
    void forget_static_changes_before(uint64_t position);
    uint64_t triangles(uint32_t draw) const { return scene_.meshes[scene_.draws[draw].mesh].index_count / 3; }

    // Records the copies of meshes uploaded since the last call and makes them visible to
    // vertex input; the staging buffers are retired.
    void record_uploads(VkCommandBuffer cmd, uint64_t frame);

    uint64_t buffer_bytes() const;

    // Calls `visit` with every vertex format combination of the meshes (with and without
    // their alpha masks), as `prepare_pipelines` was: for maps made after the meshes.
    void for_each_vertex_format(const std::function<void(const passes::VertexFormats&)>& visit) const;

private:
    struct Mesh {
        passes::CasterMesh caster;
        core::Aabb bounds;
        uint32_t instances = 0;
        std::vector<gpu::Buffer> owned;  // uploaded streams (MeshData)
        VkDescriptorSet alpha_mask_set = VK_NULL_HANDLE;
        VkDescriptorPool alpha_mask_pool = VK_NULL_HANDLE;
        uint32_t scene_index = 0;  // into scene_.meshes, this frame
    };
    struct Instance {
        uint32_t id = 0;
        uint32_t mesh = 0;  // MeshId value
        glm::mat4 world{1.0f};
        uint32_t flags = 0;
        core::Aabb world_bounds;
    };
    struct Upload {
        gpu::Buffer staging;
        VkBuffer destination;
        VkDeviceSize size;
    };

    MeshId insert_mesh(Mesh mesh);
    void attach_alpha_mask(Mesh& mesh, const AlphaMaskDesc& mask);
    VkBuffer upload(std::span<const std::byte> bytes, VkBufferUsageFlags usage, Mesh& mesh);
    Mesh& find_mesh(MeshId mesh, const char* call);
    Instance& find_instance(InstanceId instance, const char* call);
    void note_static_change(const Instance& instance);

    const gpu::Device& device_;
    RetiredObjects& retired_;
    VkDescriptorSetLayout alpha_mask_set_layout_;
    std::function<void(const passes::VertexFormats&)> prepare_pipelines_;
    std::unordered_map<uint32_t, Mesh> meshes_;
    std::vector<Instance> instances_;                        // dense, in insertion order (swap on removal)
    std::unordered_map<uint32_t, uint32_t> instance_index_;  // InstanceId value -> index into instances_
    uint32_t next_mesh_id_ = 1;
    uint32_t next_instance_id_ = 1;
    std::vector<gpu::UniqueDescriptorPool> alpha_mask_pools_;
    uint32_t alpha_masks_in_last_pool_ = 0;
    std::vector<Upload> uploads_;
    passes::CasterScene scene_;
    core::Aabb world_bounds_;
    core::Aabb static_bounds_;
    std::vector<core::Aabb> static_changes_;
    uint64_t forgotten_static_changes_ = 0;  // the log position of static_changes_[0]
    uint64_t changes_ = 0;                   // mutations so far (CasterScene::version)
};

}  // namespace penumbra::library

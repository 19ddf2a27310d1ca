#pragma once
// A Scene uploaded to the GPU by the tools' renderer: one vertex and one index buffer for
// every mesh, a texture per scene texture (plus a white fallback), a descriptor set per
// material and the draw list of the camera passes. Its meshes and instances are also given
// to the ShadowSystem as any renderer gives its own: the mesh ranges of these very buffers
// (nothing is copied), with the material's texture as the alpha mask of masked casters.
#include <optional>
#include <vector>

#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/scene/scene.hpp"
#include "penumbra/shadow_system.hpp"
#include "renderer/app_context.hpp"
#include "renderer/draw_data.hpp"

namespace penumbra::renderer {

class GpuScene {
public:
    GpuScene(const AppContext& context, const Scene& scene, ShadowSystem& shadows);

    const DrawData& draw_data() const { return draw_data_; }
    // Moves scene instance `instance` (an index into Scene::instances) to `world`: its draw
    // and its shadow caster. Throws InputError for an index out of range.
    void move_instance(size_t instance, const glm::mat4& world, ShadowSystem& shadows);
    // Orders DrawData::batches by the distance of each draw's centre from `eye`, nearest first.
    void order_draws_front_to_back(const glm::vec3& eye);

private:
    struct MeshRange {
        uint32_t first_index = 0;
        uint32_t index_count = 0;
        int32_t vertex_offset = 0;
        std::vector<MeshCluster> clusters;  // for the virtual shadow map's culling
    };

    std::vector<MeshRange> upload_geometry(const AppContext& context, const Scene& scene);
    void create_materials(const AppContext& context, const Scene& scene);
    // The white fallback texel, last in textures_.
    size_t white_texture_slot() const { return textures_.size() - 1; }
    // Where a material's texture index (Scene::textures, -1 for none) is in textures_; the
    // white texel for none or an index out of range.
    size_t texture_slot(int32_t texture) const {
        return texture >= 0 && static_cast<size_t>(texture) < white_texture_slot() ? static_cast<size_t>(texture)
                                                                                   : white_texture_slot();
    }
    void add_draws(const AppContext& context, const Scene& scene, const std::vector<MeshRange>& ranges);
    // DrawData::batches from `order` (indices into DrawData::draws), and the instance slots
    // they name.
    void build_batches(const std::vector<uint32_t>& order);
    void write_draw_model(uint32_t draw);
    void add_shadow_casters(const Scene& scene, const std::vector<MeshRange>& ranges, ShadowSystem& shadows);

    gpu::Buffer vertices_;
    gpu::Buffer indices_;
    std::vector<gpu::Image> textures_;                  // scene textures, then the white fallback last
    std::vector<gpu::UniqueSampler> texture_samplers_;  // one per texture (its glTF sampler), then the white texel's
    gpu::UniqueDescriptorSetLayout material_set_layout_;
    gpu::UniqueDescriptorPool descriptor_pool_;
    DrawData draw_data_;
    gpu::Buffer draw_models_;     // mat4 per draw, host-visible (the renderer waits for every frame)
    gpu::Buffer instance_slots_;  // uint per instance slot of the frame's batches: its draw
    // Per scene instance: its draw (an index into draw_data_.draws) and its shadow caster;
    // std::nullopt for an instance of an empty mesh.
    std::vector<std::optional<uint32_t>> instance_draws_;
    std::vector<std::optional<InstanceId>> instance_casters_;
    std::vector<glm::vec3> mesh_centres_;  // the centre of each mesh's bounds (draw sorting)
};

}  // namespace penumbra::renderer

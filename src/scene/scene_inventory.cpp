#include "penumbra/scene/inventory.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

namespace penumbra {
namespace {

// A node placed several times, or a mesh with several primitives, is one entry; objects
// made by code (the built-in forest) have no object index and group by name.
using EntryKey = std::tuple<int32_t, int32_t, std::string>;

EntryKey entry_key(const Instance& instance) {
    return {instance.origin.object, instance.origin.node, instance.origin.node >= 0 ? std::string() : instance.name};
}

bool usable_as_pattern(const std::string& name) {
    return !name.empty() && name.find_first_of("*?[") == std::string::npos;
}

void add_instance(SceneEntry& entry, const Scene& scene, size_t index, std::set<uint32_t>& meshes,
                  std::set<int32_t>& placements) {
    const Instance& instance = scene.instances[index];
    const Mesh& mesh = scene.meshes.at(instance.mesh);
    entry.instances.push_back(index);
    meshes.insert(instance.mesh);
    placements.insert(instance.origin.placement);
    entry.triangles += mesh.indices.size() / 3;
    entry.bounds.expand(transform_aabb(mesh.bounds, instance.world));
    entry.casting += instance.cast_shadows;
    entry.receiving += instance.receive_shadows;
    entry.dynamic += instance.dynamic;
    const AlphaMode mode =
        mesh.material < scene.materials.size() ? scene.materials[mesh.material].alpha_mode : AlphaMode::Opaque;
    if (std::find(entry.alpha_modes.begin(), entry.alpha_modes.end(), mode) == entry.alpha_modes.end()) {
        entry.alpha_modes.push_back(mode);
    }
    entry.primitives = static_cast<uint32_t>(meshes.size());
    entry.placements = static_cast<uint32_t>(placements.size());
}

}  // namespace

std::vector<SceneEntry> scene_inventory(const Scene& scene) {
    std::vector<SceneEntry> entries;
    std::map<EntryKey, size_t> entry_of_key;
    std::vector<std::set<uint32_t>> meshes;
    std::vector<std::set<int32_t>> placements;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const auto [found, added] = entry_of_key.try_emplace(entry_key(instance), entries.size());
        if (added) {
            entries.push_back({instance.origin, instance.name});
            meshes.emplace_back();
            placements.emplace_back();
        }
        const size_t entry = found->second;
        add_instance(entries[entry], scene, i, meshes[entry], placements[entry]);
    }
    return entries;
}

std::string exclusion_name(const InstanceOrigin& origin) {
    if (origin.node < 0) return {};
    if (usable_as_pattern(origin.node_name)) return origin.node_name;
    if (usable_as_pattern(origin.mesh_name)) return origin.mesh_name;
    return "nodes[" + std::to_string(origin.node) + "]";
}

std::string no_shadow_advice(const InstanceOrigin& origin) {
    const std::string object = origin.object >= 0 ? " in objects[" + std::to_string(origin.object) + "]" : "";
    if (origin.node >= 0) return "exclude_casters = [\"" + exclusion_name(origin) + "\"]" + object;
    return "cast_shadows = false" + object;
}

const char* alpha_mode_name(AlphaMode mode) {
    switch (mode) {
        case AlphaMode::Opaque:
            return "opaque";
        case AlphaMode::Mask:
            return "mask";
        case AlphaMode::Blend:
            return "blend";
    }
    return "opaque";
}

const char* light_type_name(LightType type) {
    switch (type) {
        case LightType::Directional:
            return "directional";
        case LightType::Spot:
            return "spot";
        case LightType::Point:
            return "point";
    }
    return "directional";
}

}  // namespace penumbra

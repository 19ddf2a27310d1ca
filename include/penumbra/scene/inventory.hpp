#pragma once
// What a loaded scene is made of, grouped the way its author names it (Penumbra::scene):
// one entry per scene-file object, and for a glTF model one per node that holds a mesh
// (all its primitives and placements together). `penumbra inspect` prints it, and the
// tools name a caster by it in their warnings.
#include <cstdint>
#include <string>
#include <vector>

#include "penumbra/scene/scene.hpp"

namespace penumbra {

struct SceneEntry {
    InstanceOrigin origin;               // the first instance's (its primitive and placement fields: that one's)
    std::string name;                    // Instance::name: "objects[2] (box)", a node's name or "nodes[i]"
    std::vector<size_t> instances;       // indices into Scene::instances
    uint32_t primitives = 0;             // distinct meshes (glTF primitives) among the instances
    uint32_t placements = 0;             // distinct placements of the object among the instances
    uint64_t triangles = 0;              // drawn once per instance
    Aabb bounds;                         // world space, every instance
    uint32_t casting = 0;                // instances that cast shadows
    uint32_t receiving = 0;              // instances that receive shadows
    uint32_t dynamic = 0;                // instances drawn every frame over the cached static casters
    std::vector<AlphaMode> alpha_modes;  // distinct, in the order met
};

// Entries in the order their first instance appears in Scene::instances.
std::vector<SceneEntry> scene_inventory(const Scene& scene);

// The exclude_casters entry that names this glTF node: its name, else its mesh's name, else
// "nodes[i]" (also used for names holding a pattern character, '*', '?' or '[', which
// exclude_casters would read as a pattern); empty for objects that are not glTF models.
std::string exclusion_name(const InstanceOrigin& origin);

// What the author changes so that the entry casts no shadow, as one phrase:
// `exclude_casters = ["Sky"] in objects[3]` or `cast_shadows = false in objects[1]`
// (built-in geometry made by code: its cast_shadows).
std::string no_shadow_advice(const InstanceOrigin& origin);

// The names scene files write: "opaque", "mask", "blend"; "directional", "spot", "point".
const char* alpha_mode_name(AlphaMode mode);
const char* light_type_name(LightType type);

}  // namespace penumbra

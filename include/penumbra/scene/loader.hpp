#pragma once
// Loading scenes (Penumbra::scene): TOML scene files (docs/scene-format.md), the glTF 2.0
// models they reference, and the built-in scenes. Every problem a user can cause throws
// InputError with one line naming the file, the key and the offending value.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "penumbra/scene/scene.hpp"

namespace penumbra {

constexpr std::string_view kBuiltinPrefix = "builtin:";
constexpr std::string_view kDefaultSceneName = "builtin:default";

// A path to a .toml scene file, or "builtin:NAME".
Scene load_scene(const std::string& path_or_builtin);

// Parses scene-file text. `origin` names the source in error messages; relative glTF
// paths are resolved against `base_directory`.
Scene parse_scene_toml(std::string_view text, const std::string& origin, const std::filesystem::path& base_directory);

// Names accepted after "builtin:".
std::vector<std::string> builtin_scene_names();
Scene builtin_scene(const std::string& name);

// glTF 2.0 (.gltf with external or embedded buffers, and .glb): node hierarchy and
// transforms, triangle meshes (sparse, quantized and morphed ones included: the static pose
// of the weights), positions, normals (computed when missing), the UV set the base colour
// texture reads, base colour factor and texture with its sampler, alphaMode with
// alphaCutoff, doubleSided (docs/scene-format.md lists the rules).
// Appends the model's meshes, materials and textures to `scene` and one Instance per
// (mesh primitive, placement): instance.world = placement * node world transform.
// With import_lights, the file's KHR_lights_punctual lights are appended to scene.lights
// too, one per (light node, placement), after the scene's own (so that the first
// directional light of the file becomes the sun only when the scene defines none).
// exclude_casters: names of nodes or meshes ('*' matches any run of characters) whose
// primitives cast no shadow; a pattern that matches no name is an error. Primitives with a
// KHR_materials_unlit material (skies, backdrops) cast none either. placement_casts and
// placement_receives, when not empty, give each placement's instances their
// cast_shadows and receive_shadows.
struct GltfImportOptions {
    bool import_lights = false;
    std::vector<std::string> exclude_casters;
    std::vector<bool> placement_casts;
    std::vector<bool> placement_receives;
    std::vector<bool> placement_dynamic;  // likewise each placement's Instance::dynamic
};
void append_gltf(Scene& scene, const std::filesystem::path& file, const std::vector<glm::mat4>& placements,
                 const GltfImportOptions& options = {});

}  // namespace penumbra

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

// What loading one scene may produce (issue 32): a few hundred bytes of glTF can describe
// billions of triangles (accessors without data, one mesh placed by many nodes) and a small
// PNG can declare gigapixels. Before anything is decoded or expanded, a load counts what
// its glTF models would make, from their accessor counts, node hierarchy, placements and
// image headers, and refuses (InputError, one line) a model that would take the scene past
// either limit; users with really big scenes raise them (`penumbra --max-scene-triangles`,
// `--max-scene-bytes`). Built-in and primitive objects count too, as they stand when a
// model is added.
struct LoadBudget {
    // Triangles drawn when every instance is drawn once (Scene::triangle_count()): a mesh
    // placed 64 times counts 64 times, since each placement costs its draw.
    uint64_t max_triangles = uint64_t{1} << 25;  // 33,554,432
    // Bytes of the meshes (vertices and 32-bit indices, each converted mesh once) and of the
    // decoded RGBA8 textures the scene holds. Loading needs a few times one primitive's or
    // one image's share on top while it converts it (its accessors read as doubles, a
    // 16-bit image decoded at 8 bytes a pixel).
    uint64_t max_bytes = uint64_t{1} << 30;  // 1 GiB
    // How the messages tell the user to raise each limit (the tools name their flags).
    std::string max_triangles_name = "LoadBudget::max_triangles";
    std::string max_bytes_name = "LoadBudget::max_bytes";
};

// A path to a .toml scene file, or "builtin:NAME".
Scene load_scene(const std::string& path_or_builtin, const LoadBudget& budget = {});

// Parses scene-file text. `origin` names the source in error messages; relative glTF
// paths are resolved against `base_directory`.
Scene parse_scene_toml(std::string_view text, const std::string& origin, const std::filesystem::path& base_directory,
                       const LoadBudget& budget = {});

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
    // Counted with what `scene` already holds; a model that would exceed it is refused
    // before its images are decoded (image headers) and before its meshes are converted.
    LoadBudget budget;
};
void append_gltf(Scene& scene, const std::filesystem::path& file, const std::vector<glm::mat4>& placements,
                 const GltfImportOptions& options = {});

}  // namespace penumbra

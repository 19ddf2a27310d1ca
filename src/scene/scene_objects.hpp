#pragma once
// The [[objects]] array of a scene file: primitives (plane, box, sphere, cylinder) with
// their materials and procedural textures, and glTF models with their instances.
#include <filesystem>

#include "penumbra/scene/loader.hpp"
#include "penumbra/scene/scene.hpp"
#include "scene/toml_fields.hpp"

namespace penumbra {

// Reads root.objects and appends meshes, materials, textures and instances to `scene`.
// Relative glTF paths are resolved against `base_directory`; each model is held to `budget`.
void append_scene_objects(TomlTableReader& root, Scene& scene, const std::filesystem::path& base_directory,
                          const LoadBudget& budget);

}  // namespace penumbra

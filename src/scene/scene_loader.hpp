#pragma once
// Loading scenes: TOML scene files (docs/scene-format.md), glTF 2.0 models they
// reference, and the built-in scenes. Every problem a user can cause throws
// InputError with one line naming the file, the key and the offending value.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene.hpp"

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

}  // namespace penumbra

#pragma once
// Settings files (Penumbra::scene): the [output] and [shadow] tables of a scene file, and
// config files (--config, docs/cli.md) which may also hold [camera] and [sun] overrides;
// and the writer that produces a config file reading back to the same values (floats with
// 9 significant digits, which round-trips every float).
#include <filesystem>
#include <string>

#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/scene.hpp"
#include "penumbra/scene/settings_overrides.hpp"

namespace penumbra {

// Reads [output] and [shadow] from a scene file (other tables are the scene parser's).
SettingsOverrides load_settings_from_scene_file(const std::filesystem::path& scene_file);

// Reads a config file: [output], [shadow], [camera], [sun]; any other table or key is an error.
SettingsOverrides load_settings_file(const std::filesystem::path& config_file);

// Reads config-file text (the tables and keys of load_settings_file); errors name `origin`.
SettingsOverrides parse_settings_text(const std::string& text, const std::string& origin);

// Every key of [output] and [shadow], every key of [camera], and [sun] when `sun` is not
// null. The debug view has no config key and is not written.
std::string format_settings_file(const RenderSettings& settings, const Camera& camera, const Light* sun);

// Writes format_settings_file() to `path` atomically (a temporary file renamed into place).
// Throws InputError when the file cannot be written.
void write_settings_file(const std::filesystem::path& path, const RenderSettings& settings, const Camera& camera,
                         const Light* sun);

}  // namespace penumbra

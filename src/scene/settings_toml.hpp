#pragma once
// Render settings from TOML: the [output] and [shadow] tables of a scene file, and
// config files (--config) which may also hold [camera] and [sun] overrides.
#include <filesystem>
#include <string>

#include "core/settings_overrides.hpp"

namespace penumbra {

// Reads [output] and [shadow] from a scene file (other tables are the scene parser's).
SettingsOverrides load_settings_from_scene_file(const std::filesystem::path& scene_file);

// Reads a config file: [output], [shadow], [camera], [sun]; any other table or key is an error.
SettingsOverrides load_settings_file(const std::filesystem::path& config_file);

// Reads config-file text (the tables and keys of load_settings_file); errors name `origin`.
SettingsOverrides parse_settings_text(const std::string& text, const std::string& origin);

}  // namespace penumbra

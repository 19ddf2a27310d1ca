#include "penumbra/scene/setting_presentation.hpp"
#include "penumbra/scene/settings_files.hpp"

#include <cstdint>
#include <functional>
#include <map>

#include "penumbra/errors.hpp"
#include "penumbra/settings.hpp"
#include "scene/toml_fields.hpp"

namespace penumbra {
namespace {

// Every reader below reads all the keys its table may hold and then rejects the others, so
// that the error for a typo lists the keys the table understands.

// A setting's value as its declaration's type reads from TOML, checked against the
// declaration (so a message names the table's key and the allowed values).
std::optional<SettingValue> read_setting(TomlTableReader& reader, const SettingDeclaration& setting) {
    const char* key = presentation_of(setting).key_in_config();
    std::optional<SettingValue> value;
    switch (setting.type) {
        case SettingType::Boolean:
            if (const std::optional<bool> read = reader.optional_boolean(key)) value = *read;
            break;
        case SettingType::Integer:
            if (const std::optional<int64_t> read = reader.optional_integer(key, INT64_MIN, INT64_MAX)) value = *read;
            break;
        case SettingType::Number:
            if (const std::optional<double> read = reader.optional_number(key)) value = *read;
            break;
        case SettingType::Choice:
            if (std::optional<std::string> read = reader.optional_string(key)) value = std::move(*read);
            break;
        case SettingType::NumberList:
            if (std::optional<std::vector<float>> read = reader.optional_number_list(key)) value = std::move(*read);
            break;
    }
    if (value) {
        if (const std::string problem = setting_value_problem(setting, *value); !problem.empty()) {
            reader.fail(key, problem);
        }
    }
    return value;
}

// [output]: the tools' settings (kOutputSettingDeclarations).
void read_output_table(TomlTableReader& reader, SettingsOverrides& o) {
    for (const SettingDeclaration& setting : kOutputSettingDeclarations) {
        if (std::optional<SettingValue> value = read_setting(reader, setting))
            o.settings.assign(setting, std::move(*value));
    }
    reader.reject_unknown_keys();
}

// [shadow]: every setting of kSettingDeclarations, by its config key.
void read_shadow_table(TomlTableReader& reader, SettingsOverrides& o) {
    for (const SettingDeclaration& setting : kSettingDeclarations) {
        if (std::optional<SettingValue> value = read_setting(reader, setting))
            o.settings.assign(setting, std::move(*value));
    }
    reader.reject_unknown_keys();
}

void read_camera_table(TomlTableReader& reader, SettingsOverrides& o) {
    o.eye = reader.optional_vec3("eye");
    o.target = reader.optional_vec3("target");
    o.up = reader.optional_vec3("up");
    o.fov = reader.optional_float("fov");
    o.near_plane = reader.optional_float("near");
    o.far_plane = reader.optional_float("far");
    reader.reject_unknown_keys();
}

void read_sun_table(TomlTableReader& reader, SettingsOverrides& o) {
    o.light_direction = reader.optional_vec3("direction");
    o.angular_diameter = reader.optional_float("angular_diameter");
    reader.reject_unknown_keys();
}

using TableHandler = std::function<void(TomlTableReader&, SettingsOverrides&)>;

// Runs the handler of each table present; with `reject_other_tables`, any other top-level
// key or table is an error (a scene file's other tables belong to the scene parser).
SettingsOverrides read_tables(const toml::table& root, const std::string& origin,
                              const std::map<std::string, TableHandler>& handlers, bool reject_other_tables) {
    SettingsOverrides overrides;
    TomlTableReader root_reader(root, origin, "");
    for (const auto& [name, handler] : handlers) {
        if (const toml::table* table = root_reader.optional_table(name)) {
            TomlTableReader reader(*table, origin, name);
            handler(reader, overrides);
        }
    }
    if (reject_other_tables) root_reader.reject_unknown_keys("table or key");
    return overrides;
}

const std::map<std::string, TableHandler>& config_file_tables() {
    static const std::map<std::string, TableHandler> tables{{"output", read_output_table},
                                                            {"shadow", read_shadow_table},
                                                            {"camera", read_camera_table},
                                                            {"sun", read_sun_table}};
    return tables;
}

}  // namespace

SettingsOverrides load_settings_from_scene_file(const std::filesystem::path& scene_file) {
    return read_tables(parse_toml_file(scene_file, "scene file"), scene_file.string(),
                       {{"output", read_output_table}, {"shadow", read_shadow_table}}, false);
}

SettingsOverrides load_settings_file(const std::filesystem::path& config_file) {
    return read_tables(parse_toml_file(config_file, "config file"), config_file.string(), config_file_tables(), true);
}

SettingsOverrides parse_settings_text(const std::string& text, const std::string& origin) {
    // `origin` names the line of a larger file (a viewer script): positions inside the
    // text would mislead.
    return read_tables(parse_toml_text(text, origin, false), origin, config_file_tables(), true);
}

}  // namespace penumbra

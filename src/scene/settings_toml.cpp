#include "penumbra/scene/settings_files.hpp"

#include <functional>
#include <map>

#include "penumbra/errors.hpp"
#include "penumbra/settings.hpp"
#include "scene/toml_fields.hpp"

namespace penumbra {
namespace {

// Every reader below reads all the keys its table may hold and then rejects the others, so
// that the error for a typo lists the keys the table understands.
void read_output_table(TomlTableReader& reader, SettingsOverrides& o) {
    o.width = reader.optional_integer_as<uint32_t>("width", 1, kMaxImageSize);
    o.height = reader.optional_integer_as<uint32_t>("height", 1, kMaxImageSize);
    o.resolve = reader.optional_choice<ShadowResolve>("resolve", shadow_resolve_names());
    reader.reject_unknown_keys();
}

// The filter keys of [shadow] (docs/filters.md). Their ranges are checked by
// validate_shadow_settings, which names the same keys.
void read_filter_keys(TomlTableReader& reader, FilterOverrides& f) {
    namespace k = shadow_keys;
    f.mode = reader.optional_choice<ShadowFilter>(k::kFilter, shadow_filter_names());
    f.receiver_plane_bias = reader.optional_boolean(k::kReceiverPlaneBias);
    f.pcf_radius = reader.optional_integer_as<int>(k::kPcfRadius);
    f.poisson_taps = reader.optional_integer_as<int>(k::kPoissonTaps);
    f.poisson_radius = reader.optional_float(k::kPoissonRadius);
    f.pcss_blocker_taps = reader.optional_integer_as<int>(k::kPcssBlockerTaps);
    f.pcss_quality = reader.optional_choice<PcssQuality>(k::kPcssQuality, pcss_quality_names());
    f.pcss_early_out = reader.optional_boolean(k::kPcssEarlyOut);
    f.pcss_max_penumbra = reader.optional_float(k::kPcssMaxPenumbra);
    f.light_bleeding_reduction = reader.optional_float(k::kLightBleeding);
    f.blur_radius = reader.optional_integer_as<int>(k::kBlurRadius);
    f.moments_poisson = reader.optional_boolean(k::kMomentsPoisson);
    f.evsm_positive_exponent = reader.optional_float(k::kEvsmPositiveExponent);
    f.evsm_negative_exponent = reader.optional_float(k::kEvsmNegativeExponent);
    f.evsm_components = reader.optional_integer_as<int>(k::kEvsmComponents);
    f.msm_moment_bias = reader.optional_float(k::kMsmMomentBias);
    f.msm_optimized_quantization = reader.optional_boolean(k::kMsmQuantization);
}

void read_shadow_table(TomlTableReader& reader, SettingsOverrides& o) {
    o.cascades = reader.optional_integer_as<int>("cascades", 1, 8);
    o.shadow_resolution = reader.optional_integer_as<uint32_t>("resolution", 512, 8192);
    o.split_scheme = reader.optional_choice<SplitScheme>("split_scheme", split_scheme_names());
    o.split_lambda = reader.optional_float("split_lambda");
    o.splits = reader.optional_number_list("splits");
    o.max_distance = reader.optional_float("max_distance");
    o.fit = reader.optional_choice<FitMode>("fit", fit_mode_names());
    o.constant_bias = reader.optional_float("constant_bias");
    o.slope_bias = reader.optional_float("slope_bias");
    o.bias_clamp = reader.optional_float("bias_clamp");
    o.normal_offset = reader.optional_float("normal_offset");
    o.blend_width = reader.optional_float("blend_width");
    o.strategy = reader.optional_choice<ShadowStrategy>("strategy", shadow_strategy_names());
    o.cull_casters = reader.optional_boolean("cull_casters");
    o.caster_culling = reader.optional_choice<CasterCulling>("caster_culling", caster_culling_names());
    // Spot and point lights (docs/local-lights.md); the ranges of the flags of the same names.
    o.local_shadow_budget = reader.optional_integer_as<uint32_t>("local_shadow_budget", 0, kMaxLocalShadowBudget);
    o.local_shadow_resolution = reader.optional_integer_as<uint32_t>("local_shadow_resolution", 16, 8192);
    o.local_shadow_sizing =
        reader.optional_choice<LocalShadowSizing>("local_shadow_sizing", local_shadow_sizing_names());
    read_filter_keys(reader, o.filter);
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
    return read_tables(parse_toml_file(scene_file), scene_file.string(),
                       {{"output", read_output_table}, {"shadow", read_shadow_table}}, false);
}

SettingsOverrides load_settings_file(const std::filesystem::path& config_file) {
    if (!std::filesystem::is_regular_file(config_file)) {
        throw InputError(config_file.string() + ": config file not found");
    }
    return read_tables(parse_toml_file(config_file), config_file.string(), config_file_tables(), true);
}

SettingsOverrides parse_settings_text(const std::string& text, const std::string& origin) {
    // `origin` names the line of a larger file (a viewer script): positions inside the
    // text would mislead.
    return read_tables(parse_toml_text(text, origin, false), origin, config_file_tables(), true);
}

}  // namespace penumbra

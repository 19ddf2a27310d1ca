#include "scene/settings_toml.hpp"

#include <toml++/toml.h>

#include <functional>
#include <map>
#include <set>

#include "core/errors.hpp"
#include "core/shadow_filters.hpp"

namespace penumbra {
namespace {

// Reads typed values out of one TOML table, naming "<file>: <table>.<key>" in errors.
class TableReader {
public:
    TableReader(const toml::table& table, std::string origin, std::string prefix)
        : table_(table), origin_(std::move(origin)), prefix_(std::move(prefix)) {}

    std::string where(const std::string& key) const { return origin_ + ": " + prefix_ + "." + key; }

    void reject_unknown_keys(const std::set<std::string>& known) const {
        for (const auto& [key, value] : table_) {
            if (!known.contains(std::string(key.str()))) {
                throw InputError(where(std::string(key.str())) + ": unknown key");
            }
        }
    }

    std::optional<double> number(const std::string& key) const {
        const toml::node* node = table_.get(key);
        if (!node) return std::nullopt;
        if (auto value = node->value<double>(); value && (node->is_integer() || node->is_floating_point())) {
            return *value;
        }
        throw InputError(where(key) + ": expected a number");
    }

    std::optional<float> real(const std::string& key) const {
        auto value = number(key);
        return value ? std::optional<float>(static_cast<float>(*value)) : std::nullopt;
    }

    template <typename Integer>
    std::optional<Integer> integer(const std::string& key, int64_t min, int64_t max) const {
        const toml::node* node = table_.get(key);
        if (!node) return std::nullopt;
        if (!node->is_integer()) throw InputError(where(key) + ": expected an integer");
        const int64_t value = *node->value<int64_t>();
        if (value < min || value > max) {
            throw InputError(where(key) + ": " + std::to_string(value) + " is out of range (" + std::to_string(min) +
                             ".." + std::to_string(max) + ")");
        }
        return static_cast<Integer>(value);
    }

    std::optional<bool> boolean(const std::string& key) const {
        const toml::node* node = table_.get(key);
        if (!node) return std::nullopt;
        if (!node->is_boolean()) throw InputError(where(key) + ": expected true or false");
        return *node->value<bool>();
    }

    std::optional<std::vector<float>> numbers(const std::string& key) const {
        const toml::node* node = table_.get(key);
        if (!node) return std::nullopt;
        const toml::array* array = node->as_array();
        if (!array) throw InputError(where(key) + ": expected an array of numbers");
        std::vector<float> values;
        for (const toml::node& element : *array) {
            if (!element.is_integer() && !element.is_floating_point()) {
                throw InputError(where(key) + ": expected an array of numbers");
            }
            values.push_back(static_cast<float>(*element.value<double>()));
        }
        return values;
    }

    std::optional<glm::vec3> vec3(const std::string& key) const {
        auto values = numbers(key);
        if (!values) return std::nullopt;
        if (values->size() != 3) throw InputError(where(key) + ": expected 3 numbers [x, y, z]");
        return glm::vec3((*values)[0], (*values)[1], (*values)[2]);
    }

    template <typename Enum>
    std::optional<Enum> choice(const std::string& key, const std::map<std::string, Enum>& choices) const {
        const toml::node* node = table_.get(key);
        if (!node) return std::nullopt;
        if (!node->is_string()) throw InputError(where(key) + ": expected a string");
        const std::string text = *node->value<std::string>();
        const auto found = choices.find(text);
        if (found != choices.end()) return found->second;
        std::string names;
        for (const auto& [name, value] : choices) names += (names.empty() ? "" : ", ") + name;
        throw InputError(where(key) + ": unknown value \"" + text + "\" (expected " + names + ")");
    }

private:
    const toml::table& table_;
    std::string origin_;
    std::string prefix_;
};

toml::table parse_file(const std::filesystem::path& path) {
    try {
        return toml::parse_file(path.string());
    } catch (const toml::parse_error& error) {
        const auto& begin = error.source().begin;
        throw InputError(path.string() + ":" + std::to_string(begin.line) + ":" + std::to_string(begin.column) +
                         ": malformed TOML: " + std::string(error.description()));
    }
}

const toml::table* subtable(const toml::table& root, const std::string& name, const std::string& origin) {
    const toml::node* node = root.get(name);
    if (!node) return nullptr;
    if (!node->is_table()) throw InputError(origin + ": " + name + ": expected a table [" + name + "]");
    return node->as_table();
}

void read_output_table(const TableReader& reader, SettingsOverrides& o) {
    reader.reject_unknown_keys({"width", "height"});
    o.width = reader.integer<uint32_t>("width", 1, kMaxImageSize);
    o.height = reader.integer<uint32_t>("height", 1, kMaxImageSize);
}

// The filter keys of [shadow] (docs/filters.md). Ranges are checked by
// validate_shadow_settings, which names the same keys.
const std::set<std::string>& filter_keys() {
    namespace k = shadow_keys;
    static const std::set<std::string> keys{k::kFilter,
                                            k::kReceiverPlaneBias,
                                            k::kPcfRadius,
                                            k::kPoissonTaps,
                                            k::kPoissonRadius,
                                            k::kPcssBlockerTaps,
                                            k::kPcssQuality,
                                            k::kPcssEarlyOut,
                                            k::kPcssMaxPenumbra,
                                            k::kLightBleeding,
                                            k::kBlurRadius,
                                            k::kMomentsPoisson,
                                            k::kEvsmPositiveExponent,
                                            k::kEvsmNegativeExponent,
                                            k::kEvsmComponents,
                                            k::kMsmMomentBias,
                                            k::kMsmQuantization};
    return keys;
}

void read_filter_keys(const TableReader& reader, FilterOverrides& f) {
    namespace k = shadow_keys;
    constexpr int64_t kAnyInt = 1 << 30;  // range errors come from validate_shadow_settings
    f.mode = reader.choice<ShadowFilter>(k::kFilter, shadow_filter_names());
    f.receiver_plane_bias = reader.boolean(k::kReceiverPlaneBias);
    f.pcf_radius = reader.integer<int>(k::kPcfRadius, -kAnyInt, kAnyInt);
    f.poisson_taps = reader.integer<int>(k::kPoissonTaps, -kAnyInt, kAnyInt);
    f.poisson_radius = reader.real(k::kPoissonRadius);
    f.pcss_blocker_taps = reader.integer<int>(k::kPcssBlockerTaps, -kAnyInt, kAnyInt);
    f.pcss_quality = reader.choice<PcssQuality>(k::kPcssQuality, pcss_quality_names());
    f.pcss_early_out = reader.boolean(k::kPcssEarlyOut);
    f.pcss_max_penumbra = reader.real(k::kPcssMaxPenumbra);
    f.light_bleeding_reduction = reader.real(k::kLightBleeding);
    f.blur_radius = reader.integer<int>(k::kBlurRadius, -kAnyInt, kAnyInt);
    f.moments_poisson = reader.boolean(k::kMomentsPoisson);
    f.evsm_positive_exponent = reader.real(k::kEvsmPositiveExponent);
    f.evsm_negative_exponent = reader.real(k::kEvsmNegativeExponent);
    f.evsm_components = reader.integer<int>(k::kEvsmComponents, -kAnyInt, kAnyInt);
    f.msm_moment_bias = reader.real(k::kMsmMomentBias);
    f.msm_optimized_quantization = reader.boolean(k::kMsmQuantization);
}

void read_shadow_table(const TableReader& reader, SettingsOverrides& o) {
    std::set<std::string> known{"cascades",      "resolution",  "split_scheme",  "split_lambda", "splits",
                                "max_distance",  "fit",         "constant_bias", "slope_bias",   "bias_clamp",
                                "normal_offset", "blend_width", "strategy",      "cull_casters"};
    known.insert(filter_keys().begin(), filter_keys().end());
    reader.reject_unknown_keys(known);
    read_filter_keys(reader, o.filter);
    o.cascades = reader.integer<int>("cascades", 1, 8);
    o.shadow_resolution = reader.integer<uint32_t>("resolution", 512, 8192);
    o.split_scheme = reader.choice<SplitScheme>("split_scheme", {{"uniform", SplitScheme::Uniform},
                                                                 {"log", SplitScheme::Logarithmic},
                                                                 {"practical", SplitScheme::Practical},
                                                                 {"manual", SplitScheme::Manual}});
    o.split_lambda = reader.real("split_lambda");
    o.splits = reader.numbers("splits");
    o.max_distance = reader.real("max_distance");
    o.fit = reader.choice<FitMode>("fit", {{"stable", FitMode::Stable}, {"tight", FitMode::Tight}});
    o.constant_bias = reader.real("constant_bias");
    o.slope_bias = reader.real("slope_bias");
    o.bias_clamp = reader.real("bias_clamp");
    o.normal_offset = reader.real("normal_offset");
    o.blend_width = reader.real("blend_width");
    o.strategy = reader.choice<ShadowStrategy>(
        "strategy", {{"per-cascade", ShadowStrategy::PerCascade}, {"multiview", ShadowStrategy::Multiview}});
    o.cull_casters = reader.boolean("cull_casters");
}

void read_camera_table(const TableReader& reader, SettingsOverrides& o) {
    reader.reject_unknown_keys({"eye", "target", "up", "fov", "near", "far"});
    o.eye = reader.vec3("eye");
    o.target = reader.vec3("target");
    o.up = reader.vec3("up");
    o.fov = reader.real("fov");
    o.near_plane = reader.real("near");
    o.far_plane = reader.real("far");
}

void read_sun_table(const TableReader& reader, SettingsOverrides& o) {
    reader.reject_unknown_keys({"direction", "angular_diameter"});
    o.light_direction = reader.vec3("direction");
    o.angular_diameter = reader.real("angular_diameter");
}

using TableHandler = std::function<void(const TableReader&, SettingsOverrides&)>;

SettingsOverrides read_tables(const toml::table& root, const std::string& origin,
                              const std::map<std::string, TableHandler>& handlers, bool reject_other_tables) {
    SettingsOverrides overrides;
    for (const auto& [key, node] : root) {
        const std::string name(key.str());
        const auto handler = handlers.find(name);
        if (handler == handlers.end()) {
            if (reject_other_tables) throw InputError(origin + ": " + name + ": unknown table or key");
            continue;
        }
        handler->second(TableReader(*subtable(root, name, origin), origin, name), overrides);
    }
    return overrides;
}

SettingsOverrides read_tables(const std::filesystem::path& path, const std::map<std::string, TableHandler>& handlers,
                              bool reject_other_tables) {
    return read_tables(parse_file(path), path.string(), handlers, reject_other_tables);
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
    return read_tables(scene_file, {{"output", read_output_table}, {"shadow", read_shadow_table}}, false);
}

SettingsOverrides load_settings_file(const std::filesystem::path& config_file) {
    if (!std::filesystem::is_regular_file(config_file)) {
        throw InputError(config_file.string() + ": config file not found");
    }
    return read_tables(config_file, config_file_tables(), true);
}

SettingsOverrides parse_settings_text(const std::string& text, const std::string& origin) {
    toml::table root;
    try {
        root = toml::parse(text, origin);
    } catch (const toml::parse_error& error) {
        throw InputError(origin + ": malformed TOML: " + std::string(error.description()));
    }
    return read_tables(root, origin, config_file_tables(), true);
}

}  // namespace penumbra

#pragma once
// Checked, typed reads from one table of a TOML file (a scene or a config file). Every
// problem becomes one InputError line "<origin>: <key path>: <problem, with the offending
// value>", and every key the parser asks about is remembered, so that reject_unknown_keys()
// turns a typo ("colour", or "radius" on a box) into an error instead of a silently ignored
// setting.
#include <concepts>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include <glm/glm.hpp>

namespace penumbra {

// Throws InputError("<origin>: <key_path>: <problem>").
[[noreturn]] void throw_scene_error(const std::string& origin, const std::string& key_path, const std::string& problem);

// `value` with up to 7 significant digits, as a user would write it ("0.1", "180", "-2.5").
std::string format_number(double value);

// "a string \"cone\"", "an array [1, 2]"...: the offending value for an error message.
std::string describe_toml_value(const toml::node& node);

// Parses TOML text. A syntax error becomes one InputError line
// "<origin>:<line>:<column>: malformed TOML: <description>" (without the position when
// `with_position` is false, for text that is itself one line of a larger file).
toml::table parse_toml_text(std::string_view text, const std::string& origin, bool with_position = true);

// The whole of a regular file; throws InputError "<origin>: <kind> not found", "<origin>: not
// a regular file" (a folder, FIFO or device) or "<origin>: cannot be read: <reason>".
std::string read_text_file(const std::filesystem::path& file, const std::string& origin, std::string_view kind);

// Reads (as read_text_file) and parses a TOML file; errors name the file as parse_toml_text()
// does.
toml::table parse_toml_file(const std::filesystem::path& file, std::string_view kind);

class TomlTableReader {
public:
    // `path` is the table's key path ("camera", "objects[2]"), empty for the root.
    TomlTableReader(const toml::table& table, std::string origin, std::string path);

    const std::string& origin() const { return origin_; }
    // "camera.fov", or "fov" at the root.
    std::string key_path(std::string_view key) const;
    [[noreturn]] void fail(std::string_view key, const std::string& problem) const;

    bool contains(std::string_view key);
    // Marks a key as valid without reading it (tables parsed by another layer).
    void accept(std::string_view key);

    std::optional<std::string> optional_string(std::string_view key);
    std::string required_string(std::string_view key);
    std::optional<double> optional_number(std::string_view key);  // integers accepted; finite only
    std::optional<float> optional_float(std::string_view key);
    float number_or(std::string_view key, float fallback);
    // An integer (2.0 is not one) in [min, max].
    std::optional<int64_t> optional_integer(std::string_view key, int64_t min, int64_t max);
    template <std::integral Integer>
    std::optional<Integer> optional_integer_as(std::string_view key, int64_t min = std::numeric_limits<Integer>::min(),
                                               int64_t max = std::numeric_limits<Integer>::max()) {
        const std::optional<int64_t> value = optional_integer(key, min, max);
        return value ? std::optional<Integer>(static_cast<Integer>(*value)) : std::nullopt;
    }
    std::optional<bool> optional_boolean(std::string_view key);
    bool boolean_or(std::string_view key, bool fallback);
    // A string naming one of `choices` (the error lists them all).
    template <typename Enum>
    std::optional<Enum> optional_choice(std::string_view key, const std::map<std::string, Enum>& choices) {
        const std::optional<std::string> name = optional_string(key);
        if (!name) return std::nullopt;
        if (const auto found = choices.find(*name); found != choices.end()) return found->second;
        std::vector<std::string> names;
        for (const auto& choice : choices) names.push_back(choice.first);
        fail_unknown_value(key, *name, names);
    }
    // An array of strings (possibly empty).
    std::optional<std::vector<std::string>> optional_string_list(std::string_view key);
    // An array of any number of numbers.
    std::optional<std::vector<float>> optional_number_list(std::string_view key);
    // An array of exactly N numbers.
    std::optional<glm::vec2> optional_vec2(std::string_view key);
    std::optional<glm::vec3> optional_vec3(std::string_view key);
    glm::vec3 vec3_or(std::string_view key, const glm::vec3& fallback);
    // A number s (meaning [s, s, s]) or an array of 3 numbers.
    std::optional<glm::vec3> optional_vec3_or_scalar(std::string_view key);
    // [r, g, b] (alpha 1) or [r, g, b, a].
    glm::vec4 color_or(std::string_view key, const glm::vec4& fallback);

    const toml::table* optional_table(std::string_view key);
    // An array whose elements are all tables ([[objects]] or inline tables); empty if absent.
    std::vector<const toml::table*> table_array(std::string_view key);

    // Throws for the first key of the table that no read or accept() asked about,
    // listing the keys this table understands: "<key path>: unknown <what> \"<key>\" (expected ...)".
    void reject_unknown_keys(std::string_view what = "key") const;

private:
    const toml::node* find(std::string_view key);
    [[noreturn]] void fail_unknown_value(std::string_view key, const std::string& value,
                                         const std::vector<std::string>& expected) const;
    std::vector<double> number_array(std::string_view key, const toml::array& array, size_t min_size,
                                     size_t max_size) const;

    const toml::table& table_;
    std::string origin_;
    std::string path_;
    std::vector<std::string> known_keys_;
};

}  // namespace penumbra

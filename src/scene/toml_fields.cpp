#include "scene/toml_fields.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

#include "penumbra/errors.hpp"
#include "penumbra/scene/scene.hpp"

namespace penumbra {
namespace {

constexpr size_t kAnySize = std::numeric_limits<size_t>::max();
constexpr const char* kMagnitudeLimitText = "1e9 in magnitude, the largest Penumbra's 32-bit float math carries";

std::string quote(std::string_view text) {
    std::string result = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') result += '\\';
        // Control characters (a newline inside a value) would break the one-line message.
        result += (static_cast<unsigned char>(c) < 0x20) ? '?' : c;
    }
    return result + "\"";
}

std::string join_keys(const std::vector<std::string>& keys) {
    std::string result;
    for (size_t i = 0; i < keys.size(); ++i) result += (i == 0 ? "" : ", ") + keys[i];
    return result;
}

std::string value_text(const toml::node& node) {
    if (const auto* text = node.as_string()) return quote(text->get());
    if (const auto* integer = node.as_integer()) return std::to_string(integer->get());
    if (const auto* floating = node.as_floating_point()) return format_number(floating->get());
    if (const auto* boolean = node.as_boolean()) return boolean->get() ? "true" : "false";
    if (const auto* array = node.as_array()) {
        std::string result = "[";
        for (size_t i = 0; i < array->size(); ++i) result += (i == 0 ? "" : ", ") + value_text(*array->get(i));
        return result + "]";
    }
    if (node.is_table()) return "{...}";
    std::ostringstream text;
    if (const auto* date = node.as_date()) text << *date;
    if (const auto* time = node.as_time()) text << *time;
    if (const auto* date_time = node.as_date_time()) text << *date_time;
    return text.str();
}

std::string type_name(const toml::node& node) {
    switch (node.type()) {
        case toml::node_type::string:
            return "a string";
        case toml::node_type::integer:
        case toml::node_type::floating_point:
            return "a number";
        case toml::node_type::boolean:
            return "a boolean";
        case toml::node_type::array:
            return "an array";
        case toml::node_type::table:
            return "a table";
        default:
            return "a date/time";
    }
}

// A TOML number as a double. toml++'s value<double>() is empty for an integer a double
// cannot hold exactly (beyond 2^53), so integers are converted here, rounded: every such
// integer is far beyond the 1e9 limit that the callers then apply.
std::optional<double> number_as_double(const toml::node& node) {
    if (const auto* integer = node.as_integer()) return static_cast<double>(integer->get());
    if (const auto* floating = node.as_floating_point()) return floating->get();
    return std::nullopt;
}

[[noreturn]] void throw_parse_error(const toml::parse_error& error, const std::string& origin, bool with_position) {
    std::string description(error.description());
    // toml++ descriptions may span lines; the message must stay one line.
    for (char& c : description) {
        if (c == '\n' || c == '\r') c = ' ';
    }
    const toml::source_position where = error.source().begin;
    const std::string position =
        with_position ? ":" + std::to_string(where.line) + ":" + std::to_string(where.column) : "";
    throw InputError(origin + position + ": malformed TOML: " + description);
}

}  // namespace

toml::table parse_toml_text(std::string_view text, const std::string& origin, bool with_position) {
    try {
        return toml::parse(text, origin);
    } catch (const toml::parse_error& error) {
        throw_parse_error(error, origin, with_position);
    }
}

std::string read_text_file(const std::filesystem::path& file, const std::string& origin, std::string_view kind) {
    std::error_code error;
    const std::filesystem::file_status status = std::filesystem::status(file, error);
    if (!std::filesystem::exists(status)) throw InputError(origin + ": " + std::string(kind) + " not found");
    // A FIFO or a device (/dev/zero) would block the read, or never end it.
    if (!std::filesystem::is_regular_file(status)) throw InputError(origin + ": not a regular file");
    std::ifstream stream(file, std::ios::binary);
    if (!stream) throw InputError(origin + ": cannot be read: " + std::strerror(errno));
    std::ostringstream text;
    text << stream.rdbuf();
    if (stream.bad()) throw InputError(origin + ": cannot be read: " + std::strerror(errno));
    return text.str();
}

toml::table parse_toml_file(const std::filesystem::path& file, std::string_view kind) {
    return parse_toml_text(read_text_file(file, file.string(), kind), file.string());
}

void throw_scene_error(const std::string& origin, const std::string& key_path, const std::string& problem) {
    throw InputError(origin + ": " + key_path + ": " + problem);
}

std::string format_number(double value) {
    std::ostringstream text;
    // Values end up as floats: 7 significant digits print 0.1f as "0.1", not "0.100000001".
    text.precision(7);
    text << value;
    return text.str();
}

std::string describe_toml_value(const toml::node& node) {
    if (node.is_table()) return "a table";
    return type_name(node) + " " + value_text(node);
}

TomlTableReader::TomlTableReader(const toml::table& table, std::string origin, std::string path)
    : table_(table), origin_(std::move(origin)), path_(std::move(path)) {}

std::string TomlTableReader::key_path(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void TomlTableReader::fail(std::string_view key, const std::string& problem) const {
    throw_scene_error(origin_, key_path(key), problem);
}

const toml::node* TomlTableReader::find(std::string_view key) {
    accept(key);
    return table_.get(key);
}

bool TomlTableReader::contains(std::string_view key) { return find(key) != nullptr; }

void TomlTableReader::accept(std::string_view key) {
    if (std::find(known_keys_.begin(), known_keys_.end(), key) == known_keys_.end()) known_keys_.emplace_back(key);
}

std::optional<std::string> TomlTableReader::optional_string(std::string_view key) {
    const toml::node* node = find(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_string()) fail(key, "expected a string, got " + describe_toml_value(*node));
    return node->as_string()->get();
}

std::string TomlTableReader::required_string(std::string_view key) {
    std::optional<std::string> text = optional_string(key);
    if (!text) fail(key, "missing (a string is required)");
    return *text;
}

std::optional<double> TomlTableReader::optional_number(std::string_view key) {
    const toml::node* node = find(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_number()) fail(key, "expected a number, got " + describe_toml_value(*node));
    const double value = *number_as_double(*node);
    if (!std::isfinite(value)) fail(key, "expected a finite number, got " + value_text(*node));
    if (std::abs(value) > kMaxNumberMagnitude) fail(key, value_text(*node) + " is beyond " + kMagnitudeLimitText);
    return value;
}

std::optional<float> TomlTableReader::optional_float(std::string_view key) {
    const std::optional<double> value = optional_number(key);
    return value ? std::optional<float>(static_cast<float>(*value)) : std::nullopt;
}

float TomlTableReader::number_or(std::string_view key, float fallback) {
    return static_cast<float>(optional_number(key).value_or(fallback));
}

std::optional<int64_t> TomlTableReader::optional_integer(std::string_view key, int64_t min, int64_t max) {
    const toml::node* node = find(key);
    if (node == nullptr) return std::nullopt;
    if (const auto* floating = node->as_floating_point()) {
        std::ostringstream text;  // toml++ writes 2.0 as "2.0", which says why it is not an integer
        text << *floating;
        fail(key, "expected an integer, got " + text.str());
    }
    if (!node->is_integer()) fail(key, "expected an integer, got " + describe_toml_value(*node));
    const int64_t value = node->as_integer()->get();
    if (value < min || value > max) {
        fail(key,
             std::to_string(value) + " is out of range (" + std::to_string(min) + ".." + std::to_string(max) + ")");
    }
    return value;
}

std::optional<bool> TomlTableReader::optional_boolean(std::string_view key) {
    const toml::node* node = find(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_boolean()) fail(key, "expected true or false, got " + describe_toml_value(*node));
    return node->as_boolean()->get();
}

bool TomlTableReader::boolean_or(std::string_view key, bool fallback) {
    return optional_boolean(key).value_or(fallback);
}

void TomlTableReader::fail_unknown_value(std::string_view key, const std::string& value,
                                         const std::vector<std::string>& expected) const {
    fail(key, "unknown value " + quote(value) + " (expected " + join_keys(expected) + ")");
}

std::vector<double> TomlTableReader::number_array(std::string_view key, const toml::array& array, size_t min_size,
                                                  size_t max_size) const {
    std::string expected = "an array of " + std::to_string(min_size) + " to " + std::to_string(max_size) + " numbers";
    if (min_size == max_size) expected = "an array of " + std::to_string(min_size) + " numbers";
    if (min_size == 0 && max_size == kAnySize) expected = "an array of numbers";
    if (array.size() < min_size || array.size() > max_size) {
        fail(key, "expected " + expected + ", got " + describe_toml_value(array));
    }
    std::vector<double> values;
    for (const toml::node& element : array) {
        const std::optional<double> value = number_as_double(element);
        if (!value || !std::isfinite(*value)) fail(key, "expected " + expected + ", got " + describe_toml_value(array));
        if (std::abs(*value) > kMaxNumberMagnitude) {
            fail(key, value_text(element) + " is beyond " + kMagnitudeLimitText);
        }
        values.push_back(*value);
    }
    return values;
}

std::optional<glm::vec2> TomlTableReader::optional_vec2(std::string_view key) {
    const toml::node* node = find(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_array()) fail(key, "expected an array of 2 numbers, got " + describe_toml_value(*node));
    const std::vector<double> values = number_array(key, *node->as_array(), 2, 2);
    return glm::vec2{values[0], values[1]};
}

std::optional<glm::vec3> TomlTableReader::optional_vec3(std::string_view key) {
    const toml::node* node = find(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_array()) fail(key, "expected an array of 3 numbers, got " + describe_toml_value(*node));
    const std::vector<double> values = number_array(key, *node->as_array(), 3, 3);
    return glm::vec3{values[0], values[1], values[2]};
}

std::optional<std::vector<float>> TomlTableReader::optional_number_list(std::string_view key) {
    const toml::node* node = find(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_array()) fail(key, "expected an array of numbers, got " + describe_toml_value(*node));
    const std::vector<double> values = number_array(key, *node->as_array(), 0, kAnySize);
    return std::vector<float>(values.begin(), values.end());
}

std::optional<std::vector<std::string>> TomlTableReader::optional_string_list(std::string_view key) {
    const toml::node* node = find(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_array()) fail(key, "expected an array of strings, got " + describe_toml_value(*node));
    std::vector<std::string> strings;
    for (const toml::node& element : *node->as_array()) {
        if (!element.is_string()) {
            fail(key, "expected an array of strings, element " + std::to_string(strings.size()) + " is " +
                          describe_toml_value(element));
        }
        strings.push_back(element.as_string()->get());
    }
    return strings;
}

glm::vec3 TomlTableReader::vec3_or(std::string_view key, const glm::vec3& fallback) {
    return optional_vec3(key).value_or(fallback);
}

std::optional<glm::vec3> TomlTableReader::optional_vec3_or_scalar(std::string_view key) {
    const toml::node* node = find(key);
    if (node != nullptr && node->is_number()) return glm::vec3{static_cast<float>(*optional_number(key))};
    if (node != nullptr && !node->is_array()) {
        fail(key, "expected a number or an array of 3 numbers, got " + describe_toml_value(*node));
    }
    return optional_vec3(key);
}

glm::vec4 TomlTableReader::color_or(std::string_view key, const glm::vec4& fallback) {
    const toml::node* node = find(key);
    if (node == nullptr) return fallback;
    if (!node->is_array()) fail(key, "expected an array of 3 or 4 numbers, got " + describe_toml_value(*node));
    const std::vector<double> values = number_array(key, *node->as_array(), 3, 4);
    return glm::vec4{values[0], values[1], values[2], values.size() == 4 ? values[3] : 1.0};
}

const toml::table* TomlTableReader::optional_table(std::string_view key) {
    const toml::node* node = find(key);
    if (node == nullptr) return nullptr;
    if (!node->is_table()) fail(key, "expected a table, got " + describe_toml_value(*node));
    return node->as_table();
}

std::vector<const toml::table*> TomlTableReader::table_array(std::string_view key) {
    const toml::node* node = find(key);
    if (node == nullptr) return {};
    const toml::array* array = node->as_array();
    if (array == nullptr)
        fail(key, "expected an array of tables ([[" + std::string(key) + "]]), got " + describe_toml_value(*node));
    std::vector<const toml::table*> tables;
    for (size_t i = 0; i < array->size(); ++i) {
        const toml::node& element = *array->get(i);
        if (!element.is_table()) {
            throw_scene_error(origin_, key_path(key) + "[" + std::to_string(i) + "]",
                              "expected a table, got " + describe_toml_value(element));
        }
        tables.push_back(element.as_table());
    }
    return tables;
}

void TomlTableReader::reject_unknown_keys(std::string_view what) const {
    for (const auto& [key, node] : table_) {
        const std::string_view name = key.str();
        if (std::find(known_keys_.begin(), known_keys_.end(), name) != known_keys_.end()) continue;
        fail(name, "unknown " + std::string(what) + " " + quote(name) + " (expected " + join_keys(known_keys_) + ")");
    }
}

}  // namespace penumbra

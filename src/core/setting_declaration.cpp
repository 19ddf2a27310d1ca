// The checks and descriptions every reader of a SettingDeclaration shares, so that a config
// file, a flag and the library's validation say the same thing about the same value.
#include "penumbra/setting_declaration.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "penumbra/settings.hpp"

namespace penumbra {
namespace {

// Numbers as the messages have always printed them: 6 significant digits.
std::string number_text(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

// A name from a file or a command line, quoted (errors escape control characters).
std::string quoted(const std::string& text) { return "\"" + text + "\""; }

std::string allowed_list(std::span<const int64_t> allowed, const char* last_separator) {
    std::string text;
    for (size_t i = 0; i < allowed.size(); ++i) {
        if (i > 0) text += i + 1 == allowed.size() ? last_separator : ", ";
        text += std::to_string(allowed[i]);
    }
    return text;
}

// Built with a stream: GCC 12 at -O3 warns (-Wrestrict, a false positive) about
// "literal" + std::string chains here.
std::string range_text(const SettingDeclaration& setting) {
    std::ostringstream text;
    text << "[" << setting.minimum << ", " << setting.maximum << "]";
    return text.str();
}

// Numbers are compared as the float fields they go to, so that a bound such as 0.1 accepts
// the float nearest 0.1; written as !(inside) so that NaN, which fails every comparison,
// is rejected.
std::string number_problem(const SettingDeclaration& setting, double value) {
    const float stored = static_cast<float>(value);
    const float minimum = static_cast<float>(setting.minimum);
    const float maximum = static_cast<float>(setting.maximum);
    if (setting.minimum_exclusive) {
        if (!(stored > minimum && stored <= maximum && std::isfinite(stored))) {
            return number_text(value) + " must be a finite number greater than " + number_text(setting.minimum);
        }
        return "";
    }
    if (!(stored >= minimum && stored <= maximum)) {
        return number_text(value) + " is outside the allowed range " + range_text(setting);
    }
    return "";
}

std::string integer_problem(const SettingDeclaration& setting, int64_t value) {
    if (!setting.allowed.empty()) {
        if (std::find(setting.allowed.begin(), setting.allowed.end(), value) != setting.allowed.end()) return "";
        return std::to_string(value) + " must be " + allowed_list(setting.allowed, " or ");
    }
    if (!(static_cast<double>(value) >= setting.minimum && static_cast<double>(value) <= setting.maximum)) {
        return std::to_string(value) + " is outside the allowed range " + range_text(setting);
    }
    return "";
}

std::string choice_problem(const SettingDeclaration& setting, const std::string& name) {
    if (std::find(setting.choices.begin(), setting.choices.end(), name) != setting.choices.end()) return "";
    std::vector<std::string> names(setting.choices.begin(), setting.choices.end());
    std::sort(names.begin(), names.end());
    std::string expected;
    for (const std::string& choice : names) {
        if (!expected.empty()) expected += ", ";
        expected += choice;
    }
    return "unknown value " + quoted(name) + " (expected " + expected + ")";
}

const char* type_name(SettingType type) {
    switch (type) {
        case SettingType::Boolean:
            return "true or false";
        case SettingType::Integer:
            return "an integer";
        case SettingType::Number:
            return "a number";
        case SettingType::Choice:
            return "a name";
        case SettingType::NumberList:
            return "a list of numbers";
    }
    return "a value";
}

bool has_type(const SettingValue& value, SettingType type) {
    switch (type) {
        case SettingType::Boolean:
            return std::holds_alternative<bool>(value);
        case SettingType::Integer:
            return std::holds_alternative<int64_t>(value);
        case SettingType::Number:
            return std::holds_alternative<double>(value);
        case SettingType::Choice:
            return std::holds_alternative<std::string>(value);
        case SettingType::NumberList:
            return std::holds_alternative<std::vector<float>>(value);
    }
    return false;
}

}  // namespace

std::string setting_value_problem(const SettingDeclaration& setting, const SettingValue& value) {
    if (!has_type(value, setting.type)) return std::string("expected ") + type_name(setting.type);
    switch (setting.type) {
        case SettingType::Integer:
            return integer_problem(setting, std::get<int64_t>(value));
        case SettingType::Number:
            return number_problem(setting, std::get<double>(value));
        case SettingType::Choice:
            return choice_problem(setting, std::get<std::string>(value));
        case SettingType::NumberList:
            for (const float number : std::get<std::vector<float>>(value)) {
                if (!std::isfinite(number)) return number_text(number) + " is not a finite number";
            }
            return "";
        case SettingType::Boolean:
            return "";
    }
    return "";
}

const SettingDeclaration* find_setting(std::string_view name) {
    for (const SettingDeclaration& setting : kSettingDeclarations) {
        if (name == setting.name) return &setting;
    }
    return nullptr;
}

bool setting_applies(const SettingDeclaration& setting, const Settings& settings) {
    const uint32_t filter_bit = 1u << static_cast<uint32_t>(settings.shadow.filter.mode);
    if ((setting.filters & filter_bit) == 0) return false;
    return setting.applies_when == nullptr || setting.applies_when(settings);
}

std::string describe_allowed_values(const SettingDeclaration& setting) {
    switch (setting.type) {
        case SettingType::Integer:
            if (!setting.allowed.empty()) return allowed_list(setting.allowed, " or ");
            [[fallthrough]];
        case SettingType::Number: {
            std::ostringstream text;
            if (setting.minimum_exclusive && std::isinf(setting.maximum))
                text << "> " << setting.minimum;
            else
                text << setting.minimum << ".." << setting.maximum;
            return text.str();
        }
        case SettingType::Choice: {
            std::string names;
            for (const char* name : setting.choices) {
                if (!names.empty()) names += '|';
                names += name;
            }
            return names;
        }
        case SettingType::Boolean:
        case SettingType::NumberList:
            return "";
    }
    return "";
}

std::string format_setting_value(const SettingValue& value) {
    if (const bool* flag = std::get_if<bool>(&value)) return *flag ? "true" : "false";
    if (const int64_t* integer = std::get_if<int64_t>(&value)) return std::to_string(*integer);
    if (const double* number = std::get_if<double>(&value)) return number_text(*number);
    if (const std::string* name = std::get_if<std::string>(&value)) return *name;
    std::string list;
    for (const float number : std::get<std::vector<float>>(value)) {
        if (!list.empty()) list += ", ";
        list += number_text(number);
    }
    return list;
}

}  // namespace penumbra

#include "setting_options.hpp"

#include <charconv>
#include <cstdlib>
#include <sstream>

#include "number_checks.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/setting_presentation.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::cli {
namespace {

// Flags older than the rule "--" + name: shorter names users already type.
const std::map<std::string, std::string>& older_flag_spellings() {
    static const std::map<std::string, std::string> spellings{{"strategy", "--shadow-strategy"},
                                                              {"light_bleeding_reduction", "--light-bleeding"},
                                                              {"msm_optimized_quantization", "--msm-quantization"},
                                                              {"cull_casters", "--no-cull"}};
    return spellings;
}

std::string dashed(const char* name) {
    std::string text(name);
    for (char& c : text) c = c == '_' ? '-' : c;
    return text;
}

// Defaults from a RenderSettings: the output settings' accessors read one.
bool on_by_default(const SettingDeclaration& setting) {
    return setting.type == SettingType::Boolean && std::get<bool>(setting.get(RenderSettings{}));
}

std::string help_text(const SettingDeclaration& setting) {
    const SettingValue default_value = setting.get(RenderSettings{});
    std::string help = presentation_of(setting).help;
    switch (setting.type) {
        case SettingType::Boolean:
            return help + (on_by_default(setting) ? " (on by default; this flag turns it off)" : " (off by default)");
        case SettingType::Choice: {
            std::string list;
            for (const char* name : setting.choices) {
                list += (list.empty() ? "" : "|") + std::string(name);
                if (default_value == SettingValue(std::string(name))) list += " (default)";
            }
            return help + ": " + list;
        }
        case SettingType::NumberList:
            return help + ", comma-separated";
        case SettingType::Integer:
        case SettingType::Number:
            return help + " (" + describe_allowed_values(setting) + ", default " + format_setting_value(default_value) +
                   ")";
    }
    return help;
}

const char* type_name(SettingType type) {
    switch (type) {
        case SettingType::Integer:
            return "INT";
        case SettingType::Number:
            return "FLOAT";
        case SettingType::Choice:
            return "NAME";
        case SettingType::NumberList:
            return "LIST";
        case SettingType::Boolean:
            return "";
    }
    return "";
}

SettingValue parse_integer(const std::string& text, const std::string& flag) {
    int64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) {
        throw InputError(flag + ": expected an integer, got \"" + text + "\"");
    }
    return value;
}

SettingValue parse_number(const std::string& text, const std::string& flag) {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !sane_number(value)) {
        throw InputError(flag + ": expected a finite number within +-1e9, got \"" + text + "\"");
    }
    return value;
}

SettingValue parse_value(const SettingDeclaration& setting, const std::string& text, const std::string& flag) {
    switch (setting.type) {
        case SettingType::Integer:
            return parse_integer(text, flag);
        case SettingType::Number:
            return parse_number(text, flag);
        case SettingType::NumberList:
            return parse_float_list(text, flag);
        case SettingType::Choice:
        case SettingType::Boolean:
            break;
    }
    return text;
}

// The tools' settings, then the ShadowSystem's.
template <typename Visit>
void for_each_setting(Visit visit) {
    for (const SettingDeclaration& setting : kOutputSettingDeclarations) visit(setting);
    for (const SettingDeclaration& setting : kSettingDeclarations) visit(setting);
}

}  // namespace

std::string setting_flag(const SettingDeclaration& setting) {
    if (const auto older = older_flag_spellings().find(setting.name); older != older_flag_spellings().end()) {
        return older->second;
    }
    return (on_by_default(setting) ? "--no-" : "--") + dashed(setting.name);
}

void add_setting_options(CLI::App& command, RawSettingOptions& raw) {
    for_each_setting([&](const SettingDeclaration& setting) {
        if (setting.type == SettingType::Boolean) {
            command.add_flag(setting_flag(setting), raw.switches[setting.name], help_text(setting));
        } else {
            command.add_option(setting_flag(setting), raw.values[setting.name], help_text(setting))
                ->type_name(type_name(setting.type));
        }
    });
}

void convert_setting_options(const RawSettingOptions& raw, SettingAssignments& settings) {
    for_each_setting([&](const SettingDeclaration& setting) {
        const std::string flag = setting_flag(setting);
        SettingValue value;
        if (setting.type == SettingType::Boolean) {
            const auto given = raw.switches.find(setting.name);
            if (given == raw.switches.end() || !given->second) return;
            value = !on_by_default(setting);
        } else {
            const auto given = raw.values.find(setting.name);
            if (given == raw.values.end() || given->second.empty()) return;
            value = parse_value(setting, given->second, flag);
        }
        if (const std::string problem = setting_value_problem(setting, value); !problem.empty()) {
            throw InputError(flag + ": " + problem);
        }
        settings.assign(setting, std::move(value));
    });
}

std::vector<float> parse_float_list(const std::string& text, const std::string& flag) {
    std::vector<float> values;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        try {
            size_t used = 0;
            values.push_back(std::stof(item, &used));
            if (used != item.size() || !sane_number(values.back())) throw std::invalid_argument(item);
        } catch (const std::exception&) {
            throw InputError(flag + ": expected comma-separated numbers, got \"" + text + "\"");
        }
    }
    return values;
}

}  // namespace penumbra::cli

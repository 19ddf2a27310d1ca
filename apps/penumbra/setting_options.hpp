#pragma once
// Command-line flags for every ShadowSystem setting, made from its declaration
// (kSettingDeclarations in penumbra/settings.hpp): the flag is "--" and the setting's name
// with dashes ("--pcf-radius"; "--no-..." for a setting that is on by default), except for
// a few older spellings the tools keep; --help shows the declaration's help, allowed values
// and default. Values are checked after parsing, so that an error names the flag.
#include <CLI/CLI.hpp>

#include <map>
#include <string>

#include "penumbra/scene/settings_overrides.hpp"

namespace penumbra::cli {

// Values as typed, by setting name.
struct RawSettingOptions {
    std::map<std::string, std::string> values;  // settings that take a value
    std::map<std::string, bool> switches;       // boolean settings: whether their flag was given
};

// The flag of a setting: "--pcf-radius", "--no-receiver-plane-bias", "--shadow-strategy".
std::string setting_flag(const SettingDeclaration& setting);

void add_setting_options(CLI::App& command, RawSettingOptions& raw);

// Throws InputError naming the flag for a value its declaration rejects.
void convert_setting_options(const RawSettingOptions& raw, SettingAssignments& settings);

// "1.5,2,3" -> {1.5, 2, 3}; throws InputError naming `flag` for anything else.
std::vector<float> parse_float_list(const std::string& text, const std::string& flag);

}  // namespace penumbra::cli

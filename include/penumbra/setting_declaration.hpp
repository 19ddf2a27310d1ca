#pragma once
// How a setting of a ShadowSystem is declared, once (the table is kSettingDeclarations in
// penumbra/settings.hpp): its name, type, range or choices, the filters it applies to, what
// a change rebuilds inside a ShadowSystem, and how to read and write it in a Settings.
// validate_settings(), settings_change_effect() and the tools (which add their own
// presentation: config keys, labels, help) read the declarations, so that a setting is
// defined in one place: its field and its declaration.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace penumbra {

struct Settings;

enum class SettingType {
    Boolean,
    Integer,
    Number,
    Choice,      // one of a list of names (an enum)
    NumberList,  // any number of numbers (manual cascade splits)
};

// What a change of a setting rebuilds inside a ShadowSystem (ShadowSystem::update_settings()
// takes every change and keeps the meshes, instances and lights).
enum class SettingEffect : uint8_t {
    Live,      // a uniform: the next prepare() uses it
    Pipeline,  // specialises Penumbra's shaders (and the caller's, see shader_specialization())
    Resource,  // sizes or picks the shadow maps: they are reallocated and drawn again
};

// A setting's value in the form readers and writers exchange: Boolean: bool, Integer:
// int64_t, Number: double, Choice: the choice's name, NumberList: the numbers.
using SettingValue = std::variant<bool, int64_t, double, std::string, std::vector<float>>;

// Bit i stands for the filter of value i (ShadowFilter): the filters a setting applies to.
inline constexpr uint32_t kEveryFilter = ~0u;

struct SettingDeclaration {
    const char* name = "";  // the setting's name: error messages, reports, the tools' flags and keys
    SettingType type = SettingType::Number;
    // Integer and Number: the inclusive range; with minimum_exclusive, values must exceed minimum.
    double minimum = -std::numeric_limits<double>::infinity();
    double maximum = std::numeric_limits<double>::infinity();
    bool minimum_exclusive = false;
    std::span<const int64_t> allowed = {};            // Integer: when not empty, the only values allowed
    std::span<const char* const> choices = {};        // Choice: the names, in the order lists show them
    SettingEffect effect = SettingEffect::Live;       // what a change rebuilds in a ShadowSystem
    uint32_t filters = kEveryFilter;                  // the filters it applies to (bits by ShadowFilter value)
    bool (*applies_when)(const Settings&) = nullptr;  // and only while this holds (nullptr: always)
    SettingValue (*get)(const Settings&) = nullptr;
    // Stores a value that setting_value_problem() accepts; others are not converted.
    void (*set)(Settings&, const SettingValue&) = nullptr;
};

// "" when `value` is a valid value of the setting, else what is wrong with it, e.g.
// "6 is outside the allowed range [0, 5]" or "24 must be 16 or 32".
std::string setting_value_problem(const SettingDeclaration& setting, const SettingValue& value);

// The declaration called `name` (kSettingDeclarations), or nullptr.
const SettingDeclaration* find_setting(std::string_view name);

// Whether the setting has an effect with these settings: its filters and its condition.
bool setting_applies(const SettingDeclaration& setting, const Settings& settings);

// The allowed values as help text shows them: "0..5", "16 or 32", "> 0", "hard|pcf|...";
// "" for booleans and lists.
std::string describe_allowed_values(const SettingDeclaration& setting);

// A value as a person writes it: "1", "0.75", "pcf", "true", "10, 20, 40".
std::string format_setting_value(const SettingValue& value);

// Building declarations from a field: declare<&Settings::shadow, &ShadowSettings::bias,
// &BiasSettings::slope>({...}) fills in the type and the accessors of Settings::shadow.
// bias.slope; declare_choice<kTable, ...> does so for an enum with its ChoiceName table.
namespace setting_detail {

template <auto... Path>
struct Field {
    template <typename Root>
    static auto& in(Root& root) {
        return (root.*....*Path);
    }
};

template <typename T>
constexpr SettingType type_of() {
    if constexpr (std::is_same_v<T, bool>)
        return SettingType::Boolean;
    else if constexpr (std::is_integral_v<T>)
        return SettingType::Integer;
    else if constexpr (std::is_floating_point_v<T>)
        return SettingType::Number;
    else {
        static_assert(std::is_same_v<T, std::vector<float>>, "a setting is a bool, an integer, a float or floats");
        return SettingType::NumberList;
    }
}

template <typename T>
SettingValue to_value(const T& field) {
    if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::vector<float>>)
        return field;
    else if constexpr (std::is_integral_v<T>)
        return static_cast<int64_t>(field);
    else
        return static_cast<double>(field);
}

template <typename T>
void from_value(const SettingValue& value, T& field) {
    if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::vector<float>>) {
        if (const T* stored = std::get_if<T>(&value)) field = *stored;
    } else if constexpr (std::is_integral_v<T>) {
        if (const int64_t* stored = std::get_if<int64_t>(&value)) field = static_cast<T>(*stored);
    } else if (const double* stored = std::get_if<double>(&value)) {
        field = static_cast<T>(*stored);
    }
}

template <const auto& Choices>
inline constexpr auto kChoiceNames = [] {
    std::array<const char*, std::size(Choices)> names{};
    for (std::size_t i = 0; i < names.size(); ++i) names[i] = Choices[i].name;
    return names;
}();

}  // namespace setting_detail

// The same for any accessor F with static `in(Settings&)` and `in(const Settings&)`
// returning the field (setting_detail::Field, or a derived settings struct's own).
template <typename F>
constexpr SettingDeclaration declare_field(SettingDeclaration setting) {
    using T = std::remove_cvref_t<decltype(F::in(std::declval<Settings&>()))>;
    setting.type = setting_detail::type_of<T>();
    setting.get = [](const Settings& settings) { return setting_detail::to_value<T>(F::in(settings)); };
    setting.set = [](Settings& settings, const SettingValue& value) {
        setting_detail::from_value(value, F::in(settings));
    };
    return setting;
}

template <const auto& Choices, typename F>
constexpr SettingDeclaration declare_choice_field(SettingDeclaration setting) {
    setting.type = SettingType::Choice;
    setting.choices = setting_detail::kChoiceNames<Choices>;
    setting.get = [](const Settings& settings) {
        for (const auto& choice : Choices) {
            if (choice.value == F::in(settings)) return SettingValue(std::string(choice.name));
        }
        return SettingValue(std::string("unknown"));
    };
    setting.set = [](Settings& settings, const SettingValue& value) {
        const std::string* name = std::get_if<std::string>(&value);
        for (const auto& choice : Choices) {
            if (name && *name == choice.name) F::in(settings) = choice.value;
        }
    };
    return setting;
}

template <auto... Path>
constexpr SettingDeclaration declare(SettingDeclaration setting) {
    return declare_field<setting_detail::Field<Path...>>(setting);
}

template <const auto& Choices, auto... Path>
constexpr SettingDeclaration declare_choice(SettingDeclaration setting) {
    return declare_choice_field<Choices, setting_detail::Field<Path...>>(setting);
}

}  // namespace penumbra

// kSettingDeclarations: every field of Settings has exactly one declaration, each
// declaration reads and writes its own field and no other, the recreation rule and the
// validation follow the declarations, and values are checked against them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <set>
#include <span>
#include <stdexcept>
#include <string>

#include "penumbra/errors.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/setting_presentation.hpp"
#include "penumbra/settings.hpp"

namespace penumbra {
namespace {

// Counts an aggregate's fields: the most arguments that brace-initialise it (anything
// converts to AnyField). A field added to a settings struct without a declaration
// changes the count.
struct AnyField {
    template <typename T>
    operator T() const;
};

template <typename T, typename... Fields>
constexpr size_t field_count() {
    if constexpr (requires { T{Fields{}..., AnyField{}}; }) {
        return field_count<T, Fields..., AnyField>();
    } else {
        return sizeof...(Fields);
    }
}

TEST(SettingDeclarations, EveryFieldOfSettingsHasOneDeclaration) {
    // Four of ShadowSettings' fields are the nested virtual map, cascade, bias and filter structs.
    const size_t leaves = field_count<VirtualShadowSettings>() + field_count<CascadeSettings>() +
                          field_count<BiasSettings>() + field_count<FilterSettings>() +
                          (field_count<ShadowSettings>() - 4) + field_count<LocalShadowSettings>() +
                          field_count<ContactShadowSettings>();
    EXPECT_EQ(field_count<Settings>(), 3u);
    EXPECT_EQ(std::size(kSettingDeclarations), leaves);
}

TEST(SettingDeclarations, NamesAreUniqueAndFound) {
    std::set<std::string> names;
    for (const SettingDeclaration& setting : kSettingDeclarations) {
        EXPECT_TRUE(names.insert(setting.name).second) << setting.name;
        EXPECT_EQ(find_setting(setting.name), &setting);
        EXPECT_EQ(setting_value_problem(setting, setting.get(Settings{})), "") << setting.name << ": invalid default";
    }
    EXPECT_EQ(find_setting("no_such_setting"), nullptr);
}

// The tools present every setting, the library's and their own output settings, exactly
// once: a label, a help line, a section, and a config key unique within its table.
TEST(SettingPresentations, EveryDeclarationHasOneAndEveryOneADeclaration) {
    std::set<std::string> presented;
    for (const SettingPresentation& presentation : kSettingPresentations) {
        EXPECT_TRUE(presented.insert(presentation.name).second) << presentation.name << " is presented twice";
        EXPECT_TRUE(find_setting(presentation.name) || find_output_setting(presentation.name))
            << presentation.name << " is presented but declared nowhere";
        EXPECT_NE(*presentation.help, '\0') << presentation.name;
        EXPECT_NE(*presentation.label, '\0') << presentation.name;
        EXPECT_NE(*presentation.group, '\0') << presentation.name;
    }
    const auto check_table = [](std::span<const SettingDeclaration> table) {
        std::set<std::string> keys;
        for (const SettingDeclaration& setting : table) {
            ASSERT_NE(find_presentation(setting.name), nullptr) << setting.name << " has no presentation";
            const SettingPresentation& presentation = presentation_of(setting);
            EXPECT_TRUE(keys.insert(presentation.key_in_config()).second) << presentation.key_in_config();
            if (presentation.powers_of_two) {
                EXPECT_EQ(setting.type, SettingType::Integer) << setting.name;
            }
        }
    };
    check_table(kSettingDeclarations);
    check_table(kOutputSettingDeclarations);
    EXPECT_THROW(presentation_of(SettingDeclaration{.name = "no_such_setting"}), std::logic_error);
}

// A valid value other than the one in `defaults` (a RenderSettings for output settings).
SettingValue other_value(const SettingDeclaration& setting, const Settings& defaults) {
    const SettingValue current = setting.get(defaults);
    switch (setting.type) {
        case SettingType::Boolean:
            return !std::get<bool>(current);
        case SettingType::Integer:
            if (!setting.allowed.empty()) {
                return setting.allowed[0] == std::get<int64_t>(current) ? setting.allowed[1] : setting.allowed[0];
            }
            return std::get<int64_t>(current) == static_cast<int64_t>(setting.maximum)
                       ? static_cast<int64_t>(setting.minimum)
                       : static_cast<int64_t>(setting.maximum);
        case SettingType::Number: {
            // A quarter of the way into the range (or three quarters, if that is the default).
            const double lowest = std::isfinite(setting.minimum) ? setting.minimum : 0.0;
            const double highest = std::isfinite(setting.maximum) ? setting.maximum : lowest + 100.0;
            // Numbers are stored as floats: a value a float holds reads back unchanged.
            const auto as_float = [](double value) { return static_cast<double>(static_cast<float>(value)); };
            const double quarter = as_float(lowest + 0.25 * (highest - lowest));
            return std::get<double>(current) == quarter ? as_float(lowest + 0.75 * (highest - lowest)) : quarter;
        }
        case SettingType::Choice:
            return std::string(std::get<std::string>(current) == setting.choices[0] ? setting.choices[1]
                                                                                    : setting.choices[0]);
        case SettingType::NumberList:
            return std::vector<float>{1.0f};
    }
    return current;
}

TEST(SettingDeclarations, EachDeclarationReadsAndWritesItsOwnFieldOnly) {
    const Settings defaults;
    for (const SettingDeclaration& setting : kSettingDeclarations) {
        const SettingValue value = other_value(setting, defaults);
        ASSERT_EQ(setting_value_problem(setting, value), "") << setting.name;
        ASSERT_NE(value, setting.get(defaults)) << setting.name;
        Settings changed;
        setting.set(changed, value);
        EXPECT_EQ(setting.get(changed), value) << setting.name;
        for (const SettingDeclaration& other : kSettingDeclarations) {
            if (&other == &setting) continue;
            EXPECT_EQ(other.get(changed), other.get(defaults)) << setting.name << " wrote " << other.name;
        }
        EXPECT_EQ(settings_change_effect(defaults, changed), setting.effect) << setting.name;
    }
}

// The tools' own settings ([output]) read and write their RenderSettings fields only.
TEST(SettingDeclarations, OutputSettingsReadAndWriteTheirOwnFields) {
    const RenderSettings defaults;
    for (const SettingDeclaration& setting : kOutputSettingDeclarations) {
        EXPECT_EQ(setting_value_problem(setting, setting.get(defaults)), "") << setting.name;
        RenderSettings changed;
        const SettingValue value = other_value(setting, defaults);
        setting.set(changed, value);
        EXPECT_EQ(setting.get(changed), value) << setting.name;
        for (const SettingDeclaration& other : kOutputSettingDeclarations) {
            if (&other == &setting) continue;
            EXPECT_EQ(other.get(changed), other.get(defaults)) << setting.name;
        }
        for (const SettingDeclaration& shadow : kSettingDeclarations) {
            EXPECT_EQ(shadow.get(changed), shadow.get(defaults)) << setting.name << " wrote " << shadow.name;
        }
        EXPECT_EQ(find_output_setting(setting.name), &setting);
    }
    RenderSettings too_wide;
    too_wide.width = kMaxImageSize + 1;
    EXPECT_THROW(validate_render_settings(too_wide, "test"), InputError);
}

TEST(SettingDeclarations, ValidationNamesTheDeclarationAndItsRange) {
    Settings settings;
    find_setting("blur_radius")->set(settings, int64_t{9});
    try {
        validate_settings(settings, "origin");
        ADD_FAILURE() << "blur_radius 9 was accepted";
    } catch (const InputError& error) {
        EXPECT_STREQ(error.what(), "origin: blur_radius: 9 is outside the allowed range [0, 8]");
    }
    const SettingDeclaration& max_distance = *find_setting("max_distance");
    EXPECT_EQ(setting_value_problem(max_distance, 0.0), "0 must be a finite number greater than 0");
    EXPECT_EQ(setting_value_problem(max_distance, 1e39), "1e+39 must be a finite number greater than 0")
        << "beyond float: infinite once stored";
    EXPECT_EQ(setting_value_problem(*find_setting("bias_clamp"), 0.1), "") << "the bound itself, as a float";
    EXPECT_EQ(setting_value_problem(*find_setting("filter"), std::string("pcf")), "");
    EXPECT_EQ(setting_value_problem(*find_setting("filter"), std::string("box")),
              "unknown value \"box\" (expected evsm, hard, msm, pcf, pcss, poisson, vsm)");
    EXPECT_EQ(setting_value_problem(*find_setting("filter"), int64_t{1}), "expected a name");
    EXPECT_EQ(setting_value_problem(*find_setting("poisson_taps"), int64_t{24}), "24 must be 16 or 32");
}

TEST(SettingDeclarations, FilterParametersApplyToTheirFilters) {
    Settings settings;
    const SettingDeclaration& pcf_radius = *find_setting("pcf_radius");
    const SettingDeclaration& poisson_radius = *find_setting("poisson_radius");
    EXPECT_FALSE(setting_applies(pcf_radius, settings)) << "hard is the default";
    settings.shadow.filter.mode = ShadowFilter::Pcf;
    EXPECT_TRUE(setting_applies(pcf_radius, settings));
    EXPECT_FALSE(setting_applies(poisson_radius, settings));
    settings.shadow.filter.mode = ShadowFilter::Vsm;
    settings.shadow.filter.moments_poisson = true;
    EXPECT_TRUE(setting_applies(poisson_radius, settings)) << "the moments' Poisson taps use it too";
    EXPECT_TRUE(setting_applies(*find_setting("cascades"), settings));
    EXPECT_EQ(describe_allowed_values(pcf_radius), "0..5");
    EXPECT_EQ(describe_allowed_values(*find_setting("max_distance")), "> 0");
    EXPECT_EQ(describe_allowed_values(*find_setting("fit")), "stable|tight");
}

}  // namespace
}  // namespace penumbra

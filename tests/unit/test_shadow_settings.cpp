// validate_shadow_settings: defaults pass, boundaries pass, every out-of-range or NaN
// value is an InputError that names the origin, the setting and the value.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "penumbra/errors.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/settings.hpp"

namespace penumbra {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInfinity = std::numeric_limits<float>::infinity();

struct BadValue {
    std::string description;
    std::function<void(ShadowSettings&)> apply;
    std::string key;
    std::string value_text;
};

// The message of the InputError thrown for the settings, or "" when none is thrown.
std::string validation_message(const ShadowSettings& settings) {
    try {
        validate_shadow_settings(settings, "scene.toml");
    } catch (const InputError& error) {
        return error.what();
    }
    return "";
}

std::vector<BadValue> bad_values() {
    return {
        {"zero cascades", [](ShadowSettings& s) { s.cascades.count = 0; }, "cascades", "0"},
        {"nine cascades", [](ShadowSettings& s) { s.cascades.count = 9; }, "cascades", "9"},
        {"tiny map", [](ShadowSettings& s) { s.cascades.resolution = 256; }, "shadow_resolution", "256"},
        {"huge map", [](ShadowSettings& s) { s.cascades.resolution = 16384; }, "shadow_resolution", "16384"},
        {"negative lambda", [](ShadowSettings& s) { s.cascades.split_lambda = -0.1f; }, "split_lambda", "-0.1"},
        {"lambda above one", [](ShadowSettings& s) { s.cascades.split_lambda = 1.5f; }, "split_lambda", "1.5"},
        {"NaN lambda", [](ShadowSettings& s) { s.cascades.split_lambda = kNaN; }, "split_lambda", "nan"},
        {"zero distance", [](ShadowSettings& s) { s.cascades.max_distance = 0.0f; }, "max_distance", "0"},
        {"negative distance", [](ShadowSettings& s) { s.cascades.max_distance = -5.0f; }, "max_distance", "-5"},
        {"NaN distance", [](ShadowSettings& s) { s.cascades.max_distance = kNaN; }, "max_distance", "nan"},
        {"infinite distance", [](ShadowSettings& s) { s.cascades.max_distance = kInfinity; }, "max_distance", "inf"},
        {"negative padding", [](ShadowSettings& s) { s.cascades.filter_padding_texels = -1.0f; }, "filter_padding",
         "-1"},
        {"huge padding", [](ShadowSettings& s) { s.cascades.filter_padding_texels = 65.0f; }, "filter_padding", "65"},
        {"NaN padding", [](ShadowSettings& s) { s.cascades.filter_padding_texels = kNaN; }, "filter_padding", "nan"},
        {"negative slope", [](ShadowSettings& s) { s.bias.slope = -1.0f; }, "slope_bias", "-1"},
        {"huge slope", [](ShadowSettings& s) { s.bias.slope = 21.0f; }, "slope_bias", "21"},
        {"NaN slope", [](ShadowSettings& s) { s.bias.slope = kNaN; }, "slope_bias", "nan"},
        {"negative constant", [](ShadowSettings& s) { s.bias.constant = -2.0f; }, "constant_bias", "-2"},
        {"huge constant", [](ShadowSettings& s) { s.bias.constant = 2e5f; }, "constant_bias", "200000"},
        {"NaN constant", [](ShadowSettings& s) { s.bias.constant = kNaN; }, "constant_bias", "nan"},
        {"negative clamp", [](ShadowSettings& s) { s.bias.clamp = -0.001f; }, "bias_clamp", "-0.001"},
        {"huge clamp", [](ShadowSettings& s) { s.bias.clamp = 0.5f; }, "bias_clamp", "0.5"},
        {"NaN clamp", [](ShadowSettings& s) { s.bias.clamp = kNaN; }, "bias_clamp", "nan"},
        {"negative normal offset", [](ShadowSettings& s) { s.bias.normal_offset = -0.5f; }, "normal_offset", "-0.5"},
        {"huge normal offset", [](ShadowSettings& s) { s.bias.normal_offset = 11.0f; }, "normal_offset", "11"},
        {"NaN normal offset", [](ShadowSettings& s) { s.bias.normal_offset = kNaN; }, "normal_offset", "nan"},
        {"negative blend", [](ShadowSettings& s) { s.blend_width = -0.2f; }, "blend_width", "-0.2"},
        {"wide blend", [](ShadowSettings& s) { s.blend_width = 0.75f; }, "blend_width", "0.75"},
        {"NaN blend", [](ShadowSettings& s) { s.blend_width = kNaN; }, "blend_width", "nan"},
    };
}

void use_manual_splits(ShadowSettings& settings, std::vector<float> splits) {
    settings.cascades.scheme = SplitScheme::Manual;
    settings.cascades.count = static_cast<int>(splits.size()) + 1;
    settings.cascades.manual_splits = std::move(splits);
}

std::vector<BadValue> bad_manual_splits() {
    return {
        {"too few",
         [](ShadowSettings& s) {
             use_manual_splits(s, {5.0f, 20.0f});
             s.cascades.count = 4;
         },
         "splits", "2 values given"},
        {"not increasing",
         [](ShadowSettings& s) {
             use_manual_splits(s, {5.0f, 20.0f, 12.5f});
         },
         "splits", "12.5"},
        {"repeated",
         [](ShadowSettings& s) {
             use_manual_splits(s, {5.0f, 5.0f});
         },
         "splits", "5"},
        {"zero",
         [](ShadowSettings& s) {
             use_manual_splits(s, {0.0f, 5.0f});
         },
         "splits", "0"},
        {"negative",
         [](ShadowSettings& s) {
             use_manual_splits(s, {-3.0f, 5.0f});
         },
         "splits", "-3"},
        {"NaN",
         [](ShadowSettings& s) {
             use_manual_splits(s, {2.0f, kNaN});
         },
         "splits", "nan"},
        {"beyond max_distance",
         [](ShadowSettings& s) {
             use_manual_splits(s, {2.0f, 160.0f});
         },
         "splits", "160"},
    };
}

TEST(ShadowSettings, DefaultsValidate) { EXPECT_NO_THROW(validate_shadow_settings(ShadowSettings{}, "defaults")); }

TEST(ShadowSettings, EveryOutOfRangeValueNamesTheSettingAndTheValue) {
    std::vector<BadValue> cases = bad_values();
    for (BadValue& bad : bad_manual_splits()) cases.push_back(std::move(bad));
    for (const BadValue& bad : cases) {
        ShadowSettings settings;
        bad.apply(settings);
        const std::string message = validation_message(settings);
        ASSERT_FALSE(message.empty()) << bad.description << " was accepted";
        EXPECT_EQ(message.rfind("scene.toml: " + bad.key + ": ", 0), 0u) << bad.description << ": " << message;
        EXPECT_NE(message.find(bad.value_text), std::string::npos) << bad.description << ": " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << bad.description << ": one line expected";
    }
}

TEST(ShadowSettings, RangeBoundariesValidate) {
    ShadowSettings low;
    low.cascades.count = 1;
    low.cascades.resolution = 512;
    low.cascades.split_lambda = 0.0f;
    low.cascades.filter_padding_texels = 0.0f;
    low.bias = BiasSettings{0.0f, 0.0f, 0.0f, 0.0f};
    low.blend_width = 0.0f;
    EXPECT_NO_THROW(validate_shadow_settings(low, "low"));

    ShadowSettings high;
    high.cascades.count = 8;
    high.cascades.resolution = 8192;
    high.cascades.split_lambda = 1.0f;
    high.cascades.filter_padding_texels = 64.0f;
    high.bias = BiasSettings{1e5f, 20.0f, 0.1f, 10.0f};
    high.blend_width = 0.5f;
    EXPECT_NO_THROW(validate_shadow_settings(high, "high"));
}

TEST(ShadowSettings, ValidManualSplitsPassAndAreIgnoredForOtherSchemes) {
    ShadowSettings manual;
    use_manual_splits(manual, {4.0f, 15.0f, 60.0f});
    EXPECT_NO_THROW(validate_shadow_settings(manual, "manual"));

    ShadowSettings practical;
    practical.cascades.manual_splits = {9.0f, 1.0f};  // not used by the practical scheme
    EXPECT_NO_THROW(validate_shadow_settings(practical, "practical"));
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// What a change rebuilds inside a ShadowSystem: the maps for what sizes them or picks their
// format (the filter, the moments' components, quantization and blur, the cascade count and
// resolution, the strategy, the local-shadow budget, resolution and sizing); the pipelines
// for the specialization constants (tap counts, PCSS quality and early out, receiver-plane
// bias, the moments' Poisson taps); nothing for the uniforms (biases, splits, distances,
// blend band, contact shadows, filter radii, bleeding reduction, exponents, moment bias).
TEST(SettingsChangeEffect, MapsPipelinesOrUniforms) {
    const Settings base;
    using Change = std::function<void(Settings&)>;
    const std::vector<Change> resources = {
        [](Settings& s) { s.shadow.filter.mode = ShadowFilter::Pcss; },
        [](Settings& s) { s.shadow.filter.evsm_components = 2; },
        [](Settings& s) { s.shadow.filter.msm_optimized_quantization = true; },
        [](Settings& s) { s.shadow.filter.blur_radius = 4; },
        [](Settings& s) { s.shadow.cascades.count = 2; },
        [](Settings& s) { s.shadow.cascades.resolution = 1024; },
        [](Settings& s) { s.shadow.strategy = ShadowStrategy::Multiview; },
        [](Settings& s) { s.shadow.technique = ShadowTechnique::Virtual; },
        [](Settings& s) { s.local_shadows.budget = 2; },
        [](Settings& s) { s.local_shadows.resolution = 512; },
        [](Settings& s) { s.local_shadows.sizing = LocalShadowSizing::Fixed; },
    };
    const std::vector<Change> pipelines = {
        [](Settings& s) { s.shadow.filter.receiver_plane_bias = false; },
        [](Settings& s) { s.shadow.filter.poisson_taps = 32; },
        [](Settings& s) { s.shadow.filter.pcss_blocker_taps = 32; },
        [](Settings& s) { s.shadow.filter.pcss_quality = PcssQuality::High; },
        [](Settings& s) { s.shadow.filter.pcss_early_out = true; },
        [](Settings& s) { s.shadow.filter.moments_poisson = true; },
    };
    const std::vector<Change> uniforms = {
        [](Settings& s) { s.shadow.bias.slope = 3.0f; },
        [](Settings& s) { s.shadow.bias.normal_offset = 1.0f; },
        [](Settings& s) { s.shadow.blend_width = 0.2f; },
        [](Settings& s) { s.shadow.cascades.max_distance = 80.0f; },
        [](Settings& s) { s.shadow.cascades.split_lambda = 0.5f; },
        [](Settings& s) { s.contact.enabled = true; },
        [](Settings& s) { s.shadow.filter.pcf_radius = 3; },
        [](Settings& s) { s.shadow.filter.poisson_radius = 4.0f; },
        [](Settings& s) { s.shadow.filter.pcss_max_penumbra = 16.0f; },
        [](Settings& s) { s.shadow.filter.light_bleeding_reduction = 0.5f; },
        [](Settings& s) { s.shadow.filter.evsm_positive_exponent = 20.0f; },
        [](Settings& s) { s.shadow.filter.evsm_negative_exponent = 2.0f; },
        [](Settings& s) { s.shadow.filter.msm_moment_bias = 1e-4f; },
    };
    const auto effect_of = [&](const std::vector<Change>& changes) {
        std::vector<SettingEffect> effects;
        for (const Change& change : changes) {
            Settings next = base;
            change(next);
            effects.push_back(settings_change_effect(base, next));
        }
        return effects;
    };
    using ::testing::Each;
    EXPECT_THAT(effect_of(resources), Each(SettingEffect::Resource));
    EXPECT_THAT(effect_of(pipelines), Each(SettingEffect::Pipeline));
    EXPECT_THAT(effect_of(uniforms), Each(SettingEffect::Live));
    EXPECT_EQ(settings_change_effect(base, base), SettingEffect::Live);
    // Several at once: the largest.
    Settings several = base;
    several.shadow.bias.slope = 3.0f;
    several.shadow.filter.poisson_taps = 32;
    EXPECT_EQ(settings_change_effect(base, several), SettingEffect::Pipeline);
    several.local_shadows.budget = 2;
    EXPECT_EQ(settings_change_effect(base, several), SettingEffect::Resource);
}

// --resolve auto: deferred where a filter takes many taps and the image is large or local
// lights cast shadows, forward otherwise; an explicit choice is kept.
TEST(ShadowResolve, AutoPicksTheMeasuredFasterPath) {
    constexpr uint64_t k1080p = 1920 * 1080;
    constexpr uint64_t k4K = 3840 * 2160;
    for (const ChoiceName<ShadowFilter>& filter : kShadowFilterChoices) {
        const bool many_taps = filter.value == ShadowFilter::Pcf || filter.value == ShadowFilter::Poisson ||
                               filter.value == ShadowFilter::Pcss;
        const ShadowResolve multi_tap_path = many_taps ? ShadowResolve::Deferred : ShadowResolve::Forward;
        EXPECT_EQ(effective_resolve(ShadowResolve::Auto, filter.value, false, k1080p), ShadowResolve::Forward)
            << filter.name;
        EXPECT_EQ(effective_resolve(ShadowResolve::Auto, filter.value, false, k4K), multi_tap_path) << filter.name;
        EXPECT_EQ(effective_resolve(ShadowResolve::Auto, filter.value, true, k1080p), multi_tap_path) << filter.name;
        for (const ShadowResolve explicit_choice : {ShadowResolve::Forward, ShadowResolve::Deferred}) {
            EXPECT_EQ(effective_resolve(explicit_choice, filter.value, true, k4K), explicit_choice);
            EXPECT_EQ(effective_resolve(explicit_choice, filter.value, false, k1080p), explicit_choice);
        }
    }
}

}  // namespace
}  // namespace penumbra

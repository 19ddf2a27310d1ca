// The pure side of the shadow filters: per-cascade PCSS and receiver-plane numbers, tap
// counts, the filter settings' validation and their [shadow] keys.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/shadow_filters.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/scene/settings_files.hpp"
#include "penumbra/scene/settings_overrides.hpp"

namespace penumbra {
namespace {

std::string validation_message(const FilterSettings& filter) {
    ShadowSettings settings;
    settings.filter = filter;
    try {
        validate_shadow_settings(settings, "config.toml");
    } catch (const InputError& error) {
        return error.what();
    }
    return "";
}

TEST(ShadowFilters, LightRadiusMapsTheAngularSizeToUvPerDepthUnit) {
    Cascade cascade;
    cascade.light_extent = {20.0f, 10.0f, 50.0f};
    const CascadeFilterParams params = cascade_filter_params(cascade, 2.0f);
    // A depth difference of 0.1 is 5 m along the light; the light's radius there is
    // 5 tan(1 deg) = 0.0873 m, i.e. 0.0873 / 20 in U and 0.0873 / 10 in V (an ellipse).
    EXPECT_NEAR(0.1f * params.light_radius_uv_per_depth.x, 5.0f * std::tan(glm::radians(1.0f)) / 20.0f, 1e-6f);
    EXPECT_NEAR(0.1f * params.light_radius_uv_per_depth.y, 5.0f * std::tan(glm::radians(1.0f)) / 10.0f, 1e-6f);
    // dz/du for the steepest accepted slope: 10 m of depth (0.2) per metre (1/20 in U).
    EXPECT_NEAR(params.max_depth_gradient.x, 0.2f / (1.0f / 20.0f), 1e-4f);
    EXPECT_NEAR(params.max_depth_gradient.y, 0.2f / (1.0f / 10.0f), 1e-4f);
}

TEST(ShadowFilters, PointLightSourceHasNoPenumbra) {
    Cascade cascade;
    cascade.light_extent = {20.0f, 20.0f, 50.0f};
    EXPECT_EQ(cascade_filter_params(cascade, 0.0f).light_radius_uv_per_depth, glm::vec2(0.0f));
}

TEST(ShadowFilters, TapCountsAndMomentFilters) {
    EXPECT_EQ(pcss_filter_taps(PcssQuality::Low), 16);
    EXPECT_EQ(pcss_filter_taps(PcssQuality::Medium), 25);
    EXPECT_EQ(pcss_filter_taps(PcssQuality::High), 49);
    for (const auto& [name, filter] : shadow_filter_names()) {
        EXPECT_EQ(is_moment_filter(filter), name == "vsm" || name == "evsm" || name == "msm") << name;
    }
    EXPECT_EQ(shadow_filter_names().size(), 7u);
}

TEST(ShadowFilters, DefaultsAreValidAndHard) {
    EXPECT_EQ(validation_message(FilterSettings{}), "");
    EXPECT_EQ(FilterSettings{}.mode, ShadowFilter::Hard);
}

TEST(ShadowFilters, OutOfRangeValuesNameTheKey) {
    FilterSettings filter;
    filter.pcf_radius = 6;
    EXPECT_EQ(validation_message(filter), "config.toml: pcf_radius: 6 is outside the allowed range [0, 5]");
    filter = {};
    filter.poisson_taps = 24;
    EXPECT_EQ(validation_message(filter), "config.toml: poisson_taps: 24 must be 16 or 32");
    filter = {};
    filter.pcss_blocker_taps = 8;
    EXPECT_EQ(validation_message(filter), "config.toml: pcss_blocker_taps: 8 must be 16 or 32");
    filter = {};
    filter.evsm_components = 3;
    EXPECT_EQ(validation_message(filter), "config.toml: evsm_components: 3 must be 2 or 4");
    filter = {};
    filter.light_bleeding_reduction = std::nanf("");
    EXPECT_NE(validation_message(filter).find("light_bleeding_reduction"), std::string::npos);
    filter = {};
    filter.msm_moment_bias = 0.02f;
    EXPECT_NE(validation_message(filter).find("msm_moment_bias: 0.02"), std::string::npos);
    filter = {};
    filter.blur_radius = -1;
    EXPECT_NE(validation_message(filter).find("blur_radius: -1"), std::string::npos);
}

TEST(ShadowFilters, ConfigKeysOverrideEveryFilterSetting) {
    const auto path = std::filesystem::temp_directory_path() / "penumbra_filter_config.toml";
    std::ofstream(path) << R"([shadow]
filter = "pcss"
receiver_plane_bias = false
pcf_radius = 3
poisson_taps = 32
poisson_radius = 4.5
pcss_blocker_taps = 32
pcss_quality = "high"
pcss_early_out = true
pcss_max_penumbra = 48.0
light_bleeding_reduction = 0.4
blur_radius = 3
moments_poisson = true
evsm_positive_exponent = 30.0
evsm_negative_exponent = 8.0
evsm_components = 2
msm_moment_bias = 0.0001
msm_optimized_quantization = true

[sun]
angular_diameter = 1.5
)";
    const SettingsOverrides overrides = load_settings_file(path);
    std::filesystem::remove(path);
    RenderSettings settings;
    apply_overrides(overrides, settings);
    const FilterSettings& f = settings.shadow.filter;
    EXPECT_EQ(f.mode, ShadowFilter::Pcss);
    EXPECT_FALSE(f.receiver_plane_bias);
    EXPECT_EQ(f.pcf_radius, 3);
    EXPECT_EQ(f.poisson_taps, 32);
    EXPECT_FLOAT_EQ(f.poisson_radius, 4.5f);
    EXPECT_EQ(f.pcss_blocker_taps, 32);
    EXPECT_EQ(f.pcss_quality, PcssQuality::High);
    EXPECT_TRUE(f.pcss_early_out);
    EXPECT_FLOAT_EQ(f.pcss_max_penumbra, 48.0f);
    EXPECT_FLOAT_EQ(f.light_bleeding_reduction, 0.4f);
    EXPECT_EQ(f.blur_radius, 3);
    EXPECT_TRUE(f.moments_poisson);
    EXPECT_FLOAT_EQ(f.evsm_positive_exponent, 30.0f);
    EXPECT_FLOAT_EQ(f.evsm_negative_exponent, 8.0f);
    EXPECT_EQ(f.evsm_components, 2);
    EXPECT_FLOAT_EQ(f.msm_moment_bias, 1e-4f);
    EXPECT_TRUE(f.msm_optimized_quantization);
    Scene scene;
    scene.lights.push_back(Light{});
    apply_overrides(overrides, scene);
    EXPECT_FLOAT_EQ(scene.lights[0].angular_diameter_degrees, 1.5f);
}

}  // namespace
}  // namespace penumbra

#pragma once
// Optional overrides of the shadow filter settings from one source (scene file, config
// file, command line); part of SettingsOverrides.
#include <optional>

#include "penumbra/settings.hpp"

namespace penumbra {

struct FilterOverrides {
    std::optional<ShadowFilter> mode;
    std::optional<bool> receiver_plane_bias;
    std::optional<int> pcf_radius;
    std::optional<int> poisson_taps;
    std::optional<float> poisson_radius;
    std::optional<int> pcss_blocker_taps;
    std::optional<PcssQuality> pcss_quality;
    std::optional<bool> pcss_early_out;
    std::optional<float> pcss_max_penumbra;
    std::optional<float> light_bleeding_reduction;
    std::optional<int> blur_radius;
    std::optional<bool> moments_poisson;
    std::optional<float> evsm_positive_exponent;
    std::optional<float> evsm_negative_exponent;
    std::optional<int> evsm_components;
    std::optional<float> msm_moment_bias;
    std::optional<bool> msm_optimized_quantization;
};

void apply_filter_overrides(const FilterOverrides& overrides, FilterSettings& filter);

}  // namespace penumbra

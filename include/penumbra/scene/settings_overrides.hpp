#pragma once
// Partial settings from one source (scene file, config file or command line). Sources
// are applied in increasing priority: scene file, then --config file, then flags.
#include <cstdint>
#include <optional>
#include <vector>

#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/scene.hpp"

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

struct SettingsOverrides {
    // [output]
    std::optional<uint32_t> width;
    std::optional<uint32_t> height;
    std::optional<ShadowResolve> resolve;
    // [shadow]
    std::optional<int> cascades;
    std::optional<uint32_t> shadow_resolution;
    std::optional<SplitScheme> split_scheme;
    std::optional<float> split_lambda;
    std::optional<std::vector<float>> splits;
    std::optional<float> max_distance;
    std::optional<FitMode> fit;
    std::optional<float> constant_bias;
    std::optional<float> slope_bias;
    std::optional<float> bias_clamp;
    std::optional<float> normal_offset;
    std::optional<float> blend_width;
    std::optional<ShadowStrategy> strategy;
    std::optional<bool> cull_casters;
    std::optional<CasterCulling> caster_culling;           // --caster-culling
    FilterOverrides filter;                                // [shadow] filter keys (docs/filters.md)
    std::optional<uint32_t> local_shadow_budget;           // --local-shadow-budget
    std::optional<uint32_t> local_shadow_resolution;       // --local-shadow-resolution
    std::optional<LocalShadowSizing> local_shadow_sizing;  // --local-shadow-sizing
    // [camera] and [sun]
    std::optional<glm::vec3> eye;
    std::optional<glm::vec3> target;
    std::optional<glm::vec3> up;
    std::optional<float> fov;
    std::optional<float> near_plane;
    std::optional<float> far_plane;
    std::optional<glm::vec3> light_direction;
    std::optional<float> angular_diameter;  // degrees, the sun's disk (soft-shadow filters)
};

void apply_overrides(const SettingsOverrides& overrides, RenderSettings& settings);
// Camera and sun overrides; a sun override on a scene without a sun adds one.
void apply_overrides(const SettingsOverrides& overrides, Scene& scene);

// Throws InputError naming `origin` when the scene's camera or sun is invalid:
// eye equal to target, fov outside (0, 180), near <= 0, far <= near, zero light direction,
// angular diameter outside [0, 45] degrees.
void validate_camera_and_sun(const Scene& scene, const std::string& origin);

}  // namespace penumbra

// The public settings' range checks, choice names and recreation rule. Every message names
// the origin, the setting as the user writes it, the offending value and the allowed
// range, on one line.
#include "penumbra/settings.hpp"

#include <cmath>
#include <sstream>

#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

[[noreturn]] void reject(const std::string& origin, const char* key, const std::string& problem) {
    throw InputError(origin + ": " + key + ": " + problem);
}

template <typename Value>
void require_in_range(const std::string& origin, const char* key, Value value, Value lowest, Value highest) {
    // Written as !(inside) so that NaN, which fails every comparison, is rejected.
    if (!(value >= lowest && value <= highest)) {
        std::ostringstream problem;
        problem << value << " is outside the allowed range [" << lowest << ", " << highest << "]";
        reject(origin, key, problem.str());
    }
}

void require_positive_finite(const std::string& origin, const char* key, float value) {
    if (!(value > 0.0f) || !std::isfinite(value)) {
        std::ostringstream problem;
        problem << value << " must be a finite number greater than 0";
        reject(origin, key, problem.str());
    }
}

void validate_manual_splits(const CascadeSettings& cascades, const std::string& origin) {
    const char* key = shadow_keys::kSplits;
    const size_t expected = static_cast<size_t>(cascades.count - 1);
    if (cascades.manual_splits.size() != expected) {
        std::ostringstream problem;
        problem << cascades.manual_splits.size() << " values given, " << cascades.count << " cascades need exactly "
                << expected;
        reject(origin, key, problem.str());
    }
    float previous = 0.0f;
    for (const float split : cascades.manual_splits) {
        if (!(split > previous) || !(split < cascades.max_distance)) {
            std::ostringstream problem;
            problem << split << " must be greater than the previous split (" << previous
                    << ") and less than max_distance (" << cascades.max_distance
                    << "); splits are strictly increasing view distances";
            reject(origin, key, problem.str());
        }
        previous = split;
    }
}

void validate_cascade_settings(const CascadeSettings& cascades, const std::string& origin) {
    require_in_range(origin, shadow_keys::kCascades, cascades.count, 1, kMaxCascades);
    require_in_range(origin, shadow_keys::kResolution, cascades.resolution, 512u, 8192u);
    require_in_range(origin, shadow_keys::kSplitLambda, cascades.split_lambda, 0.0f, 1.0f);
    require_positive_finite(origin, shadow_keys::kMaxDistance, cascades.max_distance);
    require_in_range(origin, shadow_keys::kFilterPadding, cascades.filter_padding_texels, 0.0f, 64.0f);
    if (cascades.scheme == SplitScheme::Manual) validate_manual_splits(cascades, origin);
}

void validate_bias_settings(const BiasSettings& bias, const std::string& origin) {
    require_in_range(origin, shadow_keys::kSlopeBias, bias.slope, 0.0f, 20.0f);
    require_in_range(origin, shadow_keys::kConstantBias, bias.constant, 0.0f, 1.0e5f);
    require_in_range(origin, shadow_keys::kBiasClamp, bias.clamp, 0.0f, 0.1f);
    require_in_range(origin, shadow_keys::kNormalOffset, bias.normal_offset, 0.0f, 10.0f);
}

void require_one_of(const std::string& origin, const char* key, int value, int first, int second) {
    if (value != first && value != second) {
        std::ostringstream problem;
        problem << value << " must be " << first << " or " << second;
        reject(origin, key, problem.str());
    }
}

void validate_filter_settings(const FilterSettings& filter, const std::string& origin) {
    require_in_range(origin, shadow_keys::kPcfRadius, filter.pcf_radius, 0, kMaxPcfRadius);
    require_one_of(origin, shadow_keys::kPoissonTaps, filter.poisson_taps, 16, 32);
    require_in_range(origin, shadow_keys::kPoissonRadius, filter.poisson_radius, 0.5f, 32.0f);
    require_one_of(origin, shadow_keys::kPcssBlockerTaps, filter.pcss_blocker_taps, 16, 32);
    require_in_range(origin, shadow_keys::kPcssMaxPenumbra, filter.pcss_max_penumbra, 1.0f, 128.0f);
    require_in_range(origin, shadow_keys::kLightBleeding, filter.light_bleeding_reduction, 0.0f, 0.95f);
    require_in_range(origin, shadow_keys::kBlurRadius, filter.blur_radius, 0, 8);
    require_in_range(origin, shadow_keys::kEvsmPositiveExponent, filter.evsm_positive_exponent, 0.1f, 100.0f);
    require_in_range(origin, shadow_keys::kEvsmNegativeExponent, filter.evsm_negative_exponent, 0.1f, 100.0f);
    require_one_of(origin, shadow_keys::kEvsmComponents, filter.evsm_components, 2, 4);
    require_in_range(origin, shadow_keys::kMsmMomentBias, filter.msm_moment_bias, 0.0f, 0.01f);
}

}  // namespace

void validate_shadow_settings(const ShadowSettings& settings, const std::string& origin) {
    validate_cascade_settings(settings.cascades, origin);
    validate_bias_settings(settings.bias, origin);
    require_in_range(origin, shadow_keys::kBlendWidth, settings.blend_width, 0.0f, 0.5f);
    validate_filter_settings(settings.filter, origin);
}

void validate_local_shadow_settings(const LocalShadowSettings& settings, const std::string& origin) {
    if (settings.budget > kMaxLocalShadowBudget) {
        reject(origin, "local_shadow_budget",
               std::to_string(settings.budget) + " is out of range (0.." + std::to_string(kMaxLocalShadowBudget) + ")");
    }
    if (settings.resolution < 16 || settings.resolution > 8192) {
        reject(origin, "local_shadow_resolution", std::to_string(settings.resolution) + " is out of range (16..8192)");
    }
}

void validate_settings(const Settings& settings, const std::string& origin) {
    validate_shadow_settings(settings.shadow, origin);
    validate_local_shadow_settings(settings.local_shadows, origin);
}

const std::map<std::string, SplitScheme>& split_scheme_names() { return choice_map(kSplitSchemeChoices); }
const std::map<std::string, FitMode>& fit_mode_names() { return choice_map(kFitModeChoices); }
const std::map<std::string, ShadowStrategy>& shadow_strategy_names() { return choice_map(kShadowStrategyChoices); }
const std::map<std::string, ShadowFilter>& shadow_filter_names() { return choice_map(kShadowFilterChoices); }
const std::map<std::string, PcssQuality>& pcss_quality_names() { return choice_map(kPcssQualityChoices); }
const std::map<std::string, LocalShadowSizing>& local_shadow_sizing_names() {
    return choice_map(kLocalShadowSizingChoices);
}
const std::map<std::string, CasterCulling>& caster_culling_names() { return choice_map(kCasterCullingChoices); }

bool is_moment_filter(ShadowFilter filter) {
    return filter == ShadowFilter::Vsm || filter == ShadowFilter::Evsm || filter == ShadowFilter::Msm;
}

// Every filter field specialises the pipelines or sizes the moments maps.
bool requires_recreation(const Settings& current, const Settings& next) {
    const CascadeSettings& a = current.shadow.cascades;
    const CascadeSettings& b = next.shadow.cascades;
    const LocalShadowSettings& local_a = current.local_shadows;
    const LocalShadowSettings& local_b = next.local_shadows;
    return a.count != b.count || a.resolution != b.resolution || current.shadow.strategy != next.shadow.strategy ||
           current.shadow.filter != next.shadow.filter || local_a.budget != local_b.budget ||
           local_a.resolution != local_b.resolution || local_a.sizing != local_b.sizing;
}

}  // namespace penumbra

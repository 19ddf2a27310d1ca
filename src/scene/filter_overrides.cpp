#include "penumbra/scene/settings_overrides.hpp"

namespace penumbra {
namespace {

template <typename T>
void assign_if(const std::optional<T>& value, T& target) {
    if (value) target = *value;
}

}  // namespace

void apply_filter_overrides(const FilterOverrides& o, FilterSettings& filter) {
    assign_if(o.mode, filter.mode);
    assign_if(o.receiver_plane_bias, filter.receiver_plane_bias);
    assign_if(o.pcf_radius, filter.pcf_radius);
    assign_if(o.poisson_taps, filter.poisson_taps);
    assign_if(o.poisson_radius, filter.poisson_radius);
    assign_if(o.pcss_blocker_taps, filter.pcss_blocker_taps);
    assign_if(o.pcss_quality, filter.pcss_quality);
    assign_if(o.pcss_early_out, filter.pcss_early_out);
    assign_if(o.pcss_max_penumbra, filter.pcss_max_penumbra);
    assign_if(o.light_bleeding_reduction, filter.light_bleeding_reduction);
    assign_if(o.blur_radius, filter.blur_radius);
    assign_if(o.moments_poisson, filter.moments_poisson);
    assign_if(o.evsm_positive_exponent, filter.evsm_positive_exponent);
    assign_if(o.evsm_negative_exponent, filter.evsm_negative_exponent);
    assign_if(o.evsm_components, filter.evsm_components);
    assign_if(o.msm_moment_bias, filter.msm_moment_bias);
    assign_if(o.msm_optimized_quantization, filter.msm_optimized_quantization);
}

}  // namespace penumbra

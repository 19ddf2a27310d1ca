#include "passes/shadow_filter_specialization.hpp"

#include "core/shadow_filters.hpp"
#include "passes/shader_interface.hpp"

namespace penumbra::passes {
namespace {

uint32_t boolean(bool value) { return value ? VK_TRUE : VK_FALSE; }

}  // namespace

std::vector<gpu::SpecializationValue> shadow_filter_specialization(const FilterSettings& filter) {
    const bool pcss = filter.mode == ShadowFilter::Pcss;
    const int search_taps = pcss ? filter.pcss_blocker_taps : filter.poisson_taps;
    return {
        {PENUMBRA_SPEC_FILTER_MODE, static_cast<uint32_t>(filter.mode)},  // the GLSL id (shader_interface.hpp)
        {PENUMBRA_SPEC_SEARCH_TAPS, static_cast<uint32_t>(search_taps)},
        {PENUMBRA_SPEC_FILTER_TAPS, static_cast<uint32_t>(pcss_filter_taps(filter.pcss_quality))},
        {PENUMBRA_SPEC_RECEIVER_PLANE, boolean(filter.receiver_plane_bias)},
        {PENUMBRA_SPEC_PCSS_EARLY_OUT, boolean(filter.pcss_early_out)},
        {PENUMBRA_SPEC_MOMENTS_POISSON, boolean(filter.moments_poisson)},
        {PENUMBRA_SPEC_EVSM_COMPONENTS, static_cast<uint32_t>(filter.evsm_components)},
        {PENUMBRA_SPEC_MSM_QUANTIZED, boolean(filter.msm_optimized_quantization)},
    };
}

}  // namespace penumbra::passes

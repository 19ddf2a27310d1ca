// The specialization constants that select the shadow filter and its tap counts: one
// pipeline per filter configuration, so the unused paths compile away. Their ids start at
// PENUMBRA_SPEC_ID_BASE (0 unless the including shader defines it); the values come from
// ShadowSystem::shader_specialization() (Penumbra's own pipelines use the same values).
// With PENUMBRA_FILTER_FROM_UNIFORMS defined they are read from the uniforms instead.
#ifndef PENUMBRA_GLSL_FILTER_CONSTANTS
#define PENUMBRA_GLSL_FILTER_CONSTANTS

#ifndef PENUMBRA_SPEC_ID_BASE
#define PENUMBRA_SPEC_ID_BASE 0
#endif

#ifdef PENUMBRA_FILTER_FROM_UNIFORMS
// One pipeline for every filter: the same values read from the uniforms, a branch per filter
// that every invocation takes alike (as Filament switches its shadow filters); for callers
// who never rebuild their pipelines when the filter changes.
#define kPenumbraFilterMode (penumbra_shadow.filter_mode)
#define kPenumbraSearchTaps (penumbra_shadow.filter_search_taps)
#define kPenumbraFilterTaps (penumbra_shadow.filter_taps)
#define kPenumbraReceiverPlaneBias (penumbra_shadow.filter_receiver_plane_bias != 0u)
#define kPenumbraPcssEarlyOut (penumbra_shadow.filter_pcss_early_out != 0u)
#define kPenumbraMomentsPoisson (penumbra_shadow.filter_moments_poisson != 0u)
#define kPenumbraEvsmComponents (penumbra_shadow.filter_evsm_components)
#define kPenumbraMsmQuantized (penumbra_shadow.filter_msm_quantized != 0u)
#elif defined(PENUMBRA_HLSL)
[[vk::constant_id(PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_FILTER_MODE)]] const uint kPenumbraFilterMode =
    PENUMBRA_FILTER_HARD;
[[vk::constant_id(PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_SEARCH_TAPS)]] const uint kPenumbraSearchTaps = 16u;
[[vk::constant_id(PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_FILTER_TAPS)]] const uint kPenumbraFilterTaps = 25u;
[[vk::constant_id(PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_RECEIVER_PLANE)]] const bool kPenumbraReceiverPlaneBias = true;
[[vk::constant_id(PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_PCSS_EARLY_OUT)]] const bool kPenumbraPcssEarlyOut = false;
[[vk::constant_id(PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_MOMENTS_POISSON)]] const bool kPenumbraMomentsPoisson = false;
[[vk::constant_id(PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_EVSM_COMPONENTS)]] const uint kPenumbraEvsmComponents = 4u;
[[vk::constant_id(PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_MSM_QUANTIZED)]] const bool kPenumbraMsmQuantized = false;

#else
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_FILTER_MODE) const uint kPenumbraFilterMode =
    PENUMBRA_FILTER_HARD;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_SEARCH_TAPS) const uint kPenumbraSearchTaps = 16u;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_FILTER_TAPS) const uint kPenumbraFilterTaps = 25u;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_RECEIVER_PLANE) const bool kPenumbraReceiverPlaneBias = true;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_PCSS_EARLY_OUT) const bool kPenumbraPcssEarlyOut = false;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_MOMENTS_POISSON) const bool kPenumbraMomentsPoisson = false;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_EVSM_COMPONENTS) const uint kPenumbraEvsmComponents = 4u;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_MSM_QUANTIZED) const bool kPenumbraMsmQuantized = false;

#endif

// Receiver-plane depth bias applies to the comparison filters that take several taps.
bool penumbra_uses_receiver_plane_bias() {
    return kPenumbraReceiverPlaneBias &&
           (kPenumbraFilterMode == PENUMBRA_FILTER_PCF || kPenumbraFilterMode == PENUMBRA_FILTER_POISSON ||
            kPenumbraFilterMode == PENUMBRA_FILTER_PCSS);
}

bool penumbra_is_moment_filter() {
    return kPenumbraFilterMode == PENUMBRA_FILTER_VSM || kPenumbraFilterMode == PENUMBRA_FILTER_EVSM ||
           kPenumbraFilterMode == PENUMBRA_FILTER_MSM;
}

#endif

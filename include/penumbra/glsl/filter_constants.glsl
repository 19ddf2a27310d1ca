// The specialization constants that select the shadow filter and its tap counts: one
// pipeline per filter configuration, so the unused paths compile away. Their ids start at
// PENUMBRA_SPEC_ID_BASE (0 unless the including shader defines it); the values come from
// ShadowSystem::shader_specialization() (Penumbra's own pipelines use the same values).
#ifndef PENUMBRA_GLSL_FILTER_CONSTANTS
#define PENUMBRA_GLSL_FILTER_CONSTANTS

#ifndef PENUMBRA_SPEC_ID_BASE
#define PENUMBRA_SPEC_ID_BASE 0
#endif

layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_FILTER_MODE) const uint kPenumbraFilterMode =
    PENUMBRA_FILTER_HARD;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_SEARCH_TAPS) const uint kPenumbraSearchTaps = 16u;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_FILTER_TAPS) const uint kPenumbraFilterTaps = 25u;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_RECEIVER_PLANE) const bool kPenumbraReceiverPlaneBias = true;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_PCSS_EARLY_OUT) const bool kPenumbraPcssEarlyOut = false;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_MOMENTS_POISSON) const bool kPenumbraMomentsPoisson = false;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_EVSM_COMPONENTS) const uint kPenumbraEvsmComponents = 4u;
layout(constant_id = PENUMBRA_SPEC_ID_BASE + PENUMBRA_SPEC_MSM_QUANTIZED) const bool kPenumbraMsmQuantized = false;

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

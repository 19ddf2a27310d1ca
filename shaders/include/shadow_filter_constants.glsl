// Specialization constants that select a shadow filter and its tap counts: one
// pipeline per filter configuration, so the unused paths compile away. The C++ side
// sets them from FilterSettings (src/passes/lighting_pass.cpp, moments_pass.cpp).
#ifndef PENUMBRA_SHADOW_FILTER_CONSTANTS_GLSL
#define PENUMBRA_SHADOW_FILTER_CONSTANTS_GLSL

layout(constant_id = PENUMBRA_SPEC_FILTER_MODE) const uint kFilterMode = PENUMBRA_FILTER_HARD;
layout(constant_id = PENUMBRA_SPEC_SEARCH_TAPS) const uint kSearchTaps = 16u;
layout(constant_id = PENUMBRA_SPEC_FILTER_TAPS) const uint kFilterTaps = 25u;
layout(constant_id = PENUMBRA_SPEC_RECEIVER_PLANE) const bool kReceiverPlaneBias = true;
layout(constant_id = PENUMBRA_SPEC_PCSS_EARLY_OUT) const bool kPcssEarlyOut = false;
layout(constant_id = PENUMBRA_SPEC_MOMENTS_POISSON) const bool kMomentsPoisson = false;
layout(constant_id = PENUMBRA_SPEC_EVSM_COMPONENTS) const uint kEvsmComponents = 4u;
layout(constant_id = PENUMBRA_SPEC_MSM_QUANTIZED) const bool kMsmQuantized = false;

#endif

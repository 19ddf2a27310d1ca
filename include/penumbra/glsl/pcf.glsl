// The pcf kernel of the sun's cascades and of the spot and point lights' layers, written
// once (included by penumbra/shadow.glsl before filters.glsl, which uses it).
//
// A (2R+1) x (2R+1) grid of bilinear comparison taps one texel apart weighs the
// (2R+2) x (2R+2) texels around the receiver separably: on each axis 1 - f for the first,
// 1 for those between and f for the last, f being the receiver's position between texel
// centres. Pairing neighbouring texels, one bilinear comparison placed between a pair at
// the ratio of their weights reads both with those weights (times the pair's total), so
// (R+1) x (R+1) taps give the same filter: 9 instead of 25 taps for R = 2 (the "optimized
// PCF" of The Witness and of MJP's Shadows sample). Every tap still reads texels at most
// one texel from its own position, so the receiver-plane static bias keeps its meaning.
// With the hardware's fixed-point filter weights (often 8 fractional bits) the result may
// differ from the plain grid's in the last 1/256.
#ifndef PENUMBRA_GLSL_PCF
#define PENUMBRA_GLSL_PCF

#include "penumbra/glsl/dialect.glsl"

PENUMBRA_CONST int kPenumbraMaxPcfRadius = PENUMBRA_MAX_PCF_RADIUS;  // FilterSettings::pcf_radius's upper bound

// Tap `pair` (0..R) of one axis of the kernel: its offset from the receiver in texels (x)
// and its weight (y; an axis's weights sum to 2R + 1). `f` is the receiver's position past
// the texel centre before it, in [0, 1). Computed per tap rather than into arrays: arrays
// indexed in a loop spill to local memory.
vec2 penumbra_pcf_tap(float f, int radius, int pair) {
    const int first = 2 * pair - radius;  // texel index relative to the one before the receiver
    const float first_weight = first == -radius ? 1.0 - f : 1.0;
    const float second_weight = first + 1 == radius + 1 ? f : 1.0;
    const float weight = first_weight + second_weight;
    return vec2(float(first) + second_weight / weight - f, weight);
}

#endif

#version 460
// Evaluates the pcf kernel's per-axis taps (penumbra/glsl/pcf.glsl) on the GPU for every
// radius 0..PENUMBRA_MAX_PCF_RADIUS and 64 receiver positions f = k / 64 between texel
// centres, so that tests/gpu/test_pcf_kernel.cpp can check them against the plain grid.
// Invocation i: radius i / 64, f = (i % 64) / 64; it writes the R + 1 offsets, then the
// R + 1 weights, at values[i * kStride ...].
#extension GL_GOOGLE_include_directive : require
#include "penumbra/shadow_interface.h"
#include "penumbra/glsl/pcf.glsl"

layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) writeonly buffer Probe { float values[]; };

const uint kStride = 2u * uint(kPenumbraMaxPcfRadius + 1);

void main() {
    const uint i = gl_GlobalInvocationID.x;
    const int radius = int(i / 64u);
    const float f = float(i % 64u) / 64.0;
    for (int tap = 0; tap <= kPenumbraMaxPcfRadius; ++tap) {
        const vec2 t = tap <= radius ? penumbra_pcf_tap(f, radius, tap) : vec2(0.0);
        values[i * kStride + uint(tap)] = t.x;
        values[i * kStride + uint(kPenumbraMaxPcfRadius + 1 + tap)] = t.y;
    }
}

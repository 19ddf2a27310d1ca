// The sampling-rate ceiling pass's push constants (apps/bench/tap_ceiling_pass.cpp checks
// their offsets against shaders/tap_ceiling.frag).
#ifndef PENUMBRA_BENCH_SHARED_H
#define PENUMBRA_BENCH_SHARED_H

struct TapCeilingPushConstants {
    vec4 target_and_texel;  // xy: 1 / target size in pixels, z: one shadow-map texel in UV units
    uvec4 counts;           // x: texture taps per pixel, y: shadow-map layers
};

#endif

// The taps of the sampling-rate ceilings (tap_ceiling.frag and tap_ceiling.comp): `taps`
// depth-comparison lookups per pixel through the lighting pass's sampler (bilinear
// hardware PCF), walking a fixed 16-point disc whose radius grows every 16 taps, the way a
// PCF or PCSS kernel reads neighbouring texels, and cycling through the layers. The
// result is constant (the map is cleared); the filtering work is not.
#ifndef PENUMBRA_BENCH_TAP_CEILING_TAPS_GLSL
#define PENUMBRA_BENCH_TAP_CEILING_TAPS_GLSL

const vec2 kDisc[16] = vec2[](vec2(-0.94, -0.40), vec2(0.95, -0.77), vec2(-0.09, -0.93), vec2(0.34, 0.29),
                              vec2(-0.92, 0.46), vec2(-0.82, 0.15), vec2(-0.38, 0.28), vec2(-0.20, -0.16),
                              vec2(0.97, 0.76), vec2(0.44, -0.59), vec2(0.54, 0.76), vec2(-0.26, 0.99),
                              vec2(-0.88, -0.05), vec2(0.54, 0.85), vec2(0.17, -0.75), vec2(-0.71, -0.69));

// The mean of the taps at the pixel whose centre is `pixel_centre`.
float ceiling_taps(sampler2DArrayShadow shadow_map, vec2 pixel_centre, TapCeilingPushConstants params) {
    const vec2 uv = pixel_centre * params.target_and_texel.xy;
    const float texel = params.target_and_texel.z;
    const uint taps = params.counts.x;
    const uint layers = max(params.counts.y, 1u);
    float lit = 0.0;
    for (uint i = 0u; i < taps; ++i) {
        const vec2 offset = kDisc[i & 15u] * texel * float(1u + (i >> 4u));
        lit += texture(shadow_map, vec4(uv + offset, float(i % layers), 0.5));
    }
    return lit / float(max(taps, 1u));
}

#endif

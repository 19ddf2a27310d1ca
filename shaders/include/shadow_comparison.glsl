// Comparison filters of the shadow library (included by shadow.glsl): hard, PCF grid,
// rotated Poisson PCF and PCSS. Each hardware comparison tap is itself a bilinear 2x2
// percentage-closer filter (Reeves et al. 1987) on the comparison sampler.
#ifndef PENUMBRA_SHADOW_COMPARISON_GLSL
#define PENUMBRA_SHADOW_COMPARISON_GLSL

#include "poisson_disks.glsl"

// Rotation of the Poisson patterns: interleaved gradient noise per pixel (Jimenez 2014,
// "Next Generation Post Processing in Call of Duty: Advanced Warfare") plus a golden-ratio
// step per frame, so that successive frames sample new directions and a temporal filter
// can accumulate them. The frame step is Fibonacci hashing (frame * 2^32 / phi, wrapping),
// exact for any frame index, where fract(frame * 0.618) would lose precision.
mat2 sample_rotation() {
    const float noise = fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
    const float frame_offset = float(frame.filter_options.x * 2654435769u) * (1.0 / 4294967296.0);
    const float angle = 6.28318530718 * fract(noise + frame_offset);
    const float c = cos(angle);
    const float s = sin(angle);
    return mat2(c, s, -s, c);
}

// Bias for the texels a tap actually compares: a bilinear comparison reads texel centres
// up to one texel away from the tap on each axis, where the receiver's plane has moved
// by |dz/du| and |dz/dv| texels' worth (the "fractional sampling error" of receiver-plane
// bias). Zero without receiver-plane bias.
float receiver_plane_static_bias(ShadowCoord coord) { return dot(vec2(shadow_texel_uv()), abs(coord.depth_gradient)); }

// One hardware comparison tap `offset` (UV) away from the receiver. With receiver-plane
// bias the reference depth follows the receiver's plane to the tap.
float compare_tap(int cascade, ShadowCoord coord, vec2 offset, float static_bias) {
    const float reference = coord.depth + dot(coord.depth_gradient, offset) + static_bias;
    return texture(shadow_map, vec4(coord.uv + offset, float(cascade), reference));
}

// hard: one hardware comparison tap, no receiver-plane bias.
float shadow_hard(int cascade, ShadowCoord coord) {
    return texture(shadow_map, vec4(coord.uv, float(cascade), coord.depth));
}

// pcf: a (2R+1) x (2R+1) grid of comparison taps one texel apart.
float shadow_pcf(int cascade, ShadowCoord coord) {
    const int radius = int(frame.filter_params.x);
    const float texel = shadow_texel_uv();
    const float bias = receiver_plane_static_bias(coord);
    float lit = 0.0;
    for (int y = -radius; y <= radius; ++y) {
        for (int x = -radius; x <= radius; ++x) lit += compare_tap(cascade, coord, vec2(x, y) * texel, bias);
    }
    const int side = 2 * radius + 1;
    return lit / float(side * side);
}

// Sum of comparison taps over a rotated Poisson disk with per-axis radius `radius_uv`.
float poisson_comparisons(int cascade, ShadowCoord coord, uint taps, vec2 radius_uv, mat2 rotation) {
    const float bias = receiver_plane_static_bias(coord);
    float lit = 0.0;
    for (uint i = 0u; i < taps; ++i) {
        lit += compare_tap(cascade, coord, (rotation * poisson_tap(taps, i)) * radius_uv, bias);
    }
    return lit / float(taps);
}

// poisson: 16 or 32 comparison taps on a Poisson disk of poisson_radius texels, rotated per pixel.
float shadow_poisson(int cascade, ShadowCoord coord) {
    const vec2 radius_uv = vec2(frame.filter_params.y * shadow_texel_uv());
    return poisson_comparisons(cascade, coord, kSearchTaps, radius_uv, sample_rotation());
}

struct BlockerSearch {
    float average_depth;  // reverse-Z depth of the blockers found
    uint count;
};

// PCSS step 1 (Fernando 2005): raw depths nearer the light than the receiver's plane,
// over a rotated Poisson disk of the search radius.
BlockerSearch find_blockers(int cascade, ShadowCoord coord, vec2 radius_uv, mat2 rotation) {
    const float bias = receiver_plane_static_bias(coord);
    BlockerSearch search = BlockerSearch(0.0, 0u);
    for (uint i = 0u; i < kSearchTaps; ++i) {
        const vec2 offset = (rotation * poisson_tap(kSearchTaps, i)) * radius_uv;
        const float stored = texture(shadow_depth, vec3(coord.uv + offset, float(cascade))).r;
        const float reference = coord.depth + dot(coord.depth_gradient, offset) + bias;
        if (stored > reference) {  // reverse-Z: larger = nearer the light
            search.average_depth += stored;
            search.count += 1u;
        }
    }
    if (search.count > 0u) search.average_depth /= float(search.count);
    return search;
}

// Blockers found by fewer taps than this fade the result toward lit: at the rim of the
// search region a lone tap is not a reliable penumbra estimate.
const float kConfidentBlockers = 3.0;

// pcss: percentage-closer soft shadows (Fernando 2005) for a directional light of
// angular diameter theta. All lengths go to UV per axis through the cascade's light
// radius (cascade_filter.xy = depth range * tan(theta / 2) / (width, height)), so a
// cascade whose X and Y extents differ gets an elliptical kernel.
float shadow_pcss(int cascade, ShadowCoord coord) {
    const vec2 light_radius_per_depth = frame.cascade_filter[cascade].xy;
    const vec2 min_radius = vec2(shadow_texel_uv());
    const vec2 max_radius = min_radius * frame.filter_params.z;
    const mat2 rotation = sample_rotation();
    // 1. Blocker search: an occluder shadows the receiver only within (its distance to
    //    the receiver) * tan(theta / 2), and no occluder is farther than the light's near plane.
    const vec2 search_radius = clamp((1.0 - coord.depth) * light_radius_per_depth, min_radius, max_radius);
    const BlockerSearch blockers = find_blockers(cascade, coord, search_radius, rotation);
    if (blockers.count == 0u) return 1.0;
    if (kPcssEarlyOut && blockers.count == kSearchTaps) return 0.0;
    // 2. Penumbra: width (receiver - blocker distance) * 2 tan(theta / 2), so the filter
    //    radius is the depth difference times the light radius, clamped to [1 texel, max].
    const vec2 penumbra_radius =
        clamp((blockers.average_depth - coord.depth) * light_radius_per_depth, min_radius, max_radius);
    // 3. Variable-width Poisson PCF over the penumbra.
    const float lit = poisson_comparisons(cascade, coord, kFilterTaps, penumbra_radius, rotation);
    // 4. Blocker confidence.
    return mix(1.0, lit, smoothstep(0.0, kConfidentBlockers, float(blockers.count)));
}

#endif

// Filters of the sun's cascades (included by penumbra/glsl/sun.glsl). Comparison filters
// over the depth map: hard, PCF grid, rotated Poisson PCF and PCSS; each hardware
// comparison tap is itself a bilinear 2x2 percentage-closer filter (Reeves et al. 1987).
// Moment filters: VSM, EVSM and MSM read the moments map that Penumbra's moments conversion
// rendered (and blurred) per cascade; the receiver's distance is 1 - its reverse-Z depth,
// as in the moments (penumbra/glsl/moments.glsl).
#ifndef PENUMBRA_GLSL_SUN_FILTERS
#define PENUMBRA_GLSL_SUN_FILTERS

// Bias for the texels a tap actually compares: a bilinear comparison reads texel centres
// up to one texel away from the tap on each axis, where the receiver's plane has moved
// by |dz/du| and |dz/dv| texels' worth (the "fractional sampling error" of receiver-plane
// bias). Zero without receiver-plane bias.
float penumbra_receiver_plane_static_bias(PenumbraShadowCoord coord) { return dot(vec2(penumbra_shadow.texel_uv), abs(coord.depth_gradient)); }

// One hardware comparison tap `offset` (UV) away from the receiver. With receiver-plane
// bias the reference depth follows the receiver's plane to the tap.
float penumbra_compare_tap(int cascade, PenumbraShadowCoord coord, vec2 offset, float static_bias) {
    const float reference = coord.depth + dot(coord.depth_gradient, offset) + static_bias;
    return texture(penumbra_cascade_map, vec4(coord.uv + offset, float(cascade), reference));
}

// hard: one hardware comparison tap, no receiver-plane bias.
float penumbra_shadow_hard(int cascade, PenumbraShadowCoord coord) {
    return texture(penumbra_cascade_map, vec4(coord.uv, float(cascade), coord.depth));
}

// pcf: the (2R+1) x (2R+1) grid of comparison taps one texel apart, as (R+1)^2 weighted
// taps (penumbra/glsl/pcf.glsl).
float penumbra_shadow_pcf(int cascade, PenumbraShadowCoord coord) {
    const int radius = int(penumbra_shadow.pcf_radius);
    const float texel = penumbra_shadow.texel_uv;
    const float bias = penumbra_receiver_plane_static_bias(coord);
    const vec2 f = fract(coord.uv / texel - 0.5);
    float lit = 0.0;
    for (int j = 0; j <= radius; ++j) {
        const vec2 y = penumbra_pcf_tap(f.y, radius, j);
        for (int i = 0; i <= radius; ++i) {
            const vec2 x = penumbra_pcf_tap(f.x, radius, i);
            const vec2 offset = vec2(x.x, y.x) * texel;
            lit += x.y * y.y * penumbra_compare_tap(cascade, coord, offset, bias);
        }
    }
    const float side = float(2 * radius + 1);
    return lit / (side * side);
}

// Sum of comparison taps over a rotated Poisson disk with per-axis radius `radius_uv`.
float penumbra_poisson_comparisons(int cascade, PenumbraShadowCoord coord, uint taps, vec2 radius_uv, mat2 rotation) {
    const float bias = penumbra_receiver_plane_static_bias(coord);
    float lit = 0.0;
    for (uint i = 0u; i < taps; ++i) {
        lit += penumbra_compare_tap(cascade, coord, (rotation * penumbra_poisson_tap(taps, i)) * radius_uv, bias);
    }
    return lit / float(taps);
}

// poisson: 16 or 32 comparison taps on a Poisson disk of poisson_radius texels, rotated per pixel.
float penumbra_shadow_poisson(int cascade, PenumbraShadowCoord coord, vec2 pixel) {
    const vec2 radius_uv = vec2(penumbra_shadow.poisson_radius_texels * penumbra_shadow.texel_uv);
    return penumbra_poisson_comparisons(cascade, coord, kPenumbraSearchTaps, radius_uv, penumbra_sample_rotation(pixel));
}

struct PenumbraBlockerSearch {
    float average_depth;  // reverse-Z depth of the blockers found
    uint count;
};

// PCSS step 1 (Fernando 2005): raw depths nearer the light than the receiver's plane,
// over a rotated Poisson disk of the search radius.
PenumbraBlockerSearch penumbra_find_blockers(int cascade, PenumbraShadowCoord coord, vec2 radius_uv, mat2 rotation) {
    const float bias = penumbra_receiver_plane_static_bias(coord);
    PenumbraBlockerSearch search = PenumbraBlockerSearch(0.0, 0u);
    for (uint i = 0u; i < kPenumbraSearchTaps; ++i) {
        const vec2 offset = (rotation * penumbra_poisson_tap(kPenumbraSearchTaps, i)) * radius_uv;
        const float stored = texture(penumbra_cascade_depth, vec3(coord.uv + offset, float(cascade))).r;
        const float reference = coord.depth + dot(coord.depth_gradient, offset) + bias;
        if (stored > reference) {  // reverse-Z: larger = nearer the light
            search.average_depth += stored;
            search.count += 1u;
        }
    }
    if (search.count > 0u) search.average_depth /= float(search.count);
    return search;
}

// PCSS step 3's Poisson disk for a light footprint of radius `penumbra_radius` (shared by
// the sun and the spot and point lights, local.glsl). Every tap is a bilinear 2x2
// comparison, which by itself spreads an edge over one texel: a box one texel wide, of
// per-axis variance texel^2 / 12. A uniform disk of radius r has a per-axis variance of
// r^2 / 4, and variances add under convolution, so the disk that makes disk (x) bilinear
// as wide as the light's disk of radius R has r^2 = R^2 - texel^2 / 3. Below
// R = texel / sqrt(3) the bilinear tap alone is already as wide as the light: r = 0. (A
// one-texel floor on the disk made PCSS about twice the ray-traced penumbra at the sun's
// usual sub-texel widths: issue 16, docs/QUALITY.md.)
vec2 penumbra_pcss_disk_radius(vec2 penumbra_radius, float texel) {
    return sqrt(max(penumbra_radius * penumbra_radius - vec2(texel * texel / 3.0), vec2(0.0)));
}

// A disk narrower than this fraction of a texel barely moves any tap's bilinear weights:
// PCSS then makes one comparison at the receiver, without the rotation's noise or its cost.
const float kPenumbraSingleTapDisk = 0.05;

bool penumbra_pcss_is_single_tap(vec2 disk_radius, float texel) { return max(disk_radius.x, disk_radius.y) < kPenumbraSingleTapDisk * texel; }

// PCSS's comparison at the receiver itself: the hard filter's, plus the receiver-plane
// static bias when that bias is on (it is then PCSS's only protection against acne).
float penumbra_pcss_centre_tap(int cascade, PenumbraShadowCoord coord) {
    return penumbra_compare_tap(cascade, coord, vec2(0.0), penumbra_receiver_plane_static_bias(coord));
}

// pcss: percentage-closer soft shadows (Fernando 2005) for a directional light of
// angular diameter theta. All lengths go to UV per axis through the cascade's light
// radius (cascade_filter.xy = depth range * tan(theta / 2) / (width, height)), so a
// cascade whose X and Y extents differ gets an elliptical kernel. Where the penumbra is
// narrower than the bilinear comparison (the sun's usual case unless the caster is far),
// it is one comparison at the receiver, as hard is.
float penumbra_shadow_pcss(int cascade, PenumbraShadowCoord coord, vec2 pixel) {
    const vec2 light_radius_per_depth = penumbra_shadow.cascades[cascade].light_radius_uv_per_depth;
    const float texel = penumbra_shadow.texel_uv;
    const vec2 max_radius = vec2(texel * penumbra_shadow.pcss_max_penumbra_texels);
    const mat2 rotation = penumbra_sample_rotation(pixel);
    // 1. Blocker search: an occluder shadows the receiver only within (its distance to
    //    the receiver) * tan(theta / 2), and no occluder is farther than the light's near
    //    plane. None found: any occluder is nearer the receiver than the search's bias (a
    //    contact, a thin gap), so its penumbra is below a texel and the comparison at the
    //    receiver decides; returning lit there made contacts and thin gaps leak light.
    const vec2 search_radius = clamp((1.0 - coord.depth) * light_radius_per_depth, vec2(texel), max_radius);
    const PenumbraBlockerSearch blockers = penumbra_find_blockers(cascade, coord, search_radius, rotation);
    if (blockers.count == 0u) return penumbra_pcss_centre_tap(cascade, coord);
    if (kPenumbraPcssEarlyOut && blockers.count == kPenumbraSearchTaps) return 0.0;
    // 2. Penumbra: width (receiver - blocker distance) * 2 tan(theta / 2), so the light's
    //    footprint radius is the depth difference times the light radius (at most max).
    const vec2 penumbra_radius = min((blockers.average_depth - coord.depth) * light_radius_per_depth, max_radius);
    // 3. Variable-width Poisson PCF over the penumbra, less the taps' own bilinear width.
    //    Every blocker found counts: a fade toward lit below 3 blockers (removed) erased
    //    the shadows of thin casters, which only a few search taps hit.
    const vec2 disk_radius = penumbra_pcss_disk_radius(penumbra_radius, texel);
    if (penumbra_pcss_is_single_tap(disk_radius, texel)) return penumbra_pcss_centre_tap(cascade, coord);
    return penumbra_poisson_comparisons(cascade, coord, kPenumbraFilterTaps, disk_radius, rotation);
}

// The smallest depth difference (in distance units, 0..1 over the cascade's depth range)
// that the moment filters resolve: the minimum variance is its square (warped for EVSM).
// It absorbs float rounding of the second moment (d^2 - mean^2 cancels).
const float kPenumbraMomentDepthTolerance = 5e-4;

// Linear filtering (and the optional Poisson taps) average the moments: the average of
// a moment vector is the moment vector of the mixed distribution, which is why moments
// can be prefiltered at all.
vec4 penumbra_fetch_moments(int cascade, vec2 uv, vec2 pixel) {
    if (!kPenumbraMomentsPoisson) return texture(penumbra_cascade_moments, vec3(uv, float(cascade)));
    const mat2 rotation = penumbra_sample_rotation(pixel);
    const vec2 radius_uv = vec2(penumbra_shadow.poisson_radius_texels * penumbra_shadow.texel_uv);
    vec4 sum = vec4(0.0);
    for (uint i = 0u; i < 16u; ++i) {
        sum += texture(penumbra_cascade_moments, vec3(uv + (rotation * penumbra_poisson_tap(16u, i)) * radius_uv, float(cascade)));
    }
    return sum / 16.0;
}

// Lauritzen 2007 (GPU Gems 3, ch. 8): light bleeding shows up as the low tail of the
// bound, so remap [amount, 1] to [0, 1], trading some softness for darker bleeding.
float penumbra_reduce_light_bleeding(float p_max, float amount) { return clamp((p_max - amount) / (1.0 - amount), 0.0, 1.0); }

// Chebyshev's one-sided inequality (Donnelly & Lauritzen 2006): an upper bound on the
// fraction of occluders at least as far as `receiver`, given the mean and second moment.
float penumbra_chebyshev_upper_bound(vec2 moments, float receiver, float min_variance) {
    if (receiver <= moments.x) return 1.0;
    const float variance = max(moments.y - moments.x * moments.x, min_variance);
    const float difference = receiver - moments.x;
    return variance / (variance + difference * difference);
}

// vsm: Chebyshev's bound on (d, d^2).
float penumbra_vsm_visibility(vec4 moments, float receiver) {
    const float min_variance = kPenumbraMomentDepthTolerance * kPenumbraMomentDepthTolerance;
    return penumbra_chebyshev_upper_bound(moments.xy, receiver, min_variance);
}

// evsm: the bound on exponentially warped depths (Lauritzen & McCool 2008). The warp
// makes the receiver's distance to far occluders huge relative to the variance, which
// suppresses most of VSM's bleeding; the negative warp (4 components) bounds the other
// side. The tolerance is scaled by the warp's slope, d/dd e^{c w} = 2 c e^{c w}.
float penumbra_evsm_visibility(vec4 moments, float receiver, vec2 exponents) {
    const vec2 warped = penumbra_evsm_warp(receiver, exponents);
    const vec2 tolerance = kPenumbraMomentDepthTolerance * 2.0 * exponents * abs(warped);
    float p_max = penumbra_chebyshev_upper_bound(moments.xy, warped.x, tolerance.x * tolerance.x);
    if (kPenumbraEvsmComponents == 4u) p_max = min(p_max, penumbra_chebyshev_upper_bound(moments.zw, warped.y, tolerance.y * tolerance.y));
    return p_max;
}

// Peters & Klein 2015, Algorithm 3 ("Hamburger 4MSM"): the shadow intensity, the
// smallest possible fraction of occluders in front of `receiver` over all depth
// distributions with these four moments (bounded by a three-point distribution).
float penumbra_msm_hamburger_intensity(vec4 moments, float receiver, float moment_bias) {
    // 1. Bias the moments toward those of a spread distribution: keeps the Hankel matrix
    //    positive definite under rounding.
    const vec4 b = mix(moments, vec4(0.5), moment_bias);
    // 2. Solve [1 b1 b2; b1 b2 b3; b2 b3 b4] c = (1, z, z^2) by its LDL^T (Cholesky) factors.
    const float d2 = b.y - b.x * b.x;
    const float l32 = (b.z - b.x * b.y) / d2;
    const float d3 = b.w - b.y * b.y - l32 * l32 * d2;
    const float y2 = receiver - b.x;
    const float y3 = receiver * receiver - b.y - l32 * y2;
    const float c3 = y3 / d3;
    const float c2 = y2 / d2 - l32 * c3;
    const float c1 = 1.0 - b.x * c2 - b.y * c3;
    // 3. The other two support points: the roots of c3 z^2 + c2 z + c1.
    const float p = c2 / c3;
    const float q = c1 / c3;
    const float r = sqrt(max(0.25 * p * p - q, 0.0));
    const float z2 = -0.5 * p - r;
    const float z3 = -0.5 * p + r;
    // 4.-6. The weight of the support points in front of the receiver.
    if (receiver <= z2) return 0.0;
    if (receiver <= z3) {
        return clamp((receiver * z3 - b.x * (receiver + z3) + b.y) / ((z3 - z2) * (receiver - z2)), 0.0, 1.0);
    }
    return clamp(1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((receiver - z2) * (receiver - z3)), 0.0, 1.0);
}

// msm: four moments, optionally stored with the optimized quantization (an affine map,
// so it commutes with the filtering and is undone after it).
float penumbra_msm_visibility(vec4 moments, float receiver) {
    if (kPenumbraMsmQuantized) moments = penumbra_msm_dequantize(moments);
    return 1.0 - penumbra_msm_hamburger_intensity(moments, receiver, penumbra_shadow.msm_moment_bias);
}

// The visibility of a receiver at `receiver` (distance, 0..1, larger = farther from the
// light) through filtered `moments`, for the configured moment filter, with light-bleeding
// reduction. Shared by the sun's cascades and the spot and point lights (local_lights.glsl).
float penumbra_moments_visibility(vec4 moments, float receiver) {
    float visibility;
    if (kPenumbraFilterMode == PENUMBRA_FILTER_EVSM) {
        visibility = penumbra_evsm_visibility(moments, receiver, vec2(penumbra_shadow.evsm_positive_exponent, penumbra_shadow.evsm_negative_exponent));
    } else if (kPenumbraFilterMode == PENUMBRA_FILTER_MSM) {
        visibility = penumbra_msm_visibility(moments, receiver);
    } else {
        visibility = penumbra_vsm_visibility(moments, receiver);
    }
    return penumbra_reduce_light_bleeding(visibility, penumbra_shadow.light_bleeding_reduction);
}

// vsm, evsm, msm through one cascade: the receiver's distance is 1 - its reverse-Z depth.
float penumbra_shadow_moments(int cascade, PenumbraShadowCoord coord, vec2 pixel) {
    return penumbra_moments_visibility(penumbra_fetch_moments(cascade, coord.uv, pixel), 1.0 - coord.depth);
}

#endif

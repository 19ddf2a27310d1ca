// Moment filters of the shadow library (included by shadow.glsl): VSM, EVSM and MSM
// read the moments map that the moments pass rendered (and blurred) per cascade. The
// receiver's distance is 1 - its reverse-Z depth, as in the moments (moments.glsl).
#ifndef PENUMBRA_SHADOW_MOMENTS_GLSL
#define PENUMBRA_SHADOW_MOMENTS_GLSL

#include "moments.glsl"

// The smallest depth difference (in distance units, 0..1 over the cascade's depth range)
// that the moment filters resolve: the minimum variance is its square (warped for EVSM).
// It absorbs float rounding of the second moment (d^2 - mean^2 cancels).
const float kMomentDepthTolerance = 5e-4;

// Linear filtering (and the optional Poisson taps) average the moments: the average of
// a moment vector is the moment vector of the mixed distribution, which is why moments
// can be prefiltered at all.
vec4 fetch_moments(int cascade, vec2 uv) {
    if (!kMomentsPoisson) return texture(shadow_moments, vec3(uv, float(cascade)));
    const mat2 rotation = sample_rotation();
    const vec2 radius_uv = vec2(frame.filter_params.y * shadow_texel_uv());
    vec4 sum = vec4(0.0);
    for (uint i = 0u; i < 16u; ++i) {
        sum += texture(shadow_moments, vec3(uv + (rotation * poisson_tap(16u, i)) * radius_uv, float(cascade)));
    }
    return sum / 16.0;
}

// Lauritzen 2007 (GPU Gems 3, ch. 8): light bleeding shows up as the low tail of the
// bound, so remap [amount, 1] to [0, 1], trading some softness for darker bleeding.
float reduce_light_bleeding(float p_max, float amount) { return clamp((p_max - amount) / (1.0 - amount), 0.0, 1.0); }

// Chebyshev's one-sided inequality (Donnelly & Lauritzen 2006): an upper bound on the
// fraction of occluders at least as far as `receiver`, given the mean and second moment.
float chebyshev_upper_bound(vec2 moments, float receiver, float min_variance) {
    if (receiver <= moments.x) return 1.0;
    const float variance = max(moments.y - moments.x * moments.x, min_variance);
    const float difference = receiver - moments.x;
    return variance / (variance + difference * difference);
}

// vsm: Chebyshev's bound on (d, d^2).
float vsm_visibility(vec4 moments, float receiver) {
    const float min_variance = kMomentDepthTolerance * kMomentDepthTolerance;
    return chebyshev_upper_bound(moments.xy, receiver, min_variance);
}

// evsm: the bound on exponentially warped depths (Lauritzen & McCool 2008). The warp
// makes the receiver's distance to far occluders huge relative to the variance, which
// suppresses most of VSM's bleeding; the negative warp (4 components) bounds the other
// side. The tolerance is scaled by the warp's slope, d/dd e^{c w} = 2 c e^{c w}.
float evsm_visibility(vec4 moments, float receiver, vec2 exponents) {
    const vec2 warped = evsm_warp(receiver, exponents);
    const vec2 tolerance = kMomentDepthTolerance * 2.0 * exponents * abs(warped);
    float p_max = chebyshev_upper_bound(moments.xy, warped.x, tolerance.x * tolerance.x);
    if (kEvsmComponents == 4u) p_max = min(p_max, chebyshev_upper_bound(moments.zw, warped.y, tolerance.y * tolerance.y));
    return p_max;
}

// Peters & Klein 2015, Algorithm 3 ("Hamburger 4MSM"): the shadow intensity, the
// smallest possible fraction of occluders in front of `receiver` over all depth
// distributions with these four moments (bounded by a three-point distribution).
float msm_hamburger_intensity(vec4 moments, float receiver, float moment_bias) {
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
float msm_visibility(vec4 moments, float receiver) {
    if (kMsmQuantized) moments = msm_dequantize(moments);
    return 1.0 - msm_hamburger_intensity(moments, receiver, frame.moment_params.w);
}

// The visibility of a receiver at `receiver` (distance, 0..1, larger = farther from the
// light) through filtered `moments`, for the configured moment filter, with light-bleeding
// reduction. Shared by the sun's cascades and the spot and point lights (local_lights.glsl).
float moments_visibility(vec4 moments, float receiver) {
    float visibility;
    if (kFilterMode == PENUMBRA_FILTER_EVSM) {
        visibility = evsm_visibility(moments, receiver, frame.moment_params.yz);
    } else if (kFilterMode == PENUMBRA_FILTER_MSM) {
        visibility = msm_visibility(moments, receiver);
    } else {
        visibility = vsm_visibility(moments, receiver);
    }
    return reduce_light_bleeding(visibility, frame.moment_params.x);
}

// vsm, evsm, msm through one cascade: the receiver's distance is 1 - its reverse-Z depth.
float shadow_moment_filter(int cascade, ShadowCoord coord) {
    return moments_visibility(fetch_moments(cascade, coord.uv), 1.0 - coord.depth);
}

#endif

// Moment encodings of an occluder distance for the prefiltered shadow filters, shared
// by Penumbra's moments conversion (which writes them) and the shadow library (which reads them).
// The distance is d = 1 - reverse-Z depth, in [0, 1], larger = farther from the light.
//
//   VSM:  (d, d^2), Donnelly & Lauritzen 2006, "Variance Shadow Maps".
//   EVSM: (e^{c+ w}, e^{2 c+ w}, -e^{-c- w}, e^{-2 c- w}) with w = 2 d - 1, Lauritzen & McCool
//         2008, "Layered Variance Shadow Maps" (exponential warp); 2 components keep the
//         positive warp only.
//   MSM:  (d, d^2, d^3, d^4), Peters & Klein 2015, "Moment Shadow Mapping", optionally
//         transformed by their optimized quantization (section 4.3) for RGBA16 storage.
#ifndef PENUMBRA_GLSL_MOMENTS
#define PENUMBRA_GLSL_MOMENTS

#include "penumbra/glsl/dialect.glsl"

// Both warps of EVSM: x = e^{c+ w} (positive), y = -e^{-c- w} (negative); w = 2 d - 1 in [-1, 1]
// centres the range so that the exponents reach the format's limits symmetrically.
vec2 penumbra_evsm_warp(float distance, vec2 exponents) {
    const float w = 2.0 * distance - 1.0;
    return vec2(exp(exponents.x * w), -exp(-exponents.y * w));
}

// Peters & Klein 2015, eq. in section 4.3: an affine map of (d, d^2, d^3, d^4) whose
// result stays in [0, 1] and spreads the information evenly over 16-bit channels. The
// published matrices multiply a row vector (b M): the result is b's components times M's
// rows, summed (written out, so that GLSL and HLSL read the rows alike).
PENUMBRA_CONST vec4 kPenumbraMsmQuantization[4] = {vec4(-2.07224649, 13.7948857237, 0.105877704, 9.7924062118),
                                                   vec4(32.23703778, -59.4683975703, -1.9077466311, -33.7652110555),
                                                   vec4(-68.571074599, 82.0359750338, 9.3496555107, 47.9456096605),
                                                   vec4(39.3703274134, -35.364903257, -6.6543490743, -23.9728048165)};
PENUMBRA_CONST vec4 kPenumbraMsmDequantization[4] = {vec4(0.2227744146, 0.1549679261, 0.1451988946, 0.163127443),
                                                     vec4(0.0771972861, 0.1394629426, 0.2120202157, 0.2591432266),
                                                     vec4(0.7926986636, 0.7963415838, 0.7258694464, 0.6539092497),
                                                     vec4(0.0319417555, -0.1722823173, -0.2758014811, -0.3376131734)};
PENUMBRA_CONST vec4 kPenumbraMsmQuantizationOffset = vec4(0.035955884801, 0.0, 0.0, 0.0);

// The row vector b times the matrix of these rows.
vec4 penumbra_times_rows(vec4 b, vec4 row0, vec4 row1, vec4 row2, vec4 row3) {
    return b.x * row0 + b.y * row1 + b.z * row2 + b.w * row3;
}

vec4 penumbra_msm_quantize(vec4 moments) {
    return penumbra_times_rows(moments, kPenumbraMsmQuantization[0], kPenumbraMsmQuantization[1],
                               kPenumbraMsmQuantization[2], kPenumbraMsmQuantization[3]) +
           kPenumbraMsmQuantizationOffset;
}
vec4 penumbra_msm_dequantize(vec4 stored) {
    return penumbra_times_rows(stored - kPenumbraMsmQuantizationOffset, kPenumbraMsmDequantization[0],
                               kPenumbraMsmDequantization[1], kPenumbraMsmDequantization[2],
                               kPenumbraMsmDequantization[3]);
}

// The moments stored for an occluder at `distance`. `distance_dx`, `distance_dy` are its
// slopes per texel (from the neighbouring texels of the depth map): VSM adds the variance of the plane over
// the texel, 1/4 (dx^2 + dy^2) (Donnelly & Lauritzen 2006, section 3.2), against acne.
vec4 penumbra_encode_moments(uint filter_mode, float distance, float distance_dx, float distance_dy, vec2 evsm_exponents,
                    bool msm_quantized) {
    if (filter_mode == PENUMBRA_FILTER_EVSM) {
        const vec2 warped = penumbra_evsm_warp(distance, evsm_exponents);
        return vec4(warped.x, warped.x * warped.x, warped.y, warped.y * warped.y);
    }
    if (filter_mode == PENUMBRA_FILTER_MSM) {
        const float square = distance * distance;
        const vec4 moments = vec4(distance, square, square * distance, square * square);
        return msm_quantized ? penumbra_msm_quantize(moments) : moments;
    }
    const float slope_variance = 0.25 * (distance_dx * distance_dx + distance_dy * distance_dy);
    return vec4(distance, distance * distance + slope_variance, 0.0, 0.0);
}

#endif

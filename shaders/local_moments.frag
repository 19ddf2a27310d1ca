#version 460
// Local lights' moments pass (vsm, evsm, msm for spot and point lights): converts one
// layer of the local shadow map from reverse-Z depth to the moments of the occluder's
// linear distance along the layer's axis, divided by the far plane (the range). Perspective depth
// is hyperbolic (most of its range lies next to the near plane), so a fixed minimum
// variance or light-bleeding threshold would mean centimetres near the light and metres
// at its range; the linear distance keeps them uniform, as the sun's orthographic depth is.
// Dividing by the range rather than normalising over [near, far] keeps the nearest caster
// (which defines the near plane) off distance 0: a caster face at exactly 0 or 1 makes
// the moment-biased distribution of MSM a two-point one, whose Hankel matrix is singular.
// Converting the depth map (instead of rendering the casters again) gives the same
// moments per texel at the cost of one full-screen triangle per layer.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(set = 0, binding = PENUMBRA_BINDING_BLUR_SOURCE) uniform sampler2DArray local_depth;
layout(push_constant) uniform PushBlock { LocalMomentsPushConstants pass; };

#include "penumbra/glsl/filter_constants.glsl"
#include "penumbra/glsl/moments.glsl"

layout(location = 0) out vec4 out_moments;

// Beyond this change of distance between neighbouring texels (normalised units) the
// neighbours lie on different surfaces: their difference is a silhouette, not a slope,
// and must not widen the texel's variance.
const float kMaxSlopePerTexel = 0.02;

float slope_or_zero(float difference) { return abs(difference) <= kMaxSlopePerTexel ? difference : 0.0; }

void main() {
    const float depth = texelFetch(local_depth, ivec3(ivec2(gl_FragCoord.xy), int(pass.layer.x)), 0).r;
    const float n = pass.depth_range.x;
    const float f = pass.depth_range.y;
    // Inverse of reverse-Z perspective depth = b / z - a, a = n / (f - n), b = f n / (f - n);
    // "nothing cast" (depth 0) becomes the far plane, distance 1.
    const float view_depth = (f * n / (f - n)) / (depth + n / (f - n));
    const float distance = clamp(view_depth / f, 0.0, 1.0);
    const float distance_dx = slope_or_zero(dFdx(distance));
    const float distance_dy = slope_or_zero(dFdy(distance));
    out_moments = penumbra_encode_moments(kPenumbraFilterMode, distance, distance_dx, distance_dy, pass.depth_range.zw,
                                          kPenumbraMsmQuantized);
}

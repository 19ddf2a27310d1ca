#version 460
// Moments from depth (vsm, evsm, msm; docs/filters.md): converts one layer of a reverse-Z
// depth map, rendered by the ordinary depth pass, to the moments of each texel's occluder
// distance (penumbra/glsl/moments.glsl) in the moments map. For the sun's orthographic
// cascades the distance is 1 - depth; for a spot or point light's perspective layer, the
// linear distance along the layer's axis over the light's range (perspective depth is
// hyperbolic, and a fixed minimum variance or light-bleeding threshold would mean
// centimetres near the light and metres at its range; dividing by the range rather than
// normalising over [near, far] keeps the nearest caster off distance 0, where MSM's
// moment-biased distribution turns singular). "Nothing cast" (depth 0) becomes distance 1.
// Rendering the casters once into depth and converting here replaces rasterising every
// caster a second time into a fat colour target.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"
#include "moments_storage.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2DArray depth_map;  // nearest
layout(set = 0, binding = 1, PENUMBRA_MOMENTS_QUALIFIER) uniform writeonly PENUMBRA_MOMENTS_IMAGE moments_map;
layout(push_constant) uniform PushBlock { MomentsPushConstants pass; };

#include "penumbra/glsl/filter_constants.glsl"
#include "penumbra/glsl/moments.glsl"

// Beyond this change of distance between neighbouring texels (normalised units) the two
// lie on different surfaces: a silhouette, not a slope, which must not widen the variance.
const float kMaxSlopePerTexel = 0.02;

float distance_at(ivec2 texel) {
    const ivec3 layer_texel = ivec3(penumbra_moments_layer_texel(pass, texel), int(pass.layer.x));
    const float depth = texelFetch(depth_map, layer_texel, 0).r;
    const float n = pass.depth_range.x;
    const float f = pass.depth_range.y;
    if (f <= 0.0) return 1.0 - depth;  // orthographic (the sun's cascades)
    // Inverse of reverse-Z perspective depth = b / z - a, a = n / (f - n), b = f n / (f - n).
    const float view_depth = (f * n / (f - n)) / (depth + n / (f - n));
    return clamp(view_depth / f, 0.0, 1.0);
}

// The slope of the occluder's surface along one axis, as a fragment shader's derivative of
// a rasterised caster gives it: of the two one-texel differences, the one that stays on the
// surface (the smaller), 0 where both cross a silhouette.
float slope(float centre, float before, float after) {
    const float forward = after - centre;
    const float backward = centre - before;
    const float smaller = abs(forward) <= abs(backward) ? forward : backward;
    return abs(smaller) <= kMaxSlopePerTexel ? smaller : 0.0;
}

void main() {
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, pass.region.zw))) return;
    const ivec2 texel = ivec2(pass.region.xy + gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, ivec2(pass.layer.y)))) return;
    const float distance = distance_at(texel);
    const float dx = slope(distance, distance_at(texel - ivec2(1, 0)), distance_at(texel + ivec2(1, 0)));
    const float dy = slope(distance, distance_at(texel - ivec2(0, 1)), distance_at(texel + ivec2(0, 1)));
    const vec4 moments =
        penumbra_encode_moments(kPenumbraFilterMode, distance, dx, dy, pass.depth_range.zw, kPenumbraMsmQuantized);
    PENUMBRA_STORE_MOMENTS(moments_map, ivec3(penumbra_moments_layer_texel(pass, texel), int(pass.layer.x)), moments);
}

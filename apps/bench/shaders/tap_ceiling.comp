#version 460
// Sampling-rate ceiling of compute shaders (`penumbra bench --ceiling compute-taps`): the
// taps of tap_ceiling_taps.glsl once per pixel in 8 x 8 workgroups, as Penumbra's compute
// resolve (shaders/visibility_resolve.comp) runs, into an RGBA8 storage image: the limit
// that the deferred resolve is read against.
#extension GL_GOOGLE_include_directive : require
#include "bench_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2DArrayShadow shadow_map;
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D target;
layout(push_constant) uniform PushBlock { TapCeilingPushConstants params; };

#include "tap_ceiling_taps.glsl"

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(target)))) return;
    imageStore(target, pixel, vec4(vec3(ceiling_taps(shadow_map, vec2(pixel) + 0.5, params)), 1.0));
}

#version 460
// One direction of the separable Gaussian blur of the moments map, for one layer: a
// full-screen triangle (shaders/fullscreen.vert) reads the other ping-pong image. Moments
// are linear in the distribution, so blurring them is filtering the shadow (Donnelly &
// Lauritzen 2006); taps beyond the edge of the layer's used corner clamp to it.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(set = 0, binding = PENUMBRA_BINDING_BLUR_SOURCE) uniform sampler2DArray source;
layout(push_constant) uniform PushBlock { BlurPushConstants blur; };

layout(location = 0) out vec4 out_moments;

void main() {
    const int layer = int(blur.params.x);
    const int radius = int(blur.params.y);
    const ivec2 direction = blur.params.z != 0u ? ivec2(1, 0) : ivec2(0, 1);
    // A local light below the map's resolution uses only the top-left corner of its layer.
    const ivec2 used = blur.params.w > 0u ? ivec2(int(blur.params.w)) : textureSize(source, 0).xy;
    const ivec2 last_texel = min(used, textureSize(source, 0).xy) - 1;
    const ivec2 texel = ivec2(gl_FragCoord.xy);
    // sigma = radius / 2: the kernel's ends weigh e^-2 (0.14) of its centre.
    const float inverse_two_sigma_squared = 2.0 / float(max(radius * radius, 1));
    vec4 sum = vec4(0.0);
    float weight_sum = 0.0;
    for (int i = -radius; i <= radius; ++i) {
        const float weight = exp(-float(i * i) * inverse_two_sigma_squared);
        const ivec2 tap = clamp(texel + i * direction, ivec2(0), last_texel);
        sum += weight * texelFetch(source, ivec3(tap, layer), 0);
        weight_sum += weight;
    }
    out_moments = sum / weight_sum;
}

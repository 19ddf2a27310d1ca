#version 460
// Sampling-rate ceiling (`penumbra bench --ceiling taps`): every pixel takes `taps`
// depth-comparison lookups from a shadow map through the lighting pass's sampler
// (bilinear hardware PCF), so the pass is bound by texture filtering, not by ALU or
// geometry. The taps walk a fixed 16-point disc whose radius grows every 16 taps, the
// way a PCF or PCSS kernel reads neighbouring texels, and cycle through the layers.
#extension GL_GOOGLE_include_directive : require
#include "bench_shared.h"

layout(set = 0, binding = 0) uniform sampler2DArrayShadow shadow_map;
layout(push_constant) uniform PushBlock { TapCeilingPushConstants params; };
layout(location = 0) out vec4 out_color;

const vec2 kDisc[16] = vec2[](vec2(-0.94, -0.40), vec2(0.95, -0.77), vec2(-0.09, -0.93), vec2(0.34, 0.29),
                              vec2(-0.92, 0.46), vec2(-0.82, 0.15), vec2(-0.38, 0.28), vec2(-0.20, -0.16),
                              vec2(0.97, 0.76), vec2(0.44, -0.59), vec2(0.54, 0.76), vec2(-0.26, 0.99),
                              vec2(-0.88, -0.05), vec2(0.54, 0.85), vec2(0.17, -0.75), vec2(-0.71, -0.69));

void main() {
    const vec2 uv = gl_FragCoord.xy * params.target_and_texel.xy;
    const float texel = params.target_and_texel.z;
    const uint taps = params.counts.x;
    const uint layers = max(params.counts.y, 1u);
    float lit = 0.0;
    for (uint i = 0u; i < taps; ++i) {
        const vec2 offset = kDisc[i & 15u] * texel * float(1u + (i >> 4u));
        lit += texture(shadow_map, vec4(uv + offset, float(i % layers), 0.5));
    }
    out_color = vec4(vec3(lit / float(max(taps, 1u))), 1.0);
}

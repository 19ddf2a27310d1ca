#version 460
// Sampling-rate ceiling of fragment shaders (`penumbra bench --ceiling taps`): a
// full-screen pass whose every pixel takes the taps of tap_ceiling_taps.glsl, so the pass
// is bound by texture filtering on the units that run fragment shaders (the forward
// lighting pass's), not by ALU or geometry.
#extension GL_GOOGLE_include_directive : require
#include "bench_shared.h"

layout(set = 0, binding = 0) uniform sampler2DArrayShadow shadow_map;
layout(push_constant) uniform PushBlock { TapCeilingPushConstants params; };
layout(location = 0) out vec4 out_color;

#include "tap_ceiling_taps.glsl"

void main() { out_color = vec4(vec3(ceiling_taps(shadow_map, gl_FragCoord.xy, params)), 1.0); }

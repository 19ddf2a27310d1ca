#version 460
// One direction of the separable Gaussian blur of the moments map, for one layer, from one
// storage image into the other (the moments map and its scratch image). Moments are linear
// in the depth distribution, so blurring them filters the shadow (Donnelly & Lauritzen
// 2006). Taps beyond the edge of the texels the layer uses clamp to them, so a local
// light's texels never mix with another's, and a toroidal cascade's opposite edges (side
// by side in the layer where it wraps) never mix either.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"
#include "moments_storage.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, PENUMBRA_MOMENTS_QUALIFIER) uniform readonly PENUMBRA_MOMENTS_IMAGE source;
layout(set = 0, binding = 1, PENUMBRA_MOMENTS_QUALIFIER) uniform writeonly PENUMBRA_MOMENTS_IMAGE target;
layout(push_constant) uniform PushBlock { MomentsPushConstants pass; };

void main() {
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, pass.region.zw))) return;
    const ivec2 texel = ivec2(pass.region.xy + gl_GlobalInvocationID.xy);
    const int used = int(pass.layer.y);
    if (any(greaterThanEqual(texel, ivec2(used)))) return;
    const int layer = int(pass.layer.x);
    const int radius = int(pass.layer.z);
    const ivec2 direction = pass.layer.w != 0u ? ivec2(1, 0) : ivec2(0, 1);
    // sigma = radius / 2: the kernel's ends weigh e^-2 (0.14) of its centre.
    const float inverse_two_sigma_squared = 2.0 / float(max(radius * radius, 1));
    vec4 sum = vec4(0.0);
    float weight_sum = 0.0;
    for (int i = -radius; i <= radius; ++i) {
        const float weight = exp(-float(i * i) * inverse_two_sigma_squared);
        const ivec2 tap = penumbra_moments_layer_texel(pass, texel + i * direction);
        sum += weight * PENUMBRA_LOAD_MOMENTS(source, ivec3(tap, layer));
        weight_sum += weight;
    }
    PENUMBRA_STORE_MOMENTS(target, ivec3(penumbra_moments_layer_texel(pass, texel), layer), sum / weight_sum);
}

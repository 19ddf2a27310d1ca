#version 460
// Alpha-masked casters: discard where the mask's alpha is below the cutoff, so that leaves
// and fences cast shadows with holes. Opaque casters use no fragment shader.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(push_constant) uniform PushBlock { CasterPushConstants caster; };
layout(set = PENUMBRA_SET_ALPHA_MASK, binding = PENUMBRA_BINDING_ALPHA_MASK) uniform sampler2D alpha_mask;

layout(location = 0) in vec2 in_uv;

void main() {
    if (caster.alpha_scale * texture(alpha_mask, in_uv).a < caster.alpha_cutoff) discard;
}

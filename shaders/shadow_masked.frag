#version 460
// Alpha-masked casters: discard where the material's alpha is below its cutoff so that
// leaves and fences cast shadows with holes. Opaque casters use no fragment shader.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_shared.h"

layout(push_constant) uniform PushBlock { DrawPushConstants draw; };
layout(set = PENUMBRA_SET_MATERIAL, binding = PENUMBRA_BINDING_BASE_COLOR_TEXTURE) uniform sampler2D base_color_texture;

layout(location = 0) in vec2 in_uv;

void main() {
    float alpha = draw.base_color.a;
    if (draw.flags.y != 0u) alpha *= texture(base_color_texture, in_uv).a;
    if (alpha < draw.material.x) discard;
}

#version 460
// The example's own fragment shader: the sun's visibility through Penumbra's shadow library,
// whose descriptor set this pipeline binds at set 0. A renderer would multiply its sun
// lighting by it; here it is the output (1 lit, 0 in shadow or facing away from the sun).
#extension GL_GOOGLE_include_directive : require
#define PENUMBRA_SHADOW_SET 0
#include "penumbra/shadow.glsl"
#include "penumbra/shadow_fragment.glsl"

layout(location = 0) in vec3 in_world_position;
layout(location = 1) in vec3 in_world_normal;
layout(location = 0) out float out_visibility;

void main() {
    const vec3 normal = normalize(in_world_normal);
    const PenumbraSunReceiver receiver = penumbra_sun_receiver_fragment(in_world_position, normal);
    out_visibility = penumbra_sun_visibility(receiver, normal);
}

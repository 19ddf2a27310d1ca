// Fragment-shader helpers of penumbra/shadow.glsl (include it first): they take the
// receiver-plane gradients and the geometric normal from screen-space derivatives, so
// call them in uniform control flow, before any discard or per-pixel branch (the
// derivatives of a quad whose pixels have left it are undefined).
//   vec3 penumbra_geometric_normal(world_position, shading_normal)
//   PenumbraSunReceiver penumbra_sun_receiver_fragment(world_position, normal)
#ifndef PENUMBRA_SHADOW_FRAGMENT_GLSL
#define PENUMBRA_SHADOW_FRAGMENT_GLSL

#include "penumbra/glsl/fragment.glsl"

// The sun's receiver at this fragment (gl_FragCoord), with receiver-plane gradients.
PenumbraSunReceiver penumbra_sun_receiver_fragment(vec3 world_position, vec3 normal) {
    return penumbra_sun_receiver_with_derivatives(world_position, normal, gl_FragCoord.xy);
}

#endif

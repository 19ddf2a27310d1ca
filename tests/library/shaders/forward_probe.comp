#version 460
// A caller's forward shading reduced to what Penumbra gives it: penumbra/shadow.glsl's sun
// and local-light visibility at the ground points of the library tests' top-down view
// (y = 0, facing up), one invocation per pixel. Compiled as is (the filter specialised
// with ShadowSystem::shader_specialization()) and with PENUMBRA_FILTER_FROM_UNIFORMS (one
// pipeline for every filter), so tests/library/test_forward_filter_modes.cpp can compare
// the two.
#extension GL_GOOGLE_include_directive : require
#define PENUMBRA_SHADOW_SET 0
#include "penumbra/shadow.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, set = 1, binding = 0) writeonly buffer Visibility { vec2 values[]; };
layout(push_constant) uniform Probe {
    float half_extent;  // the ground's half-width the view sees (metres)
    uint size;          // pixels per side
    uint light;         // the local light's index in set_lights()
};

void main() {
    const uvec2 texel = gl_GlobalInvocationID.xy;
    if (texel.x >= size || texel.y >= size) return;
    const vec2 pixel = vec2(texel) + 0.5;
    const vec2 ndc = 2.0 * pixel / float(size) - 1.0;
    const vec3 world = vec3(ndc.x * half_extent, 0.0, ndc.y * half_extent);
    const vec3 up = vec3(0.0, 1.0, 0.0);
    const float sun = penumbra_sun_visibility(penumbra_sun_receiver(world, up, pixel), up);
    const float local = penumbra_light_visibility(light, world, up, up, pixel);
    values[texel.y * size + texel.x] = vec2(sun, local);
}

// The fragment-stage part of the shadow library (penumbra/shadow_fragment.glsl and
// penumbra/shadow_fragment.hlsl): receiver-plane gradients and the geometric normal from
// screen-space derivatives. Call in uniform control flow, before any discard or per-pixel
// branch (the derivatives of a quad whose pixels have left it are undefined).
#ifndef PENUMBRA_GLSL_FRAGMENT
#define PENUMBRA_GLSL_FRAGMENT

#include "penumbra/glsl/dialect.glsl"

// The receiver's geometric plane (receiver-plane bias of spot and point lights, the sun's
// face test): the cross product of the position's screen-space derivatives, or the shading
// normal where the triangle is too small or too oblique for them.
vec3 penumbra_geometric_normal(vec3 world_position, vec3 shading_normal) {
    const vec3 n = cross(dFdx(world_position), dFdy(world_position));
    const float length_squared = dot(n, n);
    return length_squared > 1e-20 ? n * inversesqrt(length_squared) : shading_normal;
}

// How the virtual shadow map's coordinates in `level` change with the light view's
// (x, y, z) in metres: affine, one scale per level (penumbra_project_to_virtual_level).
vec3 penumbra_virtual_coord_step(int level, vec3 light_step) {
    const PenumbraVirtualLevel l = penumbra_virtual.levels[level];
    return vec3(light_step.xy * (l.texels_per_metre / float(penumbra_virtual_side())), light_step.z * l.depth_scale);
}

// The sun's receiver at the fragment at `pixel`, with receiver-plane gradients. Cascades:
// the derivatives of the receiver's coordinates in its cascade and the next; where the
// quad's pixels chose different cascades they mix two projections, and there is no
// gradient. The virtual shadow map: the derivatives of the light view's coordinates, which
// no level boundary breaks, scaled into the receiver's level (without the normal offset,
// which moves a plane along itself and leaves its gradient).
PenumbraSunReceiver penumbra_sun_receiver_with_derivatives(vec3 world_position, vec3 normal, vec2 pixel) {
    PenumbraSunReceiver receiver = penumbra_sun_receiver(world_position, normal, pixel);
    const ivec2 cascades = penumbra_receiver_cascades(receiver.cascade);
    vec3 coord_dx[2];
    vec3 coord_dy[2];
    bool seam = false;
    // The technique is a uniform: both branches stay in uniform control flow.
    if (penumbra_sun_is_virtual()) {
        const vec3 light = PENUMBRA_MUL(penumbra_virtual.light_view, vec4(world_position, 1.0)).xyz;
        const vec3 light_dx = dFdx(light);
        const vec3 light_dy = dFdy(light);
        for (int i = 0; i < 2; ++i) {
            coord_dx[i] = penumbra_virtual_coord_step(cascades[i], light_dx);
            coord_dy[i] = penumbra_virtual_coord_step(cascades[i], light_dy);
        }
    } else {
        for (int i = 0; i < 2; ++i) {
            const vec3 coord = penumbra_project_to_cascade(cascades[i], world_position, normal);
            coord_dx[i] = dFdx(coord);
            coord_dy[i] = dFdy(coord);
        }
        seam = fwidth(float(receiver.cascade)) != 0.0;
    }
    penumbra_set_receiver_plane(receiver, coord_dx, coord_dy, seam);
    receiver.face_normal = penumbra_geometric_normal(world_position, normal);
    return receiver;
}

#endif

// Fragment-shader helpers of penumbra/shadow.glsl (include it first): they take the
// receiver-plane gradients and the geometric normal from screen-space derivatives, so
// call them in uniform control flow, before any discard or per-pixel branch (the
// derivatives of a quad whose pixels have left it are undefined).
#ifndef PENUMBRA_SHADOW_FRAGMENT_GLSL
#define PENUMBRA_SHADOW_FRAGMENT_GLSL

// The receiver's geometric plane (receiver-plane bias of spot and point lights, the sun's
// face test): the cross
// product of the position's screen-space derivatives, or the shading normal where the
// triangle is too small or too oblique for them.
vec3 penumbra_geometric_normal(vec3 world_position, vec3 shading_normal) {
    const vec3 n = cross(dFdx(world_position), dFdy(world_position));
    const float length_squared = dot(n, n);
    return length_squared > 1e-20 ? n * inversesqrt(length_squared) : shading_normal;
}

// The sun's receiver at this fragment, with receiver-plane gradients. Where the quad's
// pixels chose different cascades the derivatives mix two projections: no gradient there.
PenumbraSunReceiver penumbra_sun_receiver_fragment(vec3 world_position, vec3 normal) {
    PenumbraSunReceiver receiver = penumbra_sun_receiver(world_position, normal, gl_FragCoord.xy);
    const ivec2 cascades = penumbra_receiver_cascades(receiver.cascade);
    vec3 coord_dx[2];
    vec3 coord_dy[2];
    for (int i = 0; i < 2; ++i) {
        const vec3 coord = penumbra_project_to_cascade(cascades[i], world_position, normal);
        coord_dx[i] = dFdx(coord);
        coord_dy[i] = dFdy(coord);
    }
    const bool seam = fwidth(float(receiver.cascade)) != 0.0;
    penumbra_set_receiver_plane(receiver, coord_dx, coord_dy, seam);
    receiver.face_normal = penumbra_geometric_normal(world_position, normal);
    return receiver;
}

#endif

// Penumbra's shadow sampling library for the directional light's cascaded shadow map.
// Included by the lighting shader after the frame uniform block is declared.
//
// Cascade selection by view depth, a blend band between neighbouring cascades and a
// distance fade follow the usual cascaded-shadow-map practice (PSSM, Zhang et al.
// 2006; Microsoft's "Cascaded Shadow Maps" article). The map stores reverse-Z depth
// (1 = nearest the light), so a receiver is lit when its depth >= the stored depth:
// the sampler compares with VK_COMPARE_OP_GREATER_OR_EQUAL.
#ifndef PENUMBRA_SHADOW_GLSL
#define PENUMBRA_SHADOW_GLSL

layout(set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_SHADOW_MAP) uniform sampler2DArrayShadow shadow_map;

int cascade_count() { return int(frame.shadow_params.x); }

float cascade_split_far(int cascade) { return frame.cascade_split_far[cascade / 4][cascade % 4]; }

float cascade_split_near(int cascade) {
    return cascade == 0 ? frame.camera_params.x : cascade_split_far(cascade - 1);
}

float cascade_texel_world_size(int cascade) { return frame.cascade_texel_world_size[cascade / 4][cascade % 4]; }

// The first cascade whose far split lies beyond the view depth, or -1 past the last one.
int select_cascade(float view_depth) {
    for (int cascade = 0; cascade < cascade_count(); ++cascade) {
        if (view_depth <= cascade_split_far(cascade)) return cascade;
    }
    return -1;
}

// One hardware comparison tap (bilinear-filtered 2x2 comparison on most hardware).
// The receiver is moved along its normal by a multiple of the cascade's world texel size
// (normal-offset shadows, Holbert 2011): larger texels need a larger offset.
float sample_cascade(int cascade, vec3 world_position, vec3 world_normal) {
    const float offset = frame.shadow_params.y * cascade_texel_world_size(cascade);
    const vec4 clip = frame.cascade_view_projection[cascade] * vec4(world_position + world_normal * offset, 1.0);
    const vec3 ndc = clip.xyz / clip.w;
    const vec2 uv = ndc.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
    return texture(shadow_map, vec4(uv, float(cascade), ndc.z));
}

// Visibility of the sun in [0, 1] through `cascade` (from select_cascade, >= 0).
// Inside the last `blend width` fraction of a cascade the result blends linearly into the
// next cascade, hiding the resolution seam; the last cascade fades to fully lit over the
// same fraction before the shadow distance.
float sun_visibility(int cascade, vec3 world_position, vec3 world_normal, float view_depth) {
    float visibility = sample_cascade(cascade, world_position, world_normal);

    const float split_near = cascade_split_near(cascade);
    const float split_far = cascade_split_far(cascade);
    const float band = frame.shadow_params.z * (split_far - split_near);
    if (band > 0.0 && view_depth > split_far - band) {
        const float t = (view_depth - (split_far - band)) / band;
        const bool has_next = cascade + 1 < cascade_count();
        const float next = has_next ? sample_cascade(cascade + 1, world_position, world_normal) : 1.0;
        visibility = mix(visibility, next, t);
    }
    return visibility;
}

#endif

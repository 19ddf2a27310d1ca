// Penumbra's shadow sampling library for the directional light's cascaded shadow map.
// Included by the lighting shader after the frame uniform block is declared. Every
// filter (docs/filters.md) lives here and in the files it includes; the filter is a
// specialization constant (shadow_filter_constants.glsl).
//
// Cascade selection by view depth, a blend band between neighbouring cascades and a
// distance fade follow the usual cascaded-shadow-map practice (PSSM, Zhang et al.
// 2006; Microsoft's "Cascaded Shadow Maps" article). The map stores reverse-Z depth
// (1 = nearest the light), so a receiver is lit when its depth >= the stored depth:
// the comparison sampler uses VK_COMPARE_OP_GREATER_OR_EQUAL.
//
// Use: prepare_shadow_receiver() in uniform control flow (it takes screen-space
// derivatives), then sun_visibility() anywhere.
#ifndef PENUMBRA_SHADOW_GLSL
#define PENUMBRA_SHADOW_GLSL

layout(set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_SHADOW_MAP) uniform sampler2DArrayShadow shadow_map;
layout(set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_SHADOW_DEPTH) uniform sampler2DArray shadow_depth;
layout(set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_SHADOW_MOMENTS) uniform sampler2DArray shadow_moments;

#include "shadow_filter_constants.glsl"

int cascade_count() { return int(frame.shadow_params.x); }

float cascade_split_far(int cascade) { return frame.cascade_split_far[cascade / 4][cascade % 4]; }

float cascade_split_near(int cascade) {
    return cascade == 0 ? frame.camera_params.x : cascade_split_far(cascade - 1);
}

float cascade_texel_world_size(int cascade) { return frame.cascade_texel_world_size[cascade / 4][cascade % 4]; }

float shadow_texel_uv() { return frame.filter_params.w; }

// The first cascade whose far split lies beyond the view depth, or -1 past the last one.
int select_cascade(float view_depth) {
    for (int cascade = 0; cascade < cascade_count(); ++cascade) {
        if (view_depth <= cascade_split_far(cascade)) return cascade;
    }
    return -1;
}

// A receiver point in one cascade's shadow map.
struct ShadowCoord {
    vec2 uv;
    float depth;          // reverse-Z depth of the receiver (1 = nearest the light)
    vec2 depth_gradient;  // receiver plane dz/du, dz/dv (0 without receiver-plane bias)
};

// The receiver in the pixel's cascade ([0]) and in the next one ([1], for the blend band).
struct ShadowReceiver {
    ShadowCoord coords[2];
};

// Shadow-map coordinates of a receiver in `cascade`. The receiver is moved along its
// normal by a multiple of the cascade's world texel size (normal-offset shadows, Holbert
// 2011): larger texels need a larger offset.
vec3 project_to_cascade(int cascade, vec3 world_position, vec3 world_normal) {
    const float offset = frame.shadow_params.y * cascade_texel_world_size(cascade);
    const vec4 clip = frame.cascade_view_projection[cascade] * vec4(world_position + world_normal * offset, 1.0);
    const vec3 ndc = clip.xyz / clip.w;
    return vec3(ndc.xy * 0.5 + 0.5, ndc.z);
}

bool uses_receiver_plane_bias() {
    return kReceiverPlaneBias &&
           (kFilterMode == PENUMBRA_FILTER_PCF || kFilterMode == PENUMBRA_FILTER_POISSON ||
            kFilterMode == PENUMBRA_FILTER_PCSS);
}

// Receiver-plane depth bias (Isidoro 2006, "Shadow Mapping: GPU-based Tips and
// Techniques"): the receiver is locally a plane z(u, v). The chain rule links the
// screen-space derivatives, (dz/dx, dz/dy) = (dz/du, dz/dv) J with J the Jacobian of
// (u, v) over (x, y), so the plane's gradient is (dz/dx, dz/dy) J^-1. Clamped to the
// cascade's limit (grazing receivers, quads straddling a silhouette). Must be called in
// uniform control flow.
vec2 receiver_plane_depth_gradient(int cascade, vec3 coord) {
    const vec3 coord_dx = dFdx(coord);
    const vec3 coord_dy = dFdy(coord);
    const mat2 uv_jacobian = mat2(coord_dx.xy, coord_dy.xy);  // columns: d(u, v)/dx, d(u, v)/dy
    const float det = determinant(uv_jacobian);
    if (abs(det) < 1e-30) return vec2(0.0);
    const vec2 gradient = vec2(coord_dx.z, coord_dy.z) * inverse(uv_jacobian);
    const vec2 limit = frame.cascade_filter[cascade].zw;
    return clamp(gradient, -limit, limit);
}

// Both cascades' coordinates of the receiver, with their receiver-plane gradients.
// Call it in uniform control flow, before any per-pixel branch, return or discard: the
// derivatives of a quad whose pixels have left it are undefined. Where the quad's pixels
// chose different cascades the derivatives mix two projections, so the gradient is
// zeroed along cascade seams.
ShadowReceiver prepare_shadow_receiver(int cascade, vec3 world_position, vec3 world_normal) {
    const int last = max(cascade_count(), 1) - 1;
    const int current = clamp(cascade, 0, last);
    const int next = min(current + 1, last);
    const vec3 current_coord = project_to_cascade(current, world_position, world_normal);
    const vec3 next_coord = project_to_cascade(next, world_position, world_normal);
    ShadowReceiver receiver;
    receiver.coords[0] = ShadowCoord(current_coord.xy, current_coord.z, vec2(0.0));
    receiver.coords[1] = ShadowCoord(next_coord.xy, next_coord.z, vec2(0.0));
    if (uses_receiver_plane_bias()) {  // a specialization constant: uniform
        const vec2 current_gradient = receiver_plane_depth_gradient(current, current_coord);
        const vec2 next_gradient = receiver_plane_depth_gradient(next, next_coord);
        const bool seam = fwidth(float(cascade)) != 0.0;
        receiver.coords[0].depth_gradient = seam ? vec2(0.0) : current_gradient;
        receiver.coords[1].depth_gradient = seam ? vec2(0.0) : next_gradient;
    }
    return receiver;
}

#include "shadow_comparison.glsl"
#include "shadow_moments.glsl"

// Visibility through one cascade with the configured filter; lookups outside the map are lit.
float sample_cascade(int cascade, ShadowCoord coord) {
    if (any(lessThan(coord.uv, vec2(0.0))) || any(greaterThan(coord.uv, vec2(1.0)))) return 1.0;
    switch (kFilterMode) {
        case PENUMBRA_FILTER_PCF:
            return shadow_pcf(cascade, coord);
        case PENUMBRA_FILTER_POISSON:
            return shadow_poisson(cascade, coord);
        case PENUMBRA_FILTER_PCSS:
            return shadow_pcss(cascade, coord);
        case PENUMBRA_FILTER_VSM:
        case PENUMBRA_FILTER_EVSM:
        case PENUMBRA_FILTER_MSM:
            return shadow_moment_filter(cascade, coord);
        default:
            return shadow_hard(cascade, coord);
    }
}

// Visibility of the sun in [0, 1] through `cascade` (from select_cascade, >= 0).
// Inside the last `blend width` fraction of a cascade the result blends linearly into the
// next cascade, hiding the resolution seam; the last cascade fades to fully lit over the
// same fraction before the shadow distance. Every filter goes through here.
float sun_visibility(int cascade, ShadowReceiver receiver, float view_depth) {
    float visibility = sample_cascade(cascade, receiver.coords[0]);

    const float split_near = cascade_split_near(cascade);
    const float split_far = cascade_split_far(cascade);
    const float band = frame.shadow_params.z * (split_far - split_near);
    if (band > 0.0 && view_depth > split_far - band) {
        const float t = (view_depth - (split_far - band)) / band;
        const bool has_next = cascade + 1 < cascade_count();
        const float next = has_next ? sample_cascade(cascade + 1, receiver.coords[1]) : 1.0;
        visibility = mix(visibility, next, t);
    }
    return visibility;
}

#endif

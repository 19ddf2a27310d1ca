// The sun's cascaded shadow map (included by penumbra/shadow.glsl): cascade selection,
// receiver coordinates with normal offset and receiver-plane bias, the cascade's view for
// the filters (penumbra/glsl/filters.glsl), and the blend band between cascades.
//
// Cascade selection by view depth, a blend band between neighbouring cascades and a
// distance fade follow the usual cascaded-shadow-map practice (PSSM, Zhang et al. 2006;
// Microsoft's "Cascaded Shadow Maps" article). The map stores reverse-Z depth (1 = nearest
// the light), so a receiver is lit when its depth >= the stored depth: the comparison
// sampler uses VK_COMPARE_OP_GREATER_OR_EQUAL.
#ifndef PENUMBRA_GLSL_SUN
#define PENUMBRA_GLSL_SUN

#include "penumbra/glsl/dialect.glsl"

int penumbra_cascade_count() { return int(penumbra_shadow.cascade_count); }

float penumbra_cascade_split_far(int cascade) { return penumbra_shadow.cascades[cascade].split_far; }

float penumbra_cascade_split_near(int cascade) {
    return cascade == 0 ? penumbra_shadow.camera_near : penumbra_cascade_split_far(cascade - 1);
}

// Distance along the prepared camera's view direction.
float penumbra_view_depth(vec3 world_position) {
    return -PENUMBRA_MUL(penumbra_shadow.camera_view, vec4(world_position, 1.0)).z;
}

// The first cascade whose far split lies beyond the view depth, or -1 past the last one
// (and always -1 when the sun casts no shadow).
int penumbra_select_cascade(float view_depth) {
    for (int cascade = 0; cascade < penumbra_cascade_count(); ++cascade) {
        if (view_depth <= penumbra_cascade_split_far(cascade)) return cascade;
    }
    return -1;
}

// The sun's map a receiver at `world_position` reads: its cascade (by view depth), or with
// the virtual shadow map its level (penumbra_virtual_receiver_level); -1 for none.
int penumbra_sun_map_of(vec3 world_position) {
    if (penumbra_sun_is_virtual()) return penumbra_virtual_receiver_level(world_position);
    return penumbra_select_cascade(penumbra_view_depth(world_position));
}

// A receiver point in one cascade's shadow map.
struct PenumbraShadowCoord {
    vec2 uv;
    float depth;          // reverse-Z depth of the receiver (1 = nearest the light)
    vec2 depth_gradient;  // receiver plane dz/du, dz/dv (0 without receiver-plane bias)
};

// Shadow-map coordinates (u, v, reverse-Z depth) of a receiver in `cascade`. The receiver
// moves along its normal by a multiple of the cascade's world texel size (normal-offset
// shadows, Holbert 2011): larger texels need a larger offset.
vec3 penumbra_project_to_cascade(int cascade, vec3 world_position, vec3 world_normal) {
    if (penumbra_sun_is_virtual()) return penumbra_project_to_virtual_level(cascade, world_position, world_normal);
    const float offset = penumbra_shadow.normal_offset_texels * penumbra_shadow.cascades[cascade].texel_world_size;
    const vec4 clip = PENUMBRA_MUL(penumbra_shadow.cascades[cascade].view_projection, vec4(world_position + world_normal * offset, 1.0));
    const vec3 ndc = clip.xyz / clip.w;
    return vec3(ndc.xy * 0.5 + 0.5, ndc.z);
}

// Receiver-plane depth bias (Isidoro 2006, "Shadow Mapping: GPU-based Tips and
// Techniques"): the receiver is locally a plane z(u, v). The chain rule links the
// screen-space derivatives, (dz/dx, dz/dy) = (dz/du, dz/dv) J with J the Jacobian of
// (u, v) over (x, y), so the plane's gradient is (dz/dx, dz/dy) J^-1. `coord_dx` and
// `coord_dy` are how the projected coordinates change to the next pixel in x and y
// (dFdx/dFdy in a fragment shader, differences of neighbours in a compute shader).
// Clamped to the cascade's limit (grazing receivers, quads straddling a silhouette).
vec2 penumbra_receiver_plane_gradient(int cascade, vec3 coord_dx, vec3 coord_dy) {
    const vec2 gradient = penumbra_plane_gradient(vec2(coord_dx.z, coord_dy.z), coord_dx.xy, coord_dy.xy, 1e-30);
    const vec2 limit = penumbra_sun_is_virtual() ? penumbra_virtual_max_depth_gradient(cascade)
                                                 : penumbra_shadow.cascades[cascade].max_depth_gradient;
    return clamp(gradient, -limit, limit);
}

// A receiver of the sun: its cascade, and its coordinates in that cascade ([0]) and in
// the next one ([1], for the blend band).
struct PenumbraSunReceiver {
    int cascade;  // -1: beyond the last cascade, or the sun casts no shadow
    float view_depth;
    vec2 pixel;  // rotates the sampling patterns (gl_FragCoord.xy, or the pixel centre)
    // The geometric normal of the visible face (the shading normal itself where derivatives
    // are not available), for penumbra_faces_light().
    vec3 face_normal;
    PenumbraShadowCoord coords[2];
};

// The cascades a receiver's coordinates are taken in: its own (the first when it has
// none) and the next one (itself for the last).
ivec2 penumbra_receiver_cascades(int cascade) {
    if (penumbra_sun_is_virtual()) return ivec2(max(cascade, 0));  // one level, no blend band
    const int last = max(penumbra_cascade_count(), 1) - 1;
    const int current = clamp(cascade, 0, last);
    return ivec2(current, min(current + 1, last));
}

// Whether a receiver faces a light (`to_light`, any length): by its shading normal and by
// its face, the geometric normal turned to the shading normal's side. A face turned away is
// in its own shadow whatever its interpolated or bent normal says: the back-lit side of a
// leaf card, the faceted terminator of a smooth-shaded sphere.
bool penumbra_faces_light(vec3 normal, vec3 face_normal, vec3 to_light) {
    const vec3 face = dot(face_normal, normal) < 0.0 ? -face_normal : face_normal;
    return dot(normal, to_light) > 0.0 && dot(face, to_light) > 0.0;
}

// Without receiver-plane gradients; penumbra_set_receiver_plane() adds them.
PenumbraSunReceiver penumbra_sun_receiver(vec3 world_position, vec3 world_normal, vec2 pixel) {
    PenumbraSunReceiver receiver;
    receiver.view_depth = penumbra_view_depth(world_position);
    receiver.cascade = penumbra_sun_map_of(world_position);
    receiver.pixel = pixel;
    receiver.face_normal = world_normal;
    const ivec2 cascades = penumbra_receiver_cascades(receiver.cascade);
    for (int i = 0; i < 2; ++i) {
        const vec3 coord = penumbra_project_to_cascade(cascades[i], world_position, world_normal);
        receiver.coords[i].uv = coord.xy;
        receiver.coords[i].depth = coord.z;
        receiver.coords[i].depth_gradient = vec2(0.0);
    }
    return receiver;
}

// The receiver-plane gradients of both coordinates, from their changes to the next pixel
// in x and y ([0]: the receiver's cascade, [1]: the next one). Where neighbouring pixels
// lie in different cascades (`seam`) the changes mix two projections: no gradient there.
void penumbra_set_receiver_plane(inout PenumbraSunReceiver receiver, vec3 coord_dx[2], vec3 coord_dy[2], bool seam) {
    if (!penumbra_uses_receiver_plane_bias() || seam) return;
    const ivec2 cascades = penumbra_receiver_cascades(receiver.cascade);
    for (int i = 0; i < 2; ++i) {
        receiver.coords[i].depth_gradient = penumbra_receiver_plane_gradient(cascades[i], coord_dx[i], coord_dy[i]);
    }
}

// An orthographic map of the sun as the filters see it (penumbra/glsl/filters.glsl): a
// cascade, or a level of the virtual shadow map. Its projection is orthographic, so reverse-Z depth is linear in the
// distance from the light: 1 - depth serves as distance for the moments and for PCSS,
// whose light radius per unit of depth (depth range * tan(theta / 2) / (width, height),
// for a sun of angular diameter theta) turns the distance from the near plane into the
// blocker search radius and the receiver-blocker distance into the penumbra radius. Taps
// are clamped to the map's texels (half a texel inside its edges, as clamp-to-edge
// addressing would read them). The map's depth range is the static instances' along the
// light: a receiver beyond it (a caller's surface that is no instance, a dynamic instance
// above or below every static one) compares as lying on the far side (lit unless a caster
// covers it) or on the near side (lit).
PenumbraShadowView penumbra_sun_map_view(PenumbraShadowCoord coord, float layer, float texel_uv, vec2 uv_offset,
                                         vec2 light_radius_per_depth, int virtual_level) {
    const float depth = clamp(coord.depth, 0.0, 1.0);
    PenumbraShadowView view;
    view.uv = coord.uv;
    view.layer = layer;
    view.depth = depth;
    view.depth_gradient = coord.depth_gradient;
    view.texel_uv = texel_uv;
    const float half_texel = 0.5 * texel_uv;
    view.uv_bounds = vec4(vec2(half_texel), vec2(1.0 - half_texel));
    view.uv_offset = uv_offset;
    view.pcss_search_radius = (1.0 - depth) * light_radius_per_depth;
    view.pcss_penumbra_scale = light_radius_per_depth;
    view.pcss_perspective = false;
    view.pcss_receiver_distance = 1.0 - depth;
    view.pcss_depth_to_distance = vec4(1.0, -1.0, 1.0, 0.0);  // 1 - depth
    view.moments_distance = 1.0 - depth;
    view.caster_slope_bias = penumbra_shadow.caster_slope_bias;
    view.caster_bias_clamp = penumbra_shadow.caster_bias_clamp;
    view.virtual_level = virtual_level;
    return view;
}

// A cascade, or with the virtual shadow map a level (every texel read then goes through
// the page table, and the window has no wrap). Where a cascade wraps around its layer
// (layer_origin), the texels beyond an edge are the opposite edge's.
PenumbraShadowView penumbra_cascade_view(int cascade, PenumbraShadowCoord coord) {
    if (penumbra_sun_is_virtual()) {
        return penumbra_sun_map_view(coord, 0.0, 1.0 / float(penumbra_virtual_side()), vec2(0.0),
                                     penumbra_virtual_light_radius_uv_per_depth(cascade), cascade);
    }
    return penumbra_sun_map_view(coord, float(cascade), penumbra_shadow.texel_uv,
                                 penumbra_shadow.cascades[cascade].layer_origin * penumbra_shadow.texel_uv,
                                 penumbra_shadow.cascades[cascade].light_radius_uv_per_depth, -1);
}

// Visibility through one cascade with the configured filter; lookups outside the map are lit.
float penumbra_sample_cascade(int cascade, PenumbraShadowCoord coord, vec2 pixel) {
    if (any(lessThan(coord.uv, vec2(0.0))) || any(greaterThan(coord.uv, vec2(1.0)))) return 1.0;
    return penumbra_filter_shadow(PENUMBRA_MAP(penumbra_cascade_map), PENUMBRA_MAP(penumbra_cascade_depth),
                                  PENUMBRA_MAP(penumbra_cascade_moments),
                                  penumbra_cascade_view(cascade, coord), pixel);
}

// The sun's shadow at a receiver in [0, 1] (1 beyond the cascades). Inside the last
// `blend width` fraction of a cascade the result blends linearly into the next cascade,
// hiding the resolution seam; the last cascade fades to fully lit over the same fraction
// before the shadow distance. Every filter goes through here.
float penumbra_sun_shadow(PenumbraSunReceiver receiver) {
    const int cascade = receiver.cascade;
    if (cascade < 0) return 1.0;
    if (penumbra_sun_is_virtual()) {
        // One level per receiver (no band between levels: their texels are as fine as the
        // pixels on both sides), fading to lit before the shadow distance as the cascades do.
        const float visibility = penumbra_sample_cascade(cascade, receiver.coords[0], receiver.pixel);
        const float fade_width = penumbra_virtual.shadow_distance - penumbra_virtual.fade_start;
        if (fade_width <= 0.0 || receiver.view_depth <= penumbra_virtual.fade_start) return visibility;
        return mix(visibility, 1.0, clamp((receiver.view_depth - penumbra_virtual.fade_start) / fade_width, 0.0, 1.0));
    }
    float visibility = penumbra_sample_cascade(cascade, receiver.coords[0], receiver.pixel);
    const float split_near = penumbra_cascade_split_near(cascade);
    const float split_far = penumbra_cascade_split_far(cascade);
    const float band = penumbra_shadow.blend_width * (split_far - split_near);
    if (band > 0.0 && receiver.view_depth > split_far - band) {
        const float t = (receiver.view_depth - (split_far - band)) / band;
        const bool has_next = cascade + 1 < penumbra_cascade_count();
        const float next = has_next ? penumbra_sample_cascade(cascade + 1, receiver.coords[1], receiver.pixel) : 1.0;
        visibility = mix(visibility, next, t);
    }
    return visibility;
}

// The sun's visibility for shading: 0 without a sun and where the surface faces away from
// it (its own shadow: by its shading normal, or by its face, e.g. the back-lit side of a
// leaf card with bent normals), else the shadow above. `normal` is the shading normal.
float penumbra_sun_visibility(PenumbraSunReceiver receiver, vec3 normal) {
    if (penumbra_shadow.to_sun.w == 0.0 || !penumbra_faces_light(normal, receiver.face_normal, penumbra_shadow.to_sun.xyz)) {
        return 0.0;
    }
    return penumbra_sun_shadow(receiver);
}

#endif

// Shadows of spot and point lights (included by penumbra/shadow.glsl): one layered map
// holds every shadowed light's layers (a spot up to 60 degrees: one perspective layer; a
// point light or a wider spot: six cube-face layers, face chosen by the major axis). Every
// filter is the sun's (penumbra/glsl/filters.glsl), through a view of the light's layer:
// hard, pcf, poisson and pcss compare against the depth map (with receiver-plane bias),
// vsm, evsm and msm read the moments of the linear distance that Penumbra's moments
// conversion made.
#ifndef PENUMBRA_GLSL_LOCAL
#define PENUMBRA_GLSL_LOCAL

#include "penumbra/glsl/dialect.glsl"

// Cube face of a direction from the light: +X, -X, +Y, -Y, +Z, -Z (src/core/local_lights.hpp).
int penumbra_cube_face(vec3 direction) {
    const vec3 a = abs(direction);
    if (a.x >= a.y && a.x >= a.z) return direction.x >= 0.0 ? 0 : 1;
    if (a.y >= a.z) return direction.y >= 0.0 ? 2 : 3;
    return direction.z >= 0.0 ? 4 : 5;
}

struct PenumbraLocalCoord {
    vec2 uv;              // in the light's used part of its layer
    float depth;          // reverse-Z
    float layer;
    float distance;       // receiver's view depth along the layer's axis (metres)
    vec2 depth_gradient;  // receiver plane: d depth / d uv (0 without receiver-plane bias)
};

float penumbra_local_texel_uv() { return penumbra_local.texel_uv; }

// A world point in `layer`: (u, v) scaled into the light's corner, reverse-Z depth, clip w.
vec4 penumbra_project_to_layer(int layer, float uv_scale, vec3 world_position) {
    const vec4 clip = PENUMBRA_MUL(penumbra_local.layer_view_projection[layer], vec4(world_position, 1.0));
    const vec3 ndc = clip.xyz / clip.w;
    return vec4((ndc.xy * 0.5 + 0.5) * uv_scale, ndc.z, clip.w);
}

// Receiver-plane depth bias (Isidoro 2006) for a perspective layer, without screen-space
// derivatives (the lookups run inside the per-light loop, in non-uniform control flow):
// over a plane, 1 / z is an affine function of the projected (u, v), and reverse-Z depth
// is affine in 1 / z, so the receiver plane's depth is affine in (u, v). Projecting two
// more points of the plane, a texel's width away along two tangents, gives its gradient
// exactly. Clamped to the receiver slope limit (max_receiver_slope) metres of depth per metre across,
// which at view depth z is slope * b * (2 tan(fov / 2)) / (z * uv_scale) in depth per UV.
vec2 penumbra_local_receiver_plane_gradient(PenumbraLocalShadow light, int layer, vec3 world_position, vec3 plane_normal,
                                   vec4 projected, float step_world) {
    const vec3 helper = abs(plane_normal.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    const vec3 tangent = normalize(cross(plane_normal, helper));
    const vec3 bitangent = cross(plane_normal, tangent);
    const vec4 a = penumbra_project_to_layer(layer, light.uv_scale, world_position + tangent * step_world);
    const vec4 b = penumbra_project_to_layer(layer, light.uv_scale, world_position + bitangent * step_world);
    // 0 where the light sees the plane edge-on (the two steps in (u, v) parallel).
    const vec2 gradient =
        penumbra_plane_gradient(vec2(a.z - projected.z, b.z - projected.z), a.xy - projected.xy, b.xy - projected.xy, 1e-24);
    const float n = light.near_plane;
    const float f = light.range;
    const float limit =
        penumbra_local.max_receiver_slope * (f * n / (f - n)) * light.fov_scale / (max(projected.w, n) * light.uv_scale);
    return clamp(gradient, vec2(-limit), vec2(limit));
}

// The receiver in its layer, moved along the normal by normal_offset texels at its distance
// (a perspective texel grows linearly with distance: 2 tan(fov / 2) * d / resolution).
PenumbraLocalCoord penumbra_project_to_local_shadow(PenumbraLocalShadow light, vec3 world_position, vec3 normal, vec3 plane_normal) {
    const vec3 from_light = world_position - light.position;
    int layer = light.first_layer;
    if (light.cube != 0u) layer += penumbra_cube_face(from_light);
    const float texel_uv = penumbra_local_texel_uv() / light.uv_scale;  // one of the light's own texels, in its UV
    const float texel_world = light.fov_scale * texel_uv * length(from_light);
    const vec3 offset_position = world_position + normal * (penumbra_local.normal_offset_texels * texel_world);
    const vec4 projected = penumbra_project_to_layer(layer, light.uv_scale, offset_position);
    PenumbraLocalCoord coord;
    coord.uv = projected.xy;
    coord.depth = projected.z;
    coord.layer = float(layer);
    coord.distance = projected.w;
    coord.depth_gradient = vec2(0.0);
    if (penumbra_uses_receiver_plane_bias()) {
        coord.depth_gradient =
            penumbra_local_receiver_plane_gradient(light, layer, offset_position, plane_normal, projected, texel_world);
    }
    return coord;
}

// A light's layer as the filters see it (penumbra/glsl/filters.glsl). Every tap stays
// inside the light's corner of the layer (half a texel from its edges), so that no filter
// reads another light's texels or a neighbouring cube face. PCSS (Fernando 2005) for a
// spherical light of radius r through a perspective layer: the blocker search covers the
// light's disk seen from the receiver, projected at the near plane; the penumbra's width
// at the receiver is w = (d_receiver - d_blocker) * r / d_blocker (linear distances along
// the layer's axis), projected into the map at the receiver's distance. The moments store
// the linear distance over the range (shaders/moments_convert.comp).
PenumbraShadowView penumbra_local_view(PenumbraLocalShadow light, PenumbraLocalCoord coord) {
    const float n = light.near_plane;
    const float f = light.range;
    const float half_texel = 0.5 * penumbra_local_texel_uv();
    const float uv_per_metre_at_receiver = light.uv_scale / (light.fov_scale * coord.distance);
    const float search_radius =
        light.radius * (coord.distance - n) / max(coord.distance, 1e-4) * light.uv_scale / (light.fov_scale * n);
    PenumbraShadowView view;
    view.virtual_level = -1;
    view.uv = coord.uv;
    view.layer = coord.layer;
    view.depth = coord.depth;
    view.depth_gradient = coord.depth_gradient;
    view.texel_uv = penumbra_local_texel_uv();
    view.uv_bounds = vec4(vec2(half_texel), vec2(light.uv_scale - half_texel));
    view.uv_offset = vec2(0.0);
    view.pcss_search_radius = vec2(search_radius);
    view.pcss_penumbra_scale = vec2(light.radius * uv_per_metre_at_receiver);
    view.pcss_perspective = true;
    view.pcss_receiver_distance = coord.distance;
    // Distance along the axis of a reverse-Z depth: depth = b / d - a with a = n / (f - n),
    // b = f n / (f - n) (perspective_reverse_z in src/core/camera_math.cpp), so d = b / (depth + a).
    view.pcss_depth_to_distance = vec4(f * n / (f - n), 0.0, n / (f - n), 1.0);
    view.moments_distance = clamp(coord.distance / light.range, 0.0, 1.0);
    view.caster_slope_bias = penumbra_local.caster_slope_bias;
    view.caster_bias_clamp = penumbra_local.caster_bias_clamp;
    return view;
}

// Whether a receiver lies outside a perspective spot's map: behind the light, or beyond the
// map's field of view (twice the outer angle: outside the cone, where the spot's own
// lighting is 0). A cube covers every direction.
bool penumbra_outside_spot_map(PenumbraLocalShadow light, PenumbraLocalCoord coord) {
    if (light.cube != 0u) return false;
    return coord.distance <= 0.0 || any(lessThan(coord.uv, vec2(0.0))) ||
           any(greaterThan(coord.uv, vec2(light.uv_scale)));
}

// Shadow visibility of a local light at a receiver (1 when unshadowed). `plane_normal` is
// the receiver's geometric normal (its plane, for receiver-plane bias). Defined everywhere:
// 1 (lit) beyond the light's range and outside a spot's map (behind the spot or outside its
// cone: the cone is the caller's lighting), never the clamped edge of the map.
float penumbra_local_shadow(PenumbraLocalShadow light, vec3 world_position, vec3 normal, vec3 plane_normal, vec2 pixel) {
    if (light.first_layer < 0) return 1.0;
    const PenumbraLocalCoord coord = penumbra_project_to_local_shadow(light, world_position, normal, plane_normal);
    if (coord.depth <= 0.0) return 1.0;  // beyond the range
    if (penumbra_outside_spot_map(light, coord)) return 1.0;
    return penumbra_filter_shadow(PENUMBRA_MAP(penumbra_local_map), PENUMBRA_MAP(penumbra_local_depth),
                                  PENUMBRA_MAP(penumbra_local_moments),
                                  penumbra_local_view(light, coord), pixel);
}

// The shadow of light `index` of the set_lights() list at a receiver: 1 for lights without
// a shadow map (unshadowed, beyond the budget, directional, or past the list).
float penumbra_light_shadow(uint index, vec3 world_position, vec3 normal, vec3 plane_normal, vec2 pixel) {
    if (index >= penumbra_local.light_count) return 1.0;
    return penumbra_local_shadow(penumbra_local.lights[index], world_position, normal, plane_normal, pixel);
}

// The visibility of spot or point light `index` for shading: 0 where the surface faces
// away from the light by its normal or its face (its own shadow, penumbra_faces_light),
// else its shadow. The cone and the distance falloff are the caller's lighting.
float penumbra_light_visibility(uint index, vec3 world_position, vec3 normal, vec3 plane_normal, vec2 pixel) {
    if (index >= penumbra_local.light_count) return 1.0;
    const PenumbraLocalShadow light = penumbra_local.lights[index];
    if (!penumbra_faces_light(normal, plane_normal, light.position - world_position)) return 0.0;
    return penumbra_local_shadow(light, world_position, normal, plane_normal, pixel);
}

#endif

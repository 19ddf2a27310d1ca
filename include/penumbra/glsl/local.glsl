// Shadows of spot and point lights (included by penumbra/shadow.glsl): one layered map
// holds every shadowed light's layers (a spot up to 60 degrees: one perspective layer; a
// point light or a wider spot: six cube-face layers, face chosen by the major axis). The
// filters mirror the sun's for perspective layers: hard, pcf, poisson and pcss compare
// against the depth map (with receiver-plane bias), vsm, evsm and msm read the moments of
// the linear distance that Penumbra's moments conversion made.
#ifndef PENUMBRA_GLSL_LOCAL
#define PENUMBRA_GLSL_LOCAL

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
    const vec4 clip = penumbra_local.layer_view_projection[layer] * vec4(world_position, 1.0);
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
    const mat2 uv_jacobian = mat2(a.xy - projected.xy, b.xy - projected.xy);  // columns: the steps in (u, v)
    if (abs(determinant(uv_jacobian)) < 1e-24) return vec2(0.0);            // the light sees the plane edge-on
    const vec2 gradient = vec2(a.z - projected.z, b.z - projected.z) * inverse(uv_jacobian);
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
    PenumbraLocalCoord coord = PenumbraLocalCoord(projected.xy, projected.z, float(layer), projected.w, vec2(0.0));
    if (penumbra_uses_receiver_plane_bias()) {
        coord.depth_gradient =
            penumbra_local_receiver_plane_gradient(light, layer, offset_position, plane_normal, projected, texel_world);
    }
    return coord;
}

// A UV kept inside the light's part of the layer (half a texel from its edges), so that
// no filter tap reads another light's texels or a neighbouring cube face.
vec2 penumbra_clamp_to_light(PenumbraLocalShadow light, vec2 uv) {
    const float half_texel = 0.5 * penumbra_local_texel_uv();
    return clamp(uv, vec2(half_texel), vec2(light.uv_scale - half_texel));
}

// Receiver-plane bias for the texels a bilinear comparison reads around a tap (as the
// sun's receiver_plane_static_bias()); 0 without receiver-plane bias.
float penumbra_local_static_bias(PenumbraLocalCoord coord) { return dot(vec2(penumbra_local_texel_uv()), abs(coord.depth_gradient)); }

// One hardware comparison tap `offset` (UV) away, its reference depth following the
// receiver's plane to the tap.
float penumbra_local_compare_tap(PenumbraLocalShadow light, PenumbraLocalCoord coord, vec2 offset, float static_bias) {
    const vec2 uv = penumbra_clamp_to_light(light, coord.uv + offset);
    const float reference = coord.depth + dot(coord.depth_gradient, uv - coord.uv) + static_bias;
    return texture(penumbra_local_map, vec4(uv, coord.layer, reference));
}

// hard: one hardware comparison at the receiver, no receiver-plane bias.
float penumbra_local_hard(PenumbraLocalShadow light, PenumbraLocalCoord coord) {
    return texture(penumbra_local_map, vec4(penumbra_clamp_to_light(light, coord.uv), coord.layer, coord.depth));
}

// pcf: the sun's kernel (penumbra/glsl/pcf.glsl), every tap kept inside the light's corner.
float penumbra_local_pcf(PenumbraLocalShadow light, PenumbraLocalCoord coord) {
    const int radius = int(penumbra_shadow.pcf_radius);
    const float texel = penumbra_local_texel_uv();
    const float bias = penumbra_local_static_bias(coord);
    const vec2 f = fract(coord.uv / texel - 0.5);
    float lit = 0.0;
    for (int j = 0; j <= radius; ++j) {
        const vec2 y = penumbra_pcf_tap(f.y, radius, j);
        for (int i = 0; i <= radius; ++i) {
            const vec2 x = penumbra_pcf_tap(f.x, radius, i);
            const vec2 offset = vec2(x.x, y.x) * texel;
            lit += x.y * y.y * penumbra_local_compare_tap(light, coord, offset, bias);
        }
    }
    const float side = float(2 * radius + 1);
    return lit / (side * side);
}

// Comparison taps over a rotated Poisson disk of `radius_uv`.
float penumbra_local_poisson_comparisons(PenumbraLocalShadow light, PenumbraLocalCoord coord, uint taps, float radius_uv, mat2 rotation) {
    const float bias = penumbra_local_static_bias(coord);
    float lit = 0.0;
    for (uint i = 0u; i < taps; ++i) {
        lit += penumbra_local_compare_tap(light, coord, (rotation * penumbra_poisson_tap(taps, i)) * radius_uv, bias);
    }
    return lit / float(taps);
}

// poisson: the sun's poisson filter (poisson_radius texels, kPenumbraSearchTaps taps, rotated per pixel).
float penumbra_local_poisson(PenumbraLocalShadow light, PenumbraLocalCoord coord, vec2 pixel) {
    return penumbra_local_poisson_comparisons(light, coord, kPenumbraSearchTaps,
                                              penumbra_shadow.poisson_radius_texels * penumbra_local_texel_uv(),
                                              penumbra_sample_rotation(pixel));
}

// Distance along the layer's axis of a reverse-Z depth: depth = b / d - a with
// a = n / (f - n), b = f n / (f - n) (perspective_reverse_z in src/core/camera_math.cpp).
float penumbra_local_linear_depth(PenumbraLocalShadow light, float depth) {
    const float n = light.near_plane;
    const float f = light.range;
    return (f * n / (f - n)) / (depth + n / (f - n));
}

// PCSS (Fernando 2005) for a spherical light of radius r seen through a perspective map:
// blockers within the light's cone, penumbra width w = (d_receiver - d_blocker) * r / d_blocker
// at the receiver, filtered over w projected into the map at the receiver's distance.
float penumbra_local_pcss(PenumbraLocalShadow light, PenumbraLocalCoord coord, vec2 pixel) {
    const float texel = penumbra_local_texel_uv();
    const float max_radius = texel * penumbra_shadow.pcss_max_penumbra_texels;
    const float uv_per_metre_at_receiver = light.uv_scale / (light.fov_scale * coord.distance);
    const float n = light.near_plane;
    const float bias = penumbra_local_static_bias(coord);
    // 1. Blocker search: the light's disk seen from the receiver, at the near plane.
    const float search = clamp(light.radius * (coord.distance - n) / max(coord.distance, 1e-4) *
                                   light.uv_scale / (light.fov_scale * n),
                               texel, max_radius);
    const mat2 rotation = penumbra_sample_rotation(pixel);
    float blocker_distance = 0.0;
    uint blockers = 0u;
    for (uint i = 0u; i < kPenumbraSearchTaps; ++i) {
        const vec2 uv = penumbra_clamp_to_light(light, coord.uv + (rotation * penumbra_poisson_tap(kPenumbraSearchTaps, i)) * search);
        const float stored = texture(penumbra_local_depth, vec3(uv, coord.layer)).r;
        if (stored > coord.depth + dot(coord.depth_gradient, uv - coord.uv) + bias) {
            blocker_distance += penumbra_local_linear_depth(light, stored);
            blockers += 1u;
        }
    }
    if (blockers == 0u) return penumbra_local_compare_tap(light, coord, vec2(0.0), bias);  // as the sun's: a contact or gap
    blocker_distance /= float(blockers);
    // 2. Penumbra width at the receiver, into the map.
    const float penumbra_world = (coord.distance - blocker_distance) * light.radius / max(blocker_distance, 1e-4);
    const float radius = min(penumbra_world * uv_per_metre_at_receiver, max_radius);
    // 3. Poisson PCF over the penumbra, less the taps' own bilinear width, as the sun's
    //    (penumbra_pcss_disk_radius): a sub-texel penumbra is one comparison at the receiver.
    const float disk_radius = penumbra_pcss_disk_radius(vec2(radius), texel).x;
    if (penumbra_pcss_is_single_tap(vec2(disk_radius), texel)) return penumbra_local_compare_tap(light, coord, vec2(0.0), bias);
    return penumbra_local_poisson_comparisons(light, coord, kPenumbraFilterTaps, disk_radius, rotation);
}

// Filtered moments around the receiver (bilinear, or 16 Poisson taps of poisson_radius
// texels with moments_poisson), inside the light's part of the layer.
vec4 penumbra_local_fetch_moments(PenumbraLocalShadow light, PenumbraLocalCoord coord, vec2 pixel) {
    if (!kPenumbraMomentsPoisson) return texture(penumbra_local_moments, vec3(penumbra_clamp_to_light(light, coord.uv), coord.layer));
    const mat2 rotation = penumbra_sample_rotation(pixel);
    const float radius_uv = penumbra_shadow.poisson_radius_texels * penumbra_local_texel_uv();
    vec4 sum = vec4(0.0);
    for (uint i = 0u; i < 16u; ++i) {
        const vec2 uv = penumbra_clamp_to_light(light, coord.uv + (rotation * penumbra_poisson_tap(16u, i)) * radius_uv);
        sum += texture(penumbra_local_moments, vec3(uv, coord.layer));
    }
    return sum / 16.0;
}

// vsm, evsm, msm: the receiver's linear distance over the range, the scale of the stored
// moments (shaders/moments_convert.comp).
float penumbra_local_moment_filter(PenumbraLocalShadow light, PenumbraLocalCoord coord, vec2 pixel) {
    const float receiver = clamp(coord.distance / light.range, 0.0, 1.0);
    return penumbra_moments_visibility(penumbra_local_fetch_moments(light, coord, pixel), receiver);
}

// Shadow visibility of a local light at a receiver (1 when unshadowed). `plane_normal` is
// the receiver's geometric normal (its plane, for receiver-plane bias).
float penumbra_local_shadow(PenumbraLocalShadow light, vec3 world_position, vec3 normal, vec3 plane_normal, vec2 pixel) {
    if (light.first_layer < 0) return 1.0;
    const PenumbraLocalCoord coord = penumbra_project_to_local_shadow(light, world_position, normal, plane_normal);
    if (coord.depth <= 0.0) return 1.0;  // beyond the range
    switch (kPenumbraFilterMode) {
        case PENUMBRA_FILTER_HARD:
            return penumbra_local_hard(light, coord);
        case PENUMBRA_FILTER_POISSON:
            return penumbra_local_poisson(light, coord, pixel);
        case PENUMBRA_FILTER_PCSS:
            return penumbra_local_pcss(light, coord, pixel);
        case PENUMBRA_FILTER_VSM:
        case PENUMBRA_FILTER_EVSM:
        case PENUMBRA_FILTER_MSM:
            return penumbra_local_moment_filter(light, coord, pixel);
        default:
            return penumbra_local_pcf(light, coord);
    }
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

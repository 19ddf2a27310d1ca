// Spot and point lights (docs/local-lights.md): physically based falloff, the smooth spot
// cone, and shadows from one layered map holding every shadowed light's layers (a spot:
// one perspective layer; a point: six cube-face layers, face chosen by the major axis).
// Included by the lighting shader after the shadow library (for kFilterMode and
// sample_rotation()). Filters: hard, pcf and pcss; poisson and the moment filters fall
// back to pcf for local lights (their maps store plain depth, no moments).
#ifndef PENUMBRA_LOCAL_LIGHTS_GLSL
#define PENUMBRA_LOCAL_LIGHTS_GLSL

layout(std140, set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_LOCAL_LIGHTS) uniform LocalLightBlock {
    LocalLightUniforms local;
};
layout(set = PENUMBRA_SET_FRAME,
       binding = PENUMBRA_BINDING_LOCAL_SHADOW_MAP) uniform sampler2DArrayShadow local_shadow_map;
layout(set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_LOCAL_SHADOW_DEPTH) uniform sampler2DArray local_shadow_depth;

int local_light_count() { return int(local.counts.x); }

// Inverse-square falloff with a smooth window at the range (Karis 2013, "Real Shading in
// Unreal Engine 4"): saturate(1 - (d / range)^4)^2 / d^2.
float distance_falloff(float distance, float range) {
    const float ratio = distance / range;
    const float window = clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
    return window * window / max(distance * distance, 1e-4);
}

// Smooth cone: 0 outside the outer angle, 1 inside the inner one, smoothstep between.
float spot_cone(LocalLight light, vec3 to_light) {
    if (light.direction_type.w != PENUMBRA_LIGHT_SPOT) return 1.0;
    const float cos_angle = dot(-to_light, light.direction_type.xyz);
    return smoothstep(light.cone.x, max(light.cone.y, light.cone.x + 1e-4), cos_angle);
}

// Cube face of a direction from a point light: +X, -X, +Y, -Y, +Z, -Z (src/core/local_lights.hpp).
int cube_face(vec3 direction) {
    const vec3 a = abs(direction);
    if (a.x >= a.y && a.x >= a.z) return direction.x >= 0.0 ? 0 : 1;
    if (a.y >= a.z) return direction.y >= 0.0 ? 2 : 3;
    return direction.z >= 0.0 ? 4 : 5;
}

struct LocalShadowCoord {
    vec2 uv;         // in the light's used part of its layer
    float depth;     // reverse-Z
    float layer;
    float distance;  // receiver's view depth along the layer's axis (metres)
};

// The receiver in its layer, moved along the normal by normal_offset texels at its distance
// (a perspective texel grows linearly with distance: 2 tan(fov / 2) * d / resolution).
LocalShadowCoord project_to_local_shadow(LocalLight light, vec3 world_position, vec3 normal) {
    const vec3 from_light = world_position - light.position_range.xyz;
    int layer = int(light.shadow.x);
    if (light.direction_type.w == PENUMBRA_LIGHT_POINT) layer += cube_face(from_light);
    const float texel_uv = local.counts.w / light.shadow.w;  // one of the light's own texels, in its UV
    const float texel_world = light.shadow.z * texel_uv * length(from_light);
    const vec3 offset_position = world_position + normal * (local.counts.z * texel_world);
    const vec4 clip = local.shadow_view_projection[layer] * vec4(offset_position, 1.0);
    const vec3 ndc = clip.xyz / clip.w;
    return LocalShadowCoord((ndc.xy * 0.5 + 0.5) * light.shadow.w, ndc.z, float(layer), clip.w);
}

// One hardware comparison tap, kept inside the light's part of the layer.
float local_compare_tap(LocalLight light, LocalShadowCoord coord, vec2 offset) {
    const float half_texel = 0.5 * local.counts.w;
    const vec2 uv = clamp(coord.uv + offset, vec2(half_texel), vec2(light.shadow.w - half_texel));
    return texture(local_shadow_map, vec4(uv, coord.layer, coord.depth));
}

float local_pcf(LocalLight light, LocalShadowCoord coord, int radius, float step_uv) {
    float lit = 0.0;
    for (int y = -radius; y <= radius; ++y) {
        for (int x = -radius; x <= radius; ++x) lit += local_compare_tap(light, coord, vec2(x, y) * step_uv);
    }
    const int side = 2 * radius + 1;
    return lit / float(side * side);
}

// Distance along the layer's axis of a reverse-Z depth: depth = b / d - a with
// a = n / (f - n), b = f n / (f - n) (perspective_reverse_z in src/core/camera_math.cpp).
float local_linear_depth(LocalLight light, float depth) {
    const float n = light.shadow.y;
    const float f = light.position_range.w;
    return (f * n / (f - n)) / (depth + n / (f - n));
}

// PCSS (Fernando 2005) for a spherical light of radius r seen through a perspective map:
// blockers within the light's cone, penumbra width w = (d_receiver - d_blocker) * r / d_blocker
// at the receiver, filtered over w projected into the map at the receiver's distance.
float local_pcss(LocalLight light, LocalShadowCoord coord) {
    const float texel = local.counts.w;
    const float max_radius = texel * local.filter_params.y;
    const float uv_per_metre_at_receiver = light.shadow.w / (light.shadow.z * coord.distance);
    const float n = light.shadow.y;
    // 1. Blocker search: the light's disk seen from the receiver, at the near plane.
    const float search = clamp(light.radiance.w * (coord.distance - n) / max(coord.distance, 1e-4) *
                                   light.shadow.w / (light.shadow.z * n),
                               texel, max_radius);
    const mat2 rotation = sample_rotation();
    float blocker_distance = 0.0;
    uint blockers = 0u;
    for (uint i = 0u; i < kSearchTaps; ++i) {
        const vec2 uv = coord.uv + (rotation * poisson_tap(kSearchTaps, i)) * search;
        const vec2 clamped = clamp(uv, vec2(0.5 * texel), vec2(light.shadow.w - 0.5 * texel));
        const float stored = texture(local_shadow_depth, vec3(clamped, coord.layer)).r;
        if (stored > coord.depth) {
            blocker_distance += local_linear_depth(light, stored);
            blockers += 1u;
        }
    }
    if (blockers == 0u) return 1.0;
    blocker_distance /= float(blockers);
    // 2. Penumbra width at the receiver, into the map.
    const float penumbra_world = (coord.distance - blocker_distance) * light.radiance.w / max(blocker_distance, 1e-4);
    const float radius = clamp(penumbra_world * uv_per_metre_at_receiver, texel, max_radius);
    // 3. Poisson PCF over the penumbra.
    float lit = 0.0;
    for (uint i = 0u; i < kFilterTaps; ++i) {
        lit += local_compare_tap(light, coord, (rotation * poisson_tap(kFilterTaps, i)) * radius);
    }
    return lit / float(kFilterTaps);
}

// Shadow visibility of a local light at a receiver (1 when unshadowed).
float local_shadow(LocalLight light, vec3 world_position, vec3 normal) {
    if (light.shadow.x < 0.0) return 1.0;
    const LocalShadowCoord coord = project_to_local_shadow(light, world_position, normal);
    if (coord.depth <= 0.0) return 1.0;  // beyond the range
    switch (kFilterMode) {
        case PENUMBRA_FILTER_HARD:
            return local_compare_tap(light, coord, vec2(0.0));
        case PENUMBRA_FILTER_PCSS:
            return local_pcss(light, coord);
        default:
            return local_pcf(light, coord, int(local.filter_params.x), local.counts.w);
    }
}

#endif

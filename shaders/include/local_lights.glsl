// Spot and point lights (docs/local-lights.md): physically based falloff, the smooth spot
// cone, and shadows from one layered map holding every shadowed light's layers (a spot:
// one perspective layer; a point or a spot wider than 60 degrees: six cube-face layers,
// face chosen by the major axis).
// Included by the lighting shader after the shadow library, whose filters it mirrors for
// perspective layers: hard, pcf, poisson and pcss compare against the depth map (with
// receiver-plane bias), vsm, evsm and msm read the moments of the linear distance that
// the local moments pass made (shaders/local_moments.frag) through moments_visibility().
#ifndef PENUMBRA_LOCAL_LIGHTS_GLSL
#define PENUMBRA_LOCAL_LIGHTS_GLSL

// A storage buffer: with 64 lights and 192 layers the block outgrows the 16 KiB that
// Vulkan guarantees for uniform buffers. Every member is a vec4 or mat4, so std430 and
// std140 lay it out alike (src/passes/shader_interface.hpp checks the offsets).
layout(std430, set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_LOCAL_LIGHTS) readonly buffer LocalLightBlock {
    LocalLightUniforms local;
};
layout(set = PENUMBRA_SET_FRAME,
       binding = PENUMBRA_BINDING_LOCAL_SHADOW_MAP) uniform sampler2DArrayShadow local_shadow_map;
layout(set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_LOCAL_SHADOW_DEPTH) uniform sampler2DArray local_shadow_depth;
layout(set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_LOCAL_MOMENTS) uniform sampler2DArray local_moments;

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

// Cube face of a direction from the light: +X, -X, +Y, -Y, +Z, -Z (src/core/local_lights.hpp).
int cube_face(vec3 direction) {
    const vec3 a = abs(direction);
    if (a.x >= a.y && a.x >= a.z) return direction.x >= 0.0 ? 0 : 1;
    if (a.y >= a.z) return direction.y >= 0.0 ? 2 : 3;
    return direction.z >= 0.0 ? 4 : 5;
}

struct LocalShadowCoord {
    vec2 uv;              // in the light's used part of its layer
    float depth;          // reverse-Z
    float layer;
    float distance;       // receiver's view depth along the layer's axis (metres)
    vec2 depth_gradient;  // receiver plane: d depth / d uv (0 without receiver-plane bias)
};

float local_texel_uv() { return local.counts.w; }

// A world point in `layer`: (u, v) scaled into the light's corner, reverse-Z depth, clip w.
vec4 project_to_layer(int layer, float uv_scale, vec3 world_position) {
    const vec4 clip = local.shadow_view_projection[layer] * vec4(world_position, 1.0);
    const vec3 ndc = clip.xyz / clip.w;
    return vec4((ndc.xy * 0.5 + 0.5) * uv_scale, ndc.z, clip.w);
}

// Receiver-plane depth bias (Isidoro 2006) for a perspective layer, without screen-space
// derivatives (the lookups run inside the per-light loop, in non-uniform control flow):
// over a plane, 1 / z is an affine function of the projected (u, v), and reverse-Z depth
// is affine in 1 / z, so the receiver plane's depth is affine in (u, v). Projecting two
// more points of the plane, a texel's width away along two tangents, gives its gradient
// exactly. Clamped to kMaxReceiverSlope (filter_params.z) metres of depth per metre across,
// which at view depth z is slope * b * (2 tan(fov / 2)) / (z * uv_scale) in depth per UV.
vec2 local_receiver_plane_gradient(LocalLight light, int layer, vec3 world_position, vec3 plane_normal,
                                   vec4 projected, float step_world) {
    const vec3 helper = abs(plane_normal.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    const vec3 tangent = normalize(cross(plane_normal, helper));
    const vec3 bitangent = cross(plane_normal, tangent);
    const vec4 a = project_to_layer(layer, light.shadow.w, world_position + tangent * step_world);
    const vec4 b = project_to_layer(layer, light.shadow.w, world_position + bitangent * step_world);
    const mat2 uv_jacobian = mat2(a.xy - projected.xy, b.xy - projected.xy);  // columns: the steps in (u, v)
    if (abs(determinant(uv_jacobian)) < 1e-24) return vec2(0.0);            // the light sees the plane edge-on
    const vec2 gradient = vec2(a.z - projected.z, b.z - projected.z) * inverse(uv_jacobian);
    const float n = light.shadow.y;
    const float f = light.position_range.w;
    const float limit =
        local.filter_params.z * (f * n / (f - n)) * light.shadow.z / (max(projected.w, n) * light.shadow.w);
    return clamp(gradient, vec2(-limit), vec2(limit));
}

bool local_uses_receiver_plane_bias() {
    return kReceiverPlaneBias && (kFilterMode == PENUMBRA_FILTER_PCF || kFilterMode == PENUMBRA_FILTER_POISSON ||
                                  kFilterMode == PENUMBRA_FILTER_PCSS);
}

// The receiver in its layer, moved along the normal by normal_offset texels at its distance
// (a perspective texel grows linearly with distance: 2 tan(fov / 2) * d / resolution).
LocalShadowCoord project_to_local_shadow(LocalLight light, vec3 world_position, vec3 normal, vec3 plane_normal) {
    const vec3 from_light = world_position - light.position_range.xyz;
    int layer = int(light.shadow.x);
    if (light.cone.z > 0.5) layer += cube_face(from_light);
    const float texel_uv = local_texel_uv() / light.shadow.w;  // one of the light's own texels, in its UV
    const float texel_world = light.shadow.z * texel_uv * length(from_light);
    const vec3 offset_position = world_position + normal * (local.counts.z * texel_world);
    const vec4 projected = project_to_layer(layer, light.shadow.w, offset_position);
    LocalShadowCoord coord = LocalShadowCoord(projected.xy, projected.z, float(layer), projected.w, vec2(0.0));
    if (local_uses_receiver_plane_bias()) {
        coord.depth_gradient =
            local_receiver_plane_gradient(light, layer, offset_position, plane_normal, projected, texel_world);
    }
    return coord;
}

// A UV kept inside the light's part of the layer (half a texel from its edges), so that
// no filter tap reads another light's texels or a neighbouring cube face.
vec2 clamp_to_light(LocalLight light, vec2 uv) {
    const float half_texel = 0.5 * local_texel_uv();
    return clamp(uv, vec2(half_texel), vec2(light.shadow.w - half_texel));
}

// Receiver-plane bias for the texels a bilinear comparison reads around a tap (as the
// sun's receiver_plane_static_bias()); 0 without receiver-plane bias.
float local_static_bias(LocalShadowCoord coord) { return dot(vec2(local_texel_uv()), abs(coord.depth_gradient)); }

// One hardware comparison tap `offset` (UV) away, its reference depth following the
// receiver's plane to the tap.
float local_compare_tap(LocalLight light, LocalShadowCoord coord, vec2 offset, float static_bias) {
    const vec2 uv = clamp_to_light(light, coord.uv + offset);
    const float reference = coord.depth + dot(coord.depth_gradient, uv - coord.uv) + static_bias;
    return texture(local_shadow_map, vec4(uv, coord.layer, reference));
}

float local_pcf(LocalLight light, LocalShadowCoord coord) {
    const int radius = int(local.filter_params.x);
    const float bias = local_static_bias(coord);
    float lit = 0.0;
    for (int y = -radius; y <= radius; ++y) {
        for (int x = -radius; x <= radius; ++x) {
            lit += local_compare_tap(light, coord, vec2(x, y) * local_texel_uv(), bias);
        }
    }
    const int side = 2 * radius + 1;
    return lit / float(side * side);
}

// Comparison taps over a rotated Poisson disk of `radius_uv`.
float local_poisson_comparisons(LocalLight light, LocalShadowCoord coord, uint taps, float radius_uv, mat2 rotation) {
    const float bias = local_static_bias(coord);
    float lit = 0.0;
    for (uint i = 0u; i < taps; ++i) {
        lit += local_compare_tap(light, coord, (rotation * poisson_tap(taps, i)) * radius_uv, bias);
    }
    return lit / float(taps);
}

// poisson: the sun's poisson filter (poisson_radius texels, kSearchTaps taps, rotated per pixel).
float local_poisson(LocalLight light, LocalShadowCoord coord) {
    return local_poisson_comparisons(light, coord, kSearchTaps, frame.filter_params.y * local_texel_uv(),
                                     sample_rotation());
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
    const float texel = local_texel_uv();
    const float max_radius = texel * local.filter_params.y;
    const float uv_per_metre_at_receiver = light.shadow.w / (light.shadow.z * coord.distance);
    const float n = light.shadow.y;
    const float bias = local_static_bias(coord);
    // 1. Blocker search: the light's disk seen from the receiver, at the near plane.
    const float search = clamp(light.radiance.w * (coord.distance - n) / max(coord.distance, 1e-4) *
                                   light.shadow.w / (light.shadow.z * n),
                               texel, max_radius);
    const mat2 rotation = sample_rotation();
    float blocker_distance = 0.0;
    uint blockers = 0u;
    for (uint i = 0u; i < kSearchTaps; ++i) {
        const vec2 uv = clamp_to_light(light, coord.uv + (rotation * poisson_tap(kSearchTaps, i)) * search);
        const float stored = texture(local_shadow_depth, vec3(uv, coord.layer)).r;
        if (stored > coord.depth + dot(coord.depth_gradient, uv - coord.uv) + bias) {
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
    return local_poisson_comparisons(light, coord, kFilterTaps, radius, rotation);
}

// Filtered moments around the receiver (bilinear, or 16 Poisson taps of poisson_radius
// texels with moments_poisson), inside the light's part of the layer.
vec4 local_fetch_moments(LocalLight light, LocalShadowCoord coord) {
    if (!kMomentsPoisson) return texture(local_moments, vec3(clamp_to_light(light, coord.uv), coord.layer));
    const mat2 rotation = sample_rotation();
    const float radius_uv = frame.filter_params.y * local_texel_uv();
    vec4 sum = vec4(0.0);
    for (uint i = 0u; i < 16u; ++i) {
        const vec2 uv = clamp_to_light(light, coord.uv + (rotation * poisson_tap(16u, i)) * radius_uv);
        sum += texture(local_moments, vec3(uv, coord.layer));
    }
    return sum / 16.0;
}

// vsm, evsm, msm: the receiver's linear distance over the range, the scale of the stored
// moments (shaders/local_moments.frag).
float local_moment_filter(LocalLight light, LocalShadowCoord coord) {
    const float receiver = clamp(coord.distance / light.position_range.w, 0.0, 1.0);
    return moments_visibility(local_fetch_moments(light, coord), receiver);
}

// Shadow visibility of a local light at a receiver (1 when unshadowed). `plane_normal` is
// the receiver's geometric normal (its plane, for receiver-plane bias).
float local_shadow(LocalLight light, vec3 world_position, vec3 normal, vec3 plane_normal) {
    if (light.shadow.x < 0.0) return 1.0;
    const LocalShadowCoord coord = project_to_local_shadow(light, world_position, normal, plane_normal);
    if (coord.depth <= 0.0) return 1.0;  // beyond the range
    switch (kFilterMode) {
        case PENUMBRA_FILTER_HARD:
            return texture(local_shadow_map, vec4(clamp_to_light(light, coord.uv), coord.layer, coord.depth));
        case PENUMBRA_FILTER_POISSON:
            return local_poisson(light, coord);
        case PENUMBRA_FILTER_PCSS:
            return local_pcss(light, coord);
        case PENUMBRA_FILTER_VSM:
        case PENUMBRA_FILTER_EVSM:
        case PENUMBRA_FILTER_MSM:
            return local_moment_filter(light, coord);
        default:
            return local_pcf(light, coord);
    }
}

#endif

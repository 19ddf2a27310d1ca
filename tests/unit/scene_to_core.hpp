#pragma once
// The scene component's Aabb, Camera and Light as the library's core math takes them
// (core/shadow_inputs.hpp), and the core functions over scene types: for tests that feed a
// scene to the core math (`using namespace penumbra::testing;` puts these overloads beside
// the core's). The library itself never sees the scene component: it converts its public
// LightDesc and Bounds.
#include <span>
#include <vector>

#include "core/camera_math.hpp"
#include "core/local_lights.hpp"
#include "core/shadow_inputs.hpp"
#include "penumbra/scene/scene.hpp"

namespace penumbra::testing {

inline core::Aabb to_core(const Aabb& box) { return {box.min, box.max}; }

inline core::Camera to_core(const Camera& camera) {
    return {camera.eye, camera.target, camera.up, camera.fov_y_degrees, camera.near_plane, camera.far_plane};
}

inline core::Light to_core(const Light& light) {
    core::Light result;
    result.type = light.type;
    result.direction = glm::normalize(light.direction);
    result.position = light.position;
    result.angular_diameter_degrees = light.angular_diameter_degrees;
    result.cast_shadows = light.cast_shadows;
    result.inner_angle_degrees = light.inner_angle_degrees;
    result.outer_angle_degrees = light.outer_angle_degrees;
    result.range = light.range;
    result.radius = light.radius;
    result.shadow_resolution = light.shadow_resolution;
    return result;
}

inline std::vector<core::Light> to_core(const std::vector<Light>& lights) {
    std::vector<core::Light> result;
    for (const Light& light : lights) result.push_back(to_core(light));
    return result;
}

inline std::vector<core::Aabb> to_core(const std::vector<Aabb>& boxes) {
    std::vector<core::Aabb> result;
    for (const Aabb& box : boxes) result.push_back(to_core(box));
    return result;
}

inline CameraView make_camera_view(const Camera& camera, float aspect) {
    return penumbra::make_camera_view(to_core(camera), aspect);
}
inline bool local_shadow_is_cube(const Light& light) { return penumbra::local_shadow_is_cube(to_core(light)); }
inline uint32_t local_shadow_layers(const Light& light) { return penumbra::local_shadow_layers(to_core(light)); }
inline float local_shadow_half_fov(const Light& light) { return penumbra::local_shadow_half_fov(to_core(light)); }
inline LocalShadowPlan plan_local_shadows(const std::vector<Light>& lights, const LocalShadowSettings& settings) {
    return penumbra::plan_local_shadows(to_core(lights), settings);
}
inline float local_shadow_near_plane(const Light& light, float nearest_caster) {
    return penumbra::local_shadow_near_plane(to_core(light), nearest_caster);
}
inline glm::mat4 spot_shadow_view_projection(const Light& spot, float near_plane) {
    return penumbra::spot_shadow_view_projection(to_core(spot), near_plane);
}
inline bool cube_face_reaches_cone(const Light& light, size_t face) {
    return penumbra::cube_face_reaches_cone(to_core(light), face);
}
inline void fit_local_shadows(LocalShadowPlan& plan, const std::vector<Light>& lights,
                              const std::vector<Aabb>& caster_boxes) {
    penumbra::fit_local_shadows(plan, to_core(lights), to_core(caster_boxes));
}
inline Sphere local_light_bounds(const Light& light) { return penumbra::local_light_bounds(to_core(light)); }
inline uint32_t coverage_shadow_resolution(const Light& light, const CameraView& camera, uint32_t viewport_height,
                                           uint32_t max_resolution) {
    return penumbra::coverage_shadow_resolution(to_core(light), camera, viewport_height, max_resolution);
}
inline void size_local_shadows(LocalShadowPlan& plan, const std::vector<Light>& lights, const CameraView& camera,
                               uint32_t viewport_height, uint32_t max_resolution) {
    penumbra::size_local_shadows(plan, to_core(lights), camera, viewport_height, max_resolution);
}
inline float nearest_caster_distance(const glm::vec3& point, const std::vector<Aabb>& boxes, float max_far) {
    return penumbra::nearest_caster_distance(point, to_core(boxes), max_far);
}
inline bool caster_may_shadow_frustum(const glm::mat4& view_projection, const Aabb& box) {
    return penumbra::caster_may_shadow_frustum(view_projection, to_core(box));
}
inline bool caster_may_shadow_sphere(const glm::vec3& center, float radius, const Aabb& box) {
    return penumbra::caster_may_shadow_sphere(center, radius, to_core(box));
}

}  // namespace penumbra::testing

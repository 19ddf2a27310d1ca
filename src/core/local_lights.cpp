#include "core/local_lights.hpp"

#include <algorithm>
#include <cmath>

#include "core/camera_math.hpp"

namespace penumbra {
namespace {

// The axes of the cube faces, in layer order.
const std::array<glm::vec3, 6> kCubeFaceAxes{glm::vec3(1, 0, 0),  glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0),
                                             glm::vec3(0, -1, 0), glm::vec3(0, 0, 1),  glm::vec3(0, 0, -1)};

// A view matrix looking from `eye` along `forward`, with any up not parallel to it.
glm::mat4 look_along(const glm::vec3& eye, const glm::vec3& forward, const glm::vec3& preferred_up) {
    const glm::vec3 f = glm::normalize(forward);
    const glm::vec3 up = std::abs(glm::dot(f, preferred_up)) > 0.99f ? glm::vec3(1.0f, 0.0f, 0.0f) : preferred_up;
    return glm::lookAt(eye, eye + f, up);
}

}  // namespace

bool local_shadow_is_cube(const core::Light& light) {
    return light.type == LightType::Point ||
           (light.type == LightType::Spot && light.outer_angle_degrees > kMaxPerspectiveSpotAngle);
}

uint32_t local_shadow_layers(const core::Light& light) {
    if (light.type == LightType::Directional) return 0;
    return local_shadow_is_cube(light) ? 6 : 1;
}

float local_shadow_half_fov(const core::Light& light) {
    return glm::radians(local_shadow_is_cube(light) ? 45.0f : light.outer_angle_degrees);
}

LocalShadowPlan plan_local_shadows(std::span<const core::Light> lights, const LocalShadowSettings& settings) {
    LocalShadowPlan plan;
    for (uint32_t i = 0; i < lights.size(); ++i) {
        const core::Light& light = lights[i];
        if (light.type == LightType::Directional || !light.cast_shadows) continue;
        const uint32_t layers = local_shadow_layers(light);
        if (plan.slots.size() >= settings.budget || plan.layer_count + layers > kMaxLocalShadowLayers) {
            plan.unshadowed.push_back(i);
            continue;
        }
        LocalShadowSlot slot;
        slot.light = i;
        slot.first_layer = plan.layer_count;
        slot.fixed_resolution = light.shadow_resolution != 0 || settings.sizing == LocalShadowSizing::Fixed;
        slot.resolution = light.shadow_resolution != 0 ? light.shadow_resolution : settings.resolution;
        slot.view_projection.resize(layers);
        plan.layer_count += layers;
        plan.atlas_resolution = std::max(plan.atlas_resolution, slot.resolution);
        plan.slots.push_back(std::move(slot));
    }
    return plan;
}

float nearest_caster_distance(const glm::vec3& point, const std::vector<core::Aabb>& boxes, float max_far) {
    float nearest = max_far;
    for (const core::Aabb& box : boxes) {
        if (box.empty()) continue;
        const glm::vec3 closest = glm::clamp(point, box.min, box.max);
        nearest = std::min(nearest, glm::length(closest - point));
    }
    // Never closer than the minimum (depth precision), never at or past the far plane.
    return std::clamp(nearest, kMinLocalShadowNear, std::max(kMinLocalShadowNear, max_far * 0.5f));
}

float local_shadow_near_plane(const core::Light& light, float nearest_caster) {
    const float corner_tangent = std::sqrt(2.0f) * std::tan(local_shadow_half_fov(light));
    const float corner_cosine = 1.0f / std::sqrt(1.0f + corner_tangent * corner_tangent);
    return std::max(kMinLocalShadowNear, nearest_caster * corner_cosine);
}

glm::mat4 spot_shadow_view_projection(const core::Light& spot, float near_plane) {
    const float fov = glm::radians(2.0f * spot.outer_angle_degrees);
    const glm::mat4 view = look_along(spot.position, spot.direction, glm::vec3(0.0f, 1.0f, 0.0f));
    return perspective_reverse_z(fov, 1.0f, near_plane, spot.range) * view;
}

std::array<glm::mat4, 6> point_shadow_view_projections(const glm::vec3& position, float near_plane, float far_plane) {
    const glm::mat4 projection = perspective_reverse_z(glm::radians(90.0f), 1.0f, near_plane, far_plane);
    std::array<glm::mat4, 6> faces{};
    for (size_t face = 0; face < 6; ++face) {
        faces[face] = projection * look_along(position, kCubeFaceAxes[face], glm::vec3(0.0f, 1.0f, 0.0f));
    }
    return faces;
}

bool cube_face_reaches_cone(const core::Light& light, size_t face) {
    if (light.type != LightType::Spot) return true;
    const glm::vec3 axis = kCubeFaceAxes.at(face);
    const float degrees_from_spot_axis =
        glm::degrees(std::acos(std::clamp(glm::dot(axis, glm::normalize(light.direction)), -1.0f, 1.0f)));
    const float face_corner_degrees = glm::degrees(std::atan(std::sqrt(2.0f)));
    return degrees_from_spot_axis - face_corner_degrees < light.outer_angle_degrees;
}

void fit_local_shadows(LocalShadowPlan& plan, std::span<const core::Light> lights,
                       const std::vector<core::Aabb>& caster_boxes) {
    for (LocalShadowSlot& slot : plan.slots) {
        const core::Light& light = lights[slot.light];
        slot.near_plane =
            local_shadow_near_plane(light, nearest_caster_distance(light.position, caster_boxes, light.range));
        slot.far_plane = light.range;
        if (!local_shadow_is_cube(light)) {
            slot.view_projection = {spot_shadow_view_projection(light, slot.near_plane)};
        } else {
            const auto faces = point_shadow_view_projections(light.position, slot.near_plane, light.range);
            slot.view_projection.assign(faces.begin(), faces.end());
        }
    }
}

Sphere local_light_bounds(const core::Light& light) {
    if (light.type != LightType::Spot) return {light.position, light.range};
    const float cos_outer = std::cos(glm::radians(light.outer_angle_degrees));
    const float radius = light.range / (2.0f * std::max(cos_outer, 1e-3f));
    if (radius >= light.range) return {light.position, light.range};
    return {light.position + glm::normalize(light.direction) * radius, radius};
}

namespace {

uint32_t next_power_of_two(float value) {
    uint32_t power = 1;
    while (static_cast<float>(power) < value && power < (1u << 30)) power <<= 1;
    return power;
}

// Whether a sphere lies entirely outside one of the camera frustum's planes (Gribb-Hartmann).
bool sphere_outside_frustum(const glm::mat4& view_projection, const Sphere& sphere) {
    const glm::mat4 m = glm::transpose(view_projection);
    const std::array<glm::vec4, 6> planes{m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[2], m[3] - m[2]};
    for (const glm::vec4& plane : planes) {
        const float length = glm::length(glm::vec3(plane));
        if (length == 0.0f) continue;
        if ((glm::dot(glm::vec3(plane), sphere.center) + plane.w) / length < -sphere.radius) return true;
    }
    return false;
}

}  // namespace

uint32_t coverage_shadow_resolution(const core::Light& light, const CameraView& camera, uint32_t viewport_height,
                                    uint32_t max_resolution) {
    const uint32_t min_resolution = std::min(kMinCoverageShadowResolution, max_resolution);
    const Sphere bounds = local_light_bounds(light);
    const float distance = glm::length(bounds.center - camera.eye);
    if (distance <= bounds.radius) return max_resolution;
    if (sphere_outside_frustum(camera.view_projection, bounds)) return min_resolution;
    // The sphere's angular radius asin(r / d) as its half-width at distance d, in pixels at
    // the screen's centre: the frustum's height there is base + per_metre * d metres
    // (a perspective's 2 tan(fov / 2) d, an orthographic view's constant height).
    const float sine = bounds.radius / distance;
    const FrustumSpan span = vertical_frustum_span(camera);
    const float half_width = distance * sine / std::sqrt(1.0f - sine * sine);
    float pixels_across =
        2.0f * half_width * static_cast<float>(viewport_height) / (span.base + span.per_metre * distance);
    if (local_shadow_is_cube(light)) pixels_across *= 0.5f;
    return std::clamp(next_power_of_two(pixels_across), min_resolution, max_resolution);
}

void size_local_shadows(LocalShadowPlan& plan, std::span<const core::Light> lights, const CameraView& camera,
                        uint32_t viewport_height, uint32_t max_resolution) {
    const SizedCamera view{camera, viewport_height};
    size_local_shadows(plan, lights, std::span<const SizedCamera>(&view, 1), max_resolution);
}

void size_local_shadows(LocalShadowPlan& plan, std::span<const core::Light> lights, std::span<const SizedCamera> views,
                        uint32_t max_resolution) {
    for (LocalShadowSlot& slot : plan.slots) {
        if (slot.fixed_resolution) continue;
        uint32_t resolution = 0;
        for (const SizedCamera& view : views) {
            resolution = std::max(resolution, coverage_shadow_resolution(lights[slot.light], view.camera,
                                                                         view.viewport_height, max_resolution));
        }
        slot.resolution = resolution;
    }
}

bool caster_may_shadow_frustum(const glm::mat4& view_projection, const core::Aabb& box) {
    if (box.empty()) return false;
    // Gribb-Hartmann: rows of the clip matrix combine into the planes -w <= x, y <= w and
    // 0 <= z <= w (reverse-Z, so z >= 0 is the far plane and z <= w the near plane).
    const glm::mat4 m = glm::transpose(view_projection);
    const std::array<glm::vec4, 5> planes{m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[2]};
    for (const glm::vec4& plane : planes) {
        // The box corner farthest along the plane normal (the "positive vertex").
        const glm::vec3 positive(plane.x >= 0.0f ? box.max.x : box.min.x, plane.y >= 0.0f ? box.max.y : box.min.y,
                                 plane.z >= 0.0f ? box.max.z : box.min.z);
        if (glm::dot(glm::vec3(plane), positive) + plane.w < 0.0f) return false;
    }
    return true;
}

bool caster_may_shadow_sphere(const glm::vec3& center, float radius, const core::Aabb& box) {
    if (box.empty()) return false;
    // Squared, as the GPU's culling compares (shaders/caster_cull.comp), without a square root.
    const glm::vec3 offset = glm::clamp(center, box.min, box.max) - center;
    return glm::dot(offset, offset) <= radius * radius;
}

}  // namespace penumbra

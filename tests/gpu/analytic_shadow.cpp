#include "analytic_shadow.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace penumbra::testing {
namespace {

std::array<glm::vec3, 8> corners(const Box& box) {
    std::array<glm::vec3, 8> result{};
    for (int i = 0; i < 8; ++i) {
        result[i] = {(i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y, (i & 4) ? box.max.z : box.min.z};
    }
    return result;
}

}  // namespace

std::string ground_scene_toml(const glm::vec3& light_direction, const std::string& objects) {
    char header[512];
    std::snprintf(header, sizeof(header), R"(
[camera]
eye = [0.0, 9.0, 7.0]
target = [0.0, 0.0, 0.0]
fov = 50.0
near = 0.1
far = 60.0

[[lights]]
type = "directional"
direction = [%f, %f, %f]

[[objects]]
type = "plane"
size = [30.0, 30.0]
)",
                  light_direction.x, light_direction.y, light_direction.z);
    return header + objects;
}

PixelRay pixel_ray(const PinholeCamera& camera, uint32_t width, uint32_t height, uint32_t x, uint32_t y) {
    const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float tan_half = std::tan(glm::radians(camera.fov_y_degrees) * 0.5f);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const float ndc_x = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 1.0f;
    const float ndc_y = 1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height);
    const glm::vec3 direction = forward + right * (ndc_x * tan_half * aspect) + up * (ndc_y * tan_half);
    return {camera.eye, glm::normalize(direction)};
}

std::optional<float> intersect_box(const PixelRay& ray, const Box& box) {
    float t_near = 0.0f;
    float t_far = 1e30f;
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(ray.direction[axis]) < 1e-12f) {
            if (ray.origin[axis] < box.min[axis] || ray.origin[axis] > box.max[axis]) return std::nullopt;
            continue;
        }
        float t0 = (box.min[axis] - ray.origin[axis]) / ray.direction[axis];
        float t1 = (box.max[axis] - ray.origin[axis]) / ray.direction[axis];
        if (t0 > t1) std::swap(t0, t1);
        t_near = std::max(t_near, t0);
        t_far = std::min(t_far, t1);
        if (t_near > t_far) return std::nullopt;
    }
    return t_near;
}

std::optional<float> intersect_ground(const PixelRay& ray, float half_size) {
    if (ray.direction.y >= -1e-9f) return std::nullopt;
    const float t = -ray.origin.y / ray.direction.y;
    const glm::vec3 hit = ray.origin + ray.direction * t;
    if (std::abs(hit.x) > half_size || std::abs(hit.z) > half_size) return std::nullopt;
    return t;
}

std::vector<glm::vec2> convex_hull(std::vector<glm::vec2> points) {
    // Andrew's monotone chain, counter-clockwise.
    std::sort(points.begin(), points.end(),
              [](const glm::vec2& a, const glm::vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    const auto cross = [](const glm::vec2& o, const glm::vec2& a, const glm::vec2& b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<glm::vec2> hull(2 * points.size());
    size_t k = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    for (size_t i = points.size() - 1, lower = k + 1; i > 0; --i) {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i - 1]) <= 0) --k;
        hull[k++] = points[i - 1];
    }
    hull.resize(k - 1);
    return hull;
}

std::vector<glm::vec2> shadow_polygon(const Box& box, const glm::vec3& light_direction) {
    std::vector<glm::vec2> points;
    for (const glm::vec3& corner : corners(box)) {
        const float t = -corner.y / light_direction.y;  // travel along the light down to y = 0
        const glm::vec3 ground = corner + light_direction * t;
        points.emplace_back(ground.x, ground.z);
    }
    return convex_hull(points);
}

std::vector<glm::vec2> point_light_shadow_polygon(const Box& box, const glm::vec3& light_position) {
    std::vector<glm::vec2> points;
    for (const glm::vec3& corner : corners(box)) {
        // Along the ray from the light through the corner, down to y = 0.
        const glm::vec3 ground =
            light_position + (corner - light_position) * (light_position.y / (light_position.y - corner.y));
        points.emplace_back(ground.x, ground.z);
    }
    return convex_hull(points);
}

bool inside_convex_polygon(const std::vector<glm::vec2>& polygon, const glm::vec2& point) {
    for (size_t i = 0; i < polygon.size(); ++i) {
        const glm::vec2& a = polygon[i];
        const glm::vec2& b = polygon[(i + 1) % polygon.size()];
        if ((b.x - a.x) * (point.y - a.y) - (b.y - a.y) * (point.x - a.x) < 0.0f) return false;
    }
    return true;
}

float distance_to_polygon_edge(const std::vector<glm::vec2>& polygon, const glm::vec2& point) {
    float best = 1e30f;
    for (size_t i = 0; i < polygon.size(); ++i) {
        const glm::vec2 a = polygon[i];
        const glm::vec2 edge = polygon[(i + 1) % polygon.size()] - a;
        const float t = std::clamp(glm::dot(point - a, edge) / glm::dot(edge, edge), 0.0f, 1.0f);
        best = std::min(best, glm::length(point - (a + edge * t)));
    }
    return best;
}

}  // namespace penumbra::testing

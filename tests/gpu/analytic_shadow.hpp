#pragma once
// Ground truth for image tests, computed from geometry alone: which pixels see the
// ground plane y = 0, and which of those lie in the shadow of an axis-aligned box lit
// by a directional light (the convex hull of the box corners projected along the
// light onto the plane).
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace penumbra::testing {

// An axis-aligned box. Scene-free, so that the library's tests (built without the scene
// component) share these functions; converts from any type with `min` and `max` (the scene
// component's Aabb).
struct Box {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};

    Box(const glm::vec3& lower, const glm::vec3& upper) : min(lower), max(upper) {}
    template <class Bounds>
    Box(const Bounds& bounds) : min(bounds.min), max(bounds.max) {}  // NOLINT: implicit on purpose
};

// A pinhole camera looking from `eye` at `target`; converts from any type with those
// members and `up` and `fov_y_degrees` (the scene component's Camera).
struct PinholeCamera {
    glm::vec3 eye{0.0f, 6.0f, 12.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 60.0f;  // vertical field of view

    PinholeCamera() = default;
    template <class Camera>
    PinholeCamera(const Camera& camera)  // NOLINT: implicit on purpose
        : eye(camera.eye), target(camera.target), up(camera.up), fov_y_degrees(camera.fov_y_degrees) {}
};

// The ground scene of the footprint and compare tests: a 30 x 30 m plane at y = 0
// (|x|, |z| <= kGroundSceneHalfSize) seen from (0, 9, 7), a directional light along
// `light_direction`, and `objects` (TOML [[objects]] tables) above the ground.
inline constexpr float kGroundSceneHalfSize = 15.0f;
std::string ground_scene_toml(const glm::vec3& light_direction, const std::string& objects);

// A 3 x 0.5 x 2 m box floating 2 m above that ground: its [[objects]] table and its bounds.
inline constexpr const char* kFloatingBoxToml = R"(
[[objects]]
type = "box"
size = [3.0, 0.5, 2.0]
translation = [0.0, 2.0, 0.0]
)";
inline const Box kFloatingBoxBounds{{-1.5f, 1.75f, -1.0f}, {1.5f, 2.25f, 1.0f}};

struct PixelRay {
    glm::vec3 origin;
    glm::vec3 direction;  // normalised
};

// The primary ray through the centre of pixel (x, y), row 0 at the top.
PixelRay pixel_ray(const PinholeCamera& camera, uint32_t width, uint32_t height, uint32_t x, uint32_t y);

// Distance along the ray to the box, if it hits.
std::optional<float> intersect_box(const PixelRay& ray, const Box& box);

// Distance along the ray to the plane y = 0 within |x|, |z| <= half_size.
std::optional<float> intersect_ground(const PixelRay& ray, float half_size);

// The convex hull of points, counter-clockwise.
std::vector<glm::vec2> convex_hull(std::vector<glm::vec2> points);

// The box's shadow on y = 0: corners projected along light_direction, as a convex polygon.
std::vector<glm::vec2> shadow_polygon(const Box& box, const glm::vec3& light_direction);

// The box's shadow on y = 0 under a point light above it (light_position.y > box.max.y).
std::vector<glm::vec2> point_light_shadow_polygon(const Box& box, const glm::vec3& light_position);

bool inside_convex_polygon(const std::vector<glm::vec2>& polygon, const glm::vec2& point);

// Distance from a point to the polygon's boundary.
float distance_to_polygon_edge(const std::vector<glm::vec2>& polygon, const glm::vec2& point);

}  // namespace penumbra::testing

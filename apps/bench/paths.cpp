#include "bench/paths.hpp"

#include <cmath>
#include <numbers>

namespace penumbra::bench {
namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

glm::vec3 rotate_about_y(const glm::vec3& v, float angle) {
    const float c = std::cos(angle);
    const float s = std::sin(angle);
    return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
}

Camera orbit(const Camera& start, float t) {
    Camera camera = start;
    camera.eye = start.target + rotate_about_y(start.eye - start.target, kTwoPi * t);
    return camera;
}

Camera flythrough(const Camera& start, float t) {
    const glm::vec3 view = start.target - start.eye;
    glm::vec3 ahead{view.x, 0.0f, view.z};
    float distance = 2.0f * glm::length(ahead);
    // Looking straight down: fly along -Z for a few view distances instead.
    if (distance < 1e-3f) {
        ahead = {0.0f, 0.0f, -1.0f};
        distance = 4.0f * glm::length(view);
    }
    ahead = glm::normalize(ahead);
    const glm::vec3 side{-ahead.z, 0.0f, ahead.x};
    Camera camera = start;
    camera.eye = start.eye + ahead * (distance * t) + side * (0.05f * distance * std::sin(kTwoPi * t));
    camera.target = camera.eye + view;  // same view direction all along
    return camera;
}

}  // namespace

Camera camera_on_path(CameraPath path, const Camera& start, float t) {
    return path == CameraPath::Orbit ? orbit(start, t) : flythrough(start, t);
}

glm::vec3 sun_on_path(LightPath path, const glm::vec3& start, float t) {
    return path == LightPath::Fixed ? start : rotate_about_y(start, kTwoPi * t);
}

const char* camera_path_name(CameraPath path) { return path == CameraPath::Orbit ? "orbit" : "flythrough"; }
const char* light_path_name(LightPath path) { return path == LightPath::Fixed ? "fixed" : "rotate"; }

}  // namespace penumbra::bench

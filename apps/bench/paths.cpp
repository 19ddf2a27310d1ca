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

// A walker's speed (1.4 m/s) at 60 frames a second.
constexpr float kWalkMetresPerFrame = 1.4f / 60.0f;

Camera walk(const Camera& start, float t, uint32_t frames) {
    const glm::vec3 view = start.target - start.eye;
    glm::vec3 ahead{view.x, 0.0f, view.z};
    ahead = glm::length(ahead) > 1e-3f ? glm::normalize(ahead) : glm::vec3(0.0f, 0.0f, -1.0f);
    const glm::vec3 step = ahead * (kWalkMetresPerFrame * t * static_cast<float>(frames));
    Camera camera = start;
    camera.eye += step;
    camera.target += step;
    return camera;
}

}  // namespace

Camera camera_on_path(CameraPath path, const Camera& start, float t, uint32_t frames) {
    switch (path) {
        case CameraPath::Orbit:
            return orbit(start, t);
        case CameraPath::Flythrough:
            return flythrough(start, t);
        case CameraPath::Walk:
            return walk(start, t, frames);
        case CameraPath::Still:
            break;
    }
    return start;
}

glm::vec3 sun_on_path(LightPath path, const glm::vec3& start, float t) {
    return path == LightPath::Fixed ? start : rotate_about_y(start, kTwoPi * t);
}

const char* camera_path_name(CameraPath path) { return choice_name(kCameraPathChoices, path); }
const char* light_path_name(LightPath path) { return choice_name(kLightPathChoices, path); }

}  // namespace penumbra::bench

#include "view_controls.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace penumbra::view {
namespace {

constexpr float kMinAngleToUp = glm::radians(1.0f);

glm::vec3 rotate(const glm::vec3& v, float radians, const glm::vec3& axis) {
    return glm::angleAxis(radians, glm::normalize(axis)) * v;
}

// Turns `offset` (a view direction times a distance) by yaw about `up` and by pitch about
// the camera's right axis, keeping it at least kMinAngleToUp away from +-up.
glm::vec3 turn_offset(const glm::vec3& offset, const glm::vec3& up, float yaw, float pitch) {
    const float length = glm::length(offset);
    glm::vec3 direction = offset / length;
    direction = rotate(direction, yaw, up);
    const float angle_to_up = std::acos(std::clamp(glm::dot(direction, up), -1.0f, 1.0f));
    // Pitching up decreases the angle to up; clamp so that it stays in [min, pi - min].
    const float new_angle = std::clamp(angle_to_up - pitch, kMinAngleToUp, glm::pi<float>() - kMinAngleToUp);
    const glm::vec3 right = glm::cross(direction, up);
    if (glm::length(right) > 1e-6f) direction = rotate(direction, angle_to_up - new_angle, right);
    return glm::normalize(direction) * length;
}

}  // namespace

CameraController::CameraController(const Camera& initial) : initial_(initial), camera_(initial) {
    speed = std::max(2.0f, glm::length(initial.target - initial.eye) * 0.5f);
}

void CameraController::move(const glm::vec3& right_up_forward) {
    const glm::vec3 up = glm::normalize(camera_.up);
    const glm::vec3 forward = glm::normalize(camera_.target - camera_.eye);
    glm::vec3 right = glm::cross(forward, up);
    right = glm::length(right) > 1e-6f ? glm::normalize(right) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 offset = right * right_up_forward.x + up * right_up_forward.y + forward * right_up_forward.z;
    camera_.eye += offset;
    camera_.target += offset;
}

void CameraController::turn(float yaw_degrees, float pitch_degrees) {
    const glm::vec3 up = glm::normalize(camera_.up);
    const float yaw = glm::radians(yaw_degrees);
    const float pitch = glm::radians(pitch_degrees);
    if (mode_ == CameraMode::Fly) {
        camera_.target = camera_.eye + turn_offset(camera_.target - camera_.eye, up, yaw, pitch);
    } else {
        // Orbiting: the eye moves about the target; looking up means the eye goes down.
        camera_.eye = camera_.target + turn_offset(camera_.eye - camera_.target, up, yaw, -pitch);
    }
}

void CameraController::zoom(float factor) {
    if (mode_ != CameraMode::Orbit) return;
    const glm::vec3 offset = camera_.eye - camera_.target;
    const float distance = std::max(0.05f, glm::length(offset) * factor);
    camera_.eye = camera_.target + glm::normalize(offset) * distance;
}

SunAngles sun_angles(const glm::vec3& travel_direction) {
    const glm::vec3 toward_sun = -glm::normalize(travel_direction);
    SunAngles angles;
    angles.elevation_degrees = glm::degrees(std::asin(std::clamp(toward_sun.y, -1.0f, 1.0f)));
    angles.azimuth_degrees = glm::degrees(std::atan2(toward_sun.x, toward_sun.z));
    return angles;
}

glm::vec3 sun_travel_direction(const SunAngles& angles) {
    const float azimuth = glm::radians(angles.azimuth_degrees);
    const float elevation = glm::radians(angles.elevation_degrees);
    const glm::vec3 toward_sun(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                               std::cos(elevation) * std::cos(azimuth));
    return -toward_sun;
}

}  // namespace penumbra::view

#include "quality/camera_jitter.hpp"

#include <algorithm>
#include <array>
#include <cmath>

// glm keeps rotate_vector among its experimental extensions.
#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/rotate_vector.hpp>

namespace penumbra::quality {
namespace {

// Motion sizes in texels, cycled through: sub-texel, one texel, a few texels.
constexpr std::array<float, 6> kTexelSteps{0.25f, 0.5f, 1.0f, 1.5f, 2.0f, 3.0f};
constexpr float kGoldenAngle = 2.39996323f;  // radians: successive directions spread evenly

}  // namespace

Camera jittered_camera(const Camera& camera, uint32_t frame, float texel_world_size) {
    if (frame == 0) return camera;
    const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float steps = kTexelSteps[(frame - 1) % kTexelSteps.size()];
    const float angle = kGoldenAngle * static_cast<float>(frame);
    const float distance = steps * texel_world_size;

    // Translation in the image plane and along the view, then a turn (yaw and pitch) whose
    // shift at the target is the same distance.
    const glm::vec3 translation =
        (right * std::cos(angle) + up * std::sin(angle) + forward * 0.5f * std::sin(2.0f * angle)) * distance;
    const float target_distance = glm::length(camera.target - camera.eye);
    const float turn = distance / std::max(target_distance, 1e-3f);
    glm::vec3 view = camera.target - camera.eye;
    view = glm::rotate(view, turn * std::sin(angle), up);
    view = glm::rotate(view, turn * std::cos(angle), right);

    Camera moved = camera;
    moved.eye = camera.eye + translation;
    moved.target = moved.eye + view;
    return moved;
}

}  // namespace penumbra::quality

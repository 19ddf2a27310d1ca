#pragma once
// Camera matrices and frustum geometry. Conventions used everywhere in Penumbra:
// right-handed world, +Y up, the camera looks down -Z in view space; Vulkan clip
// space with the Y axis flipped by the projection so that image row 0 is the top;
// reverse-Z depth (near plane -> 1, far plane -> 0) for precision with D32 float.
#include <array>

#include "core/glm_config.hpp"
#include "core/shadow_inputs.hpp"

namespace penumbra {

struct CameraView {
    glm::mat4 view{1.0f};        // world -> view (camera looks down -Z)
    glm::mat4 projection{1.0f};  // view -> Vulkan clip, reverse-Z, Y flipped
    glm::mat4 view_projection{1.0f};
    glm::vec3 eye{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};
    float fov_y_radians = 1.0f;
    float aspect = 1.0f;  // width / height
    float near_plane = 0.1f;
    float far_plane = 100.0f;
};

// Reverse-Z perspective projection into Vulkan clip space (depth 1 at near, 0 at far).
glm::mat4 perspective_reverse_z(float fov_y_radians, float aspect, float near_plane, float far_plane);

// Reverse-Z orthographic projection: view-space z = -near maps to depth 1, z = -far to 0.
// x in [left, right] and y in [bottom, top] map to [-1, 1] (no Y flip: shadow maps are
// sampled with the same matrix that rendered them, so orientation is irrelevant).
glm::mat4 orthographic_reverse_z(float left, float right, float bottom, float top, float near_plane, float far_plane);

// Builds the camera's matrices. Requires eye != target and a non-degenerate up vector
// (the scene loader validates both; an up parallel to the view direction is replaced).
CameraView make_camera_view(const core::Camera& camera, float aspect);

// The same for a caller's view matrix (world -> view, looking down -Z); the eye and the
// forward direction are taken from its inverse. Requires an invertible `view`.
CameraView make_camera_view(const glm::mat4& view, float fov_y_radians, float aspect, float near_plane,
                            float far_plane);

// World-space corners of the view frustum between view distances slice_near and slice_far
// (distances along the view direction). Order: near plane (4), then far plane (4).
std::array<glm::vec3, 8> frustum_slice_corners(const CameraView& camera, float slice_near, float slice_far);

}  // namespace penumbra

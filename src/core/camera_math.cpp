#include "core/camera_math.hpp"

#include <cmath>

namespace penumbra {

glm::mat4 perspective_reverse_z(float fov_y_radians, float aspect, float near_plane, float far_plane) {
    const float focal = 1.0f / std::tan(fov_y_radians * 0.5f);
    glm::mat4 m(0.0f);
    m[0][0] = focal / aspect;
    m[1][1] = -focal;  // Vulkan: +Y in clip space points down the image
    // depth = (a * z + b) / -z with depth(-near) = 1 and depth(-far) = 0.
    m[2][2] = near_plane / (far_plane - near_plane);
    m[2][3] = -1.0f;
    m[3][2] = far_plane * near_plane / (far_plane - near_plane);
    return m;
}

glm::mat4 orthographic_reverse_z(float left, float right, float bottom, float top, float near_plane, float far_plane) {
    glm::mat4 m(1.0f);
    m[0][0] = 2.0f / (right - left);
    m[1][1] = 2.0f / (top - bottom);
    m[3][0] = -(right + left) / (right - left);
    m[3][1] = -(top + bottom) / (top - bottom);
    // depth = a * z + b with depth(-near) = 1 and depth(-far) = 0.
    m[2][2] = 1.0f / (far_plane - near_plane);
    m[3][2] = far_plane / (far_plane - near_plane);
    return m;
}

CameraView make_camera_view(const core::Camera& camera, float aspect) {
    CameraView result;
    result.eye = camera.eye;
    result.forward = glm::normalize(camera.target - camera.eye);
    glm::vec3 up = camera.up;
    if (glm::length(glm::cross(result.forward, up)) < 1e-4f) {
        // Looking along the up axis: any perpendicular up keeps the basis valid.
        up = std::abs(result.forward.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    }
    result.view = glm::lookAtRH(camera.eye, camera.target, up);
    result.fov_y_radians = glm::radians(camera.fov_y_degrees);
    result.aspect = aspect;
    result.near_plane = camera.near_plane;
    result.far_plane = camera.far_plane;
    result.projection = perspective_reverse_z(result.fov_y_radians, aspect, camera.near_plane, camera.far_plane);
    result.view_projection = result.projection * result.view;
    return result;
}

CameraView make_camera_view(const glm::mat4& view, float fov_y_radians, float aspect, float near_plane,
                            float far_plane) {
    const glm::mat4 view_to_world = glm::inverse(view);
    CameraView result;
    result.view = view;
    result.eye = glm::vec3(view_to_world[3]);
    result.forward = glm::normalize(-glm::vec3(view_to_world[2]));
    result.fov_y_radians = fov_y_radians;
    result.aspect = aspect;
    result.near_plane = near_plane;
    result.far_plane = far_plane;
    result.projection = perspective_reverse_z(fov_y_radians, aspect, near_plane, far_plane);
    result.view_projection = result.projection * view;
    return result;
}

std::array<glm::vec3, 8> frustum_slice_corners(const CameraView& camera, float slice_near, float slice_far) {
    const glm::mat4 view_to_world = glm::inverse(camera.view);
    const float tan_half_y = std::tan(camera.fov_y_radians * 0.5f);
    const float tan_half_x = tan_half_y * camera.aspect;
    std::array<glm::vec3, 8> corners{};
    const float distances[2] = {slice_near, slice_far};
    for (int plane = 0; plane < 2; ++plane) {
        const float d = distances[plane];
        for (int i = 0; i < 4; ++i) {
            const float sx = (i & 1) ? 1.0f : -1.0f;
            const float sy = (i & 2) ? 1.0f : -1.0f;
            const glm::vec4 view_point(sx * tan_half_x * d, sy * tan_half_y * d, -d, 1.0f);
            corners[plane * 4 + i] = glm::vec3(view_to_world * view_point);
        }
    }
    return corners;
}

}  // namespace penumbra

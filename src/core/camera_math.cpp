#include "core/camera_math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

namespace {

// A symmetric perspective's edges: slopes (+-tan_x, +-tan_y) from the eye.
void set_symmetric_edges(CameraView& camera) {
    const float tan_half_y = std::tan(camera.fov_y_radians * 0.5f);
    const float tan_half_x = tan_half_y * camera.aspect;
    for (int i = 0; i < 4; ++i) {
        camera.edge_origin[i] = glm::vec2(0.0f);
        camera.edge_slope[i] = glm::vec2((i & 1) ? tan_half_x : -tan_half_x, (i & 2) ? tan_half_y : -tan_half_y);
    }
}

// View-space point of an NDC position, or nullopt-like w == 0 (a point at infinity).
glm::vec4 unproject(const glm::mat4& inverse_projection, float x, float y, float z) {
    return inverse_projection * glm::vec4(x, y, z, 1.0f);
}

// View distance (along -Z) of NDC depth z on the axis; +infinity at an infinite far plane.
float view_distance_at(const glm::mat4& inverse_projection, float z) {
    const glm::vec4 point = unproject(inverse_projection, 0.0f, 0.0f, z);
    if (std::abs(point.w) < 1e-12f * std::max(1.0f, std::abs(point.z))) return std::numeric_limits<float>::infinity();
    return -point.z / point.w;
}

// The view matrix with the eye and forward direction it places the camera at.
CameraView camera_view_placed_by(const glm::mat4& view) {
    const glm::mat4 view_to_world = glm::inverse(view);
    CameraView result;
    result.view = view;
    result.eye = glm::vec3(view_to_world[3]);
    result.forward = glm::normalize(-glm::vec3(view_to_world[2]));
    return result;
}

}  // namespace

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
    set_symmetric_edges(result);
    return result;
}

CameraView make_camera_view(const glm::mat4& view, float fov_y_radians, float aspect, float near_plane,
                            float far_plane) {
    CameraView result = camera_view_placed_by(view);
    result.fov_y_radians = fov_y_radians;
    result.aspect = aspect;
    result.near_plane = near_plane;
    result.far_plane = far_plane;
    result.projection = perspective_reverse_z(fov_y_radians, aspect, near_plane, far_plane);
    result.view_projection = result.projection * view;
    set_symmetric_edges(result);
    return result;
}

CameraView make_camera_view(const glm::mat4& view, const glm::mat4& projection, uint32_t width, uint32_t height) {
    const glm::mat4 inverse_projection = glm::inverse(projection);
    CameraView result = camera_view_placed_by(view);
    result.projection = projection;
    result.view_projection = projection * view;
    // Depth 0 and 1 are the near and far planes in either order (reverse or forward Z).
    const float at_zero = view_distance_at(inverse_projection, 0.0f);
    const float at_one = view_distance_at(inverse_projection, 1.0f);
    result.near_plane = std::min(at_zero, at_one);
    result.far_plane = std::max(at_zero, at_one);
    // Each edge through two finite depths: the near plane's and halfway (finite even with
    // an infinite far plane).
    const float near_z = at_zero < at_one ? 0.0f : 1.0f;
    for (int i = 0; i < 4; ++i) {
        const float x = (i & 1) ? 1.0f : -1.0f;
        const float y = (i & 2) ? 1.0f : -1.0f;
        const glm::vec4 a4 = unproject(inverse_projection, x, y, near_z);
        const glm::vec4 b4 = unproject(inverse_projection, x, y, 0.5f);
        const glm::vec3 a = glm::vec3(a4) / a4.w;
        const glm::vec3 b = glm::vec3(b4) / b4.w;
        const glm::vec2 slope = (glm::vec2(b) - glm::vec2(a)) / (a.z - b.z);  // per metre of distance (-z)
        result.edge_slope[i] = slope;
        result.edge_origin[i] = glm::vec2(a) - slope * -a.z;
        // A perspective's edges meet at the eye: what is left is rounding.
        if (glm::length(result.edge_origin[i]) <= 1e-3f * glm::length(slope) * -a.z) {
            result.edge_origin[i] = glm::vec2(0.0f);
        }
    }
    // The symmetric perspective the frustum is closest to (level selection, local sizing).
    const glm::vec2 span = glm::abs(result.edge_slope[3] - result.edge_slope[0]);
    result.fov_y_radians = 2.0f * std::atan(0.5f * span.y);
    result.aspect =
        span.y > 0.0f ? span.x / span.y : static_cast<float>(width) / static_cast<float>(std::max(height, 1u));
    result.jitter_allowance = kJitterPixels * span / glm::vec2(std::max(width, 1u), std::max(height, 1u));
    return result;
}

FrustumSpan vertical_frustum_span(const CameraView& camera) {
    return {std::abs(camera.edge_origin[2].y - camera.edge_origin[0].y),
            std::abs(camera.edge_slope[2].y - camera.edge_slope[0].y)};
}

std::array<glm::vec3, 8> frustum_slice_corners(const CameraView& camera, float slice_near, float slice_far) {
    const glm::mat4 view_to_world = glm::inverse(camera.view);
    std::array<glm::vec3, 8> corners{};
    const float distances[2] = {slice_near, slice_far};
    for (int plane = 0; plane < 2; ++plane) {
        const float d = distances[plane];
        for (int i = 0; i < 4; ++i) {
            const glm::vec2 xy = camera.edge_origin[i] + camera.edge_slope[i] * d;
            corners[plane * 4 + i] = glm::vec3(view_to_world * glm::vec4(xy, -d, 1.0f));
        }
    }
    return corners;
}

}  // namespace penumbra

// The public camera helpers: the same matrices Penumbra's own passes and tools use
// (core/camera_math.hpp).
#include "core/camera_math.hpp"
#include "library/conversions.hpp"
#include "penumbra/shadow_system.hpp"

namespace penumbra {

ViewDesc look_at_view(Vec3 eye, Vec3 target, Vec3 up, float fov_y_radians, float near_plane, float far_plane,
                      uint32_t width, uint32_t height) {
    core::Camera camera;
    camera.eye = library::to_glm(eye);
    camera.target = library::to_glm(target);
    camera.up = library::to_glm(up);
    camera.fov_y_degrees = glm::degrees(fov_y_radians);
    camera.near_plane = near_plane;
    camera.far_plane = far_plane;
    const float aspect = height > 0 ? static_cast<float>(width) / static_cast<float>(height) : 1.0f;
    const CameraView view = make_camera_view(camera, aspect);
    return {library::to_public(view.view), fov_y_radians, near_plane, far_plane, width, height};
}

Mat4 reverse_z_projection(const ViewDesc& view) {
    if (view.projection) return *view.projection;
    const float aspect = view.height > 0 ? static_cast<float>(view.width) / static_cast<float>(view.height) : 1.0f;
    return library::to_public(perspective_reverse_z(view.fov_y_radians, aspect, view.near_plane, view.far_plane));
}

}  // namespace penumbra

#pragma once
// Building blocks of cascade fitting (used by compute_cascades, public for tests and
// debug views). All light-space quantities are in the light view of light_view_matrix():
// the light looks down -Z, so a point's distance along the light is -z.
#include <array>
#include <cstdint>

#include "core/camera_math.hpp"
#include "core/shadow_inputs.hpp"

namespace penumbra {

struct BoundingSphere {
    glm::vec3 center{0.0f};
    float radius = 0.0f;
};

// The smallest sphere centred on the view axis that holds the frustum slice between the
// view distances slice_near and slice_far. Computed from fov, aspect and the distances
// alone, so the radius is bit-for-bit independent of the camera's position and rotation.
BoundingSphere frustum_slice_bounding_sphere(const CameraView& camera, float slice_near, float slice_far);

// An orthographic shadow volume in light view space: the XY rectangle (centre and half
// size, so that its size is exact however far from the origin it lies) and the depth
// range as distances along the light (near_distance < far_distance).
struct LightOrthoBox {
    glm::vec2 center{0.0f};
    glm::vec2 half_size{0.0f};
    float near_distance = 0.0f;
    float far_distance = 0.0f;

    glm::vec3 extent() const { return {2.0f * half_size.x, 2.0f * half_size.y, far_distance - near_distance}; }
};

// Stable fit of a sphere given in light view space: a square of side 2 * radius (radius
// rounded up to 1/16 m and padded by half a texel so the snap cannot cut the sphere),
// whose corner lies on the world-fixed grid of texel = 2 * radius / resolution.
LightOrthoBox fit_stable_box(const BoundingSphere& light_space_sphere, uint32_t resolution);

// Tight fit of points given in light view space: their XY bounds, grown by padding_texels
// on each side and by up to one texel so that the rectangle's corner lies on its texel
// grid and width == resolution * texel exactly. The depth range spans the points.
LightOrthoBox fit_tight_box(const std::array<glm::vec3, 8>& light_space_points, uint32_t resolution,
                            float padding_texels);

// Metres added to each end of a scene's depth range (at least; or 1e-3 of the range).
inline constexpr float kMinDepthMargin = 0.01f;

// The depth range of the scene bounds along the light, whatever the slice's own, plus a
// margin, and at least as deep as the window is wide (centred on the scene): casters
// between the light and the slice are rendered, every receiver lies inside, the biases
// keep their size in metres, and the mapping of depth does not change when the camera
// moves (so that a cascade's depths can be cached). An empty box leaves the slice's range.
LightOrthoBox depth_range_of_scene(const LightOrthoBox& box, const core::Aabb& light_space_scene_bounds);

// Reverse-Z orthographic projection of the box: near_distance -> depth 1, far -> 0.
glm::mat4 light_projection(const LightOrthoBox& box);

}  // namespace penumbra

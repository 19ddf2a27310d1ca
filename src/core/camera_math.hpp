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
    float far_plane = 100.0f;  // may be infinite (a caller's infinite-far projection)
    // The frustum's four edges in view space, for the NDC corners (-1,-1), (1,-1), (-1,1),
    // (1,1): at view distance d (along -Z) edge i passes through (edge_origin[i] +
    // edge_slope[i] * d, -d). A perspective's edges leave the eye (origins 0), an
    // orthographic projection's are parallel (slopes 0); off-centre (jittered) frusta have
    // unequal slopes.
    std::array<glm::vec2, 4> edge_origin{};
    std::array<glm::vec2, 4> edge_slope{};
    // A caller's projection (ViewDesc::projection): the off-centre shift, in edge slope,
    // that the stable cascade fit absorbs (kJitterPixels pixels: TAA jitter) by padding a
    // symmetric frustum instead of following it; 0 for Penumbra's own symmetric frusta.
    glm::vec2 jitter_allowance{0.0f};
};

// The sub-pixel (TAA) jitter of a caller's projection that the stable cascade fit absorbs.
inline constexpr float kJitterPixels = 2.0f;

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

// The same for a caller's projection (view -> Vulkan clip space): any perspective
// (symmetric, off-centre or jittered, finite or infinite far, reverse or forward Z) or
// orthographic projection. The near and far planes, the field of view and the frustum's
// edges are taken from it; `height` is the image's, in pixels (the jitter allowance).
CameraView make_camera_view(const glm::mat4& view, const glm::mat4& projection, uint32_t width, uint32_t height);

// The frustum's extent across the image's height at view distance d: metres =
// base + per_metre * d (perspective: base 0; orthographic: per_metre 0).
struct FrustumSpan {
    float base = 0.0f;
    float per_metre = 0.0f;
};
FrustumSpan vertical_frustum_span(const CameraView& camera);

// World-space corners of the view frustum between view distances slice_near and slice_far
// (distances along the view direction). Order: near plane (4), then far plane (4).
std::array<glm::vec3, 8> frustum_slice_corners(const CameraView& camera, float slice_near, float slice_far);

}  // namespace penumbra

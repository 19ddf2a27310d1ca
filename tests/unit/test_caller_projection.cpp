// A caller's projection (ViewDesc::projection) as the cascades see it: the frustum is read
// from the matrix, whatever its form (reverse or forward Z, infinite far, off-centre,
// jittered, orthographic); its corners are the projection's own, the stable fit's sphere
// holds them, and a TAA jitter of up to kJitterPixels leaves the stable cascades in place.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/camera_math.hpp"
#include "core/cascade_fitting.hpp"
#include "core/cascades.hpp"

namespace penumbra {
namespace {

constexpr uint32_t kWidth = 1280;
constexpr uint32_t kHeight = 720;
constexpr float kFov = 1.0f;
constexpr float kAspect = static_cast<float>(kWidth) / kHeight;
constexpr float kNear = 0.1f;
constexpr float kFar = 300.0f;

glm::mat4 test_view() { return glm::lookAt(glm::vec3(3.0f, 8.0f, 12.0f), glm::vec3(0.0f), glm::vec3(0, 1, 0)); }

// Forward Z: depth 0 at the near plane, 1 at the far plane.
glm::mat4 forward_z_perspective(float fov, float aspect, float near_plane, float far_plane) {
    const float focal = 1.0f / std::tan(0.5f * fov);
    glm::mat4 m(0.0f);
    m[0][0] = focal / aspect;
    m[1][1] = -focal;
    m[2][2] = far_plane / (near_plane - far_plane);
    m[2][3] = -1.0f;
    m[3][2] = near_plane * far_plane / (near_plane - far_plane);
    return m;
}

// Reverse Z with the far plane at infinity: depth = near / distance.
glm::mat4 infinite_reverse_z(float fov, float aspect, float near_plane) {
    glm::mat4 m = perspective_reverse_z(fov, aspect, near_plane, kFar);
    m[2][2] = 0.0f;
    m[3][2] = near_plane;
    return m;
}

// `projection` moved by `pixels` across the image (a TAA jitter: a shift in NDC).
glm::mat4 jittered(glm::mat4 projection, glm::vec2 pixels) {
    const glm::vec2 ndc = 2.0f * pixels / glm::vec2(kWidth, kHeight);
    glm::mat4 shift(1.0f);
    shift[3][0] = ndc.x;
    shift[3][1] = ndc.y;
    return shift * projection;
}

void expect_corners_project_to_the_image_corners(const CameraView& camera, float distance) {
    const std::array<glm::vec3, 8> corners = frustum_slice_corners(camera, distance, distance * 2.0f);
    for (int i = 0; i < 8; ++i) {
        const glm::vec4 clip = camera.view_projection * glm::vec4(corners[i], 1.0f);
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        EXPECT_NEAR(std::abs(ndc.x), 1.0f, 1e-3f) << "corner " << i;
        EXPECT_NEAR(std::abs(ndc.y), 1.0f, 1e-3f) << "corner " << i;
        const float view_distance = -(camera.view * glm::vec4(corners[i], 1.0f)).z;
        EXPECT_NEAR(view_distance, i < 4 ? distance : 2.0f * distance, 1e-3f * distance) << "corner " << i;
    }
}

TEST(CallerProjection, PenumbrasOwnPerspectiveGivesTheSameCamera) {
    const CameraView own = make_camera_view(test_view(), kFov, kAspect, kNear, kFar);
    const CameraView caller = make_camera_view(test_view(), own.projection, kWidth, kHeight);
    EXPECT_NEAR(caller.near_plane, kNear, 1e-5f);
    EXPECT_NEAR(caller.far_plane, kFar, kFar * 1e-3f);
    EXPECT_NEAR(caller.fov_y_radians, kFov, 1e-5f);
    EXPECT_NEAR(caller.aspect, kAspect, 1e-5f);
    const std::array<glm::vec3, 8> a = frustum_slice_corners(own, 2.0f, 40.0f);
    const std::array<glm::vec3, 8> b = frustum_slice_corners(caller, 2.0f, 40.0f);
    // The same corners (in another order: the caller's follow NDC, whose Y points down).
    for (int i = 0; i < 8; ++i) {
        float nearest = std::numeric_limits<float>::infinity();
        for (const glm::vec3& corner : b) nearest = std::min(nearest, glm::distance(a[i], corner));
        EXPECT_LT(nearest, 1e-3f) << "corner " << i;
    }
    const BoundingSphere s = frustum_slice_bounding_sphere(own, 2.0f, 40.0f);
    const BoundingSphere t = frustum_slice_bounding_sphere(caller, 2.0f, 40.0f);
    // The caller's sphere is padded for the jitter allowance: a little larger, same axis.
    EXPECT_GE(t.radius, s.radius);
    EXPECT_LT(t.radius, s.radius * 1.01f);
}

TEST(CallerProjection, EveryFormGivesItsNearAndFarPlanes) {
    const CameraView forward =
        make_camera_view(test_view(), forward_z_perspective(kFov, kAspect, kNear, kFar), kWidth, kHeight);
    EXPECT_NEAR(forward.near_plane, kNear, 1e-5f);
    EXPECT_NEAR(forward.far_plane, kFar, kFar * 1e-3f);
    const CameraView infinite =
        make_camera_view(test_view(), infinite_reverse_z(kFov, kAspect, kNear), kWidth, kHeight);
    EXPECT_NEAR(infinite.near_plane, kNear, 1e-5f);
    EXPECT_EQ(infinite.far_plane, std::numeric_limits<float>::infinity());
    const CameraView ortho =
        make_camera_view(test_view(), orthographic_reverse_z(-16.0f, 16.0f, -9.0f, 9.0f, 1.0f, 80.0f), kWidth, kHeight);
    EXPECT_NEAR(ortho.near_plane, 1.0f, 1e-4f);
    EXPECT_NEAR(ortho.far_plane, 80.0f, 1e-2f);
    const FrustumSpan span = vertical_frustum_span(ortho);
    EXPECT_NEAR(span.base, 18.0f, 1e-3f);
    EXPECT_NEAR(span.per_metre, 0.0f, 1e-6f);
    // Cascades reach min(far, max_distance), also with no far plane.
    const CascadeSet set = compute_cascades(infinite, {-0.3f, -1.0f, -0.2f}, CascadeSettings{}, core::Aabb{});
    EXPECT_EQ(set.shadow_distance, CascadeSettings{}.max_distance);
}

TEST(CallerProjection, SliceCornersAreTheProjectionsOwnAndTheSphereHoldsThem) {
    glm::mat4 off_centre = perspective_reverse_z(kFov, kAspect, kNear, kFar);
    off_centre[2][0] = 0.4f;  // a frustum shifted sideways (an oblique, off-axis view)
    off_centre[2][1] = -0.25f;
    const std::vector<glm::mat4> projections = {
        perspective_reverse_z(kFov, kAspect, kNear, kFar),
        forward_z_perspective(kFov, kAspect, kNear, kFar),
        infinite_reverse_z(kFov, kAspect, kNear),
        jittered(perspective_reverse_z(kFov, kAspect, kNear, kFar), {0.5f, -0.5f}),
        off_centre,
        orthographic_reverse_z(-16.0f, 16.0f, -9.0f, 9.0f, 1.0f, 80.0f),
        orthographic_reverse_z(-4.0f, 20.0f, -2.0f, 12.0f, 1.0f, 80.0f),
    };
    for (size_t p = 0; p < projections.size(); ++p) {
        SCOPED_TRACE(p);
        const CameraView camera = make_camera_view(test_view(), projections[p], kWidth, kHeight);
        expect_corners_project_to_the_image_corners(camera, 5.0f);
        for (const auto& [from, to] : {std::pair{1.0f, 4.0f}, std::pair{4.0f, 30.0f}, std::pair{30.0f, 70.0f}}) {
            const BoundingSphere sphere = frustum_slice_bounding_sphere(camera, from, to);
            for (const glm::vec3& corner : frustum_slice_corners(camera, from, to)) {
                EXPECT_LE(glm::distance(corner, sphere.center), sphere.radius * (1.0f + 1e-5f));
            }
        }
    }
}

// TAA moves the projection by up to a pixel every frame: stable cascades must not follow it
// (each move would shift or resize the shadow-map texels under the camera and shimmer).
TEST(CallerProjection, JitterLeavesStableCascadesInPlace) {
    const glm::mat4 projection = perspective_reverse_z(kFov, kAspect, kNear, kFar);
    core::Aabb scene;
    scene.expand(glm::vec3(-60.0f, -1.0f, -60.0f));
    scene.expand(glm::vec3(60.0f, 20.0f, 60.0f));
    const glm::vec3 light{-0.3f, -1.0f, -0.2f};
    const CascadeSet still =
        compute_cascades(make_camera_view(test_view(), projection, kWidth, kHeight), light, CascadeSettings{}, scene);
    for (const glm::vec2 jitter : {glm::vec2(0.5f, 0.5f), glm::vec2(-0.5f, 0.25f), glm::vec2(1.5f, -1.75f)}) {
        const CascadeSet moved =
            compute_cascades(make_camera_view(test_view(), jittered(projection, jitter), kWidth, kHeight), light,
                             CascadeSettings{}, scene);
        ASSERT_EQ(moved.cascades.size(), still.cascades.size());
        for (size_t c = 0; c < still.cascades.size(); ++c) {
            EXPECT_EQ(moved.cascades[c].view_projection, still.cascades[c].view_projection)
                << "cascade " << c << " jitter " << jitter.x << ", " << jitter.y;
        }
    }
}

}  // namespace
}  // namespace penumbra

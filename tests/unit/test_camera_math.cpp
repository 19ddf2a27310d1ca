// Camera conventions: reverse-Z depth, Vulkan Y flip, frustum slice corners.
#include <gtest/gtest.h>

#include <cmath>

#include "core/camera_math.hpp"

namespace penumbra {
namespace {

using core::Camera;

glm::vec3 project(const glm::mat4& view_projection, const glm::vec3& world) {
    const glm::vec4 clip = view_projection * glm::vec4(world, 1.0f);
    return glm::vec3(clip) / clip.w;
}

TEST(CameraMath, PerspectiveReverseZMapsNearToOneAndFarToZero) {
    const glm::mat4 projection = perspective_reverse_z(glm::radians(60.0f), 1.5f, 0.1f, 500.0f);
    EXPECT_NEAR(project(projection, {0.0f, 0.0f, -0.1f}).z, 1.0f, 1e-6f);
    EXPECT_NEAR(project(projection, {0.0f, 0.0f, -500.0f}).z, 0.0f, 1e-6f);
    // Depth falls monotonically with distance.
    float previous = 2.0f;
    for (float distance = 0.2f; distance < 500.0f; distance *= 1.7f) {
        const float depth = project(projection, {0.0f, 0.0f, -distance}).z;
        EXPECT_LT(depth, previous) << "distance " << distance;
        previous = depth;
    }
}

TEST(CameraMath, PerspectiveFlipsYForVulkan) {
    const glm::mat4 projection = perspective_reverse_z(glm::radians(90.0f), 2.0f, 1.0f, 10.0f);
    const glm::vec3 top_right = project(projection, {4.0f, 2.0f, -2.0f});  // on the frustum's edge
    EXPECT_NEAR(top_right.x, 1.0f, 1e-6f);
    EXPECT_NEAR(top_right.y, -1.0f, 1e-6f);  // up in view space is the image's top row
}

TEST(CameraMath, OrthographicReverseZMapsBoxToClipVolume) {
    const glm::mat4 projection = orthographic_reverse_z(-3.0f, 5.0f, 1.0f, 2.0f, -4.0f, 12.0f);
    const glm::vec3 near_corner = project(projection, {-3.0f, 1.0f, 4.0f});  // view z = -near
    const glm::vec3 far_corner = project(projection, {5.0f, 2.0f, -12.0f});  // view z = -far
    EXPECT_NEAR(near_corner.x, -1.0f, 1e-6f);
    EXPECT_NEAR(near_corner.y, -1.0f, 1e-6f);
    EXPECT_NEAR(near_corner.z, 1.0f, 1e-6f);
    EXPECT_NEAR(far_corner.x, 1.0f, 1e-6f);
    EXPECT_NEAR(far_corner.y, 1.0f, 1e-6f);
    EXPECT_NEAR(far_corner.z, 0.0f, 1e-6f);
    EXPECT_FLOAT_EQ(projection[3][3], 1.0f);  // affine: no perspective divide
}

TEST(CameraMath, FrustumSliceCornersProjectToClipCorners) {
    Camera camera;
    camera.eye = {3.0f, 4.0f, 5.0f};
    camera.target = {-2.0f, 0.5f, -7.0f};
    camera.near_plane = 0.5f;
    camera.far_plane = 300.0f;
    const CameraView view = make_camera_view(camera, 16.0f / 9.0f);
    const std::array<glm::vec3, 8> corners = frustum_slice_corners(view, 0.5f, 300.0f);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 ndc = project(view.view_projection, corners[i]);
        EXPECT_NEAR(std::abs(ndc.x), 1.0f, 1e-4f) << "corner " << i;
        EXPECT_NEAR(std::abs(ndc.y), 1.0f, 1e-4f) << "corner " << i;
        EXPECT_NEAR(ndc.z, i < 4 ? 1.0f : 0.0f, 1e-4f) << "corner " << i;
    }
}

TEST(CameraMath, ForwardAgreesWithViewMatrix) {
    Camera camera;
    camera.eye = {1.0f, 2.0f, 3.0f};
    camera.target = {4.0f, -1.0f, 0.0f};
    const CameraView view = make_camera_view(camera, 1.0f);
    const glm::vec3 ahead = glm::vec3(view.view * glm::vec4(view.eye + view.forward, 1.0f));
    EXPECT_NEAR(ahead.x, 0.0f, 1e-5f);
    EXPECT_NEAR(ahead.y, 0.0f, 1e-5f);
    EXPECT_NEAR(ahead.z, -1.0f, 1e-5f);
}

TEST(CameraMath, LookingStraightDownKeepsAValidBasis) {
    for (const float vertical : {-1.0f, 1.0f}) {
        Camera camera;
        camera.eye = {0.0f, 10.0f, 0.0f};
        camera.target = {0.0f, 10.0f + 5.0f * vertical, 0.0f};
        const CameraView view = make_camera_view(camera, 1.0f);
        for (int column = 0; column < 4; ++column) {
            for (int row = 0; row < 4; ++row) EXPECT_TRUE(std::isfinite(view.view_projection[column][row]));
        }
        EXPECT_NEAR(std::abs(glm::determinant(glm::mat3(view.view))), 1.0f, 1e-5f);
    }
}

}  // namespace
}  // namespace penumbra

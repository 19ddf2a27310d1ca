// Spot and point lights in scene files (docs/scene-format.md, docs/local-lights.md):
// their keys, defaults and the one-line errors for out-of-range values.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/local_lights.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "scene_test_support.hpp"
#include "scene_to_core.hpp"

namespace penumbra {
namespace {

using namespace testing;  // the core functions over the scene's types (scene_to_core.hpp)

using ::testing::HasSubstr;
using testing::scene_error;

TEST(SceneLights, SpotLightKeys) {
    const Scene scene = testing::parse_scene_text(R"(
[[lights]]
type = "spot"
position = [4.0, 6.0, 2.0]
direction = [-0.5, -1.0, -0.2]
inner_angle = 20.0
outer_angle = 30.0
range = 25.0
radius = 0.1
color = [1.0, 0.9, 0.8]
intensity = 40.0
cast_shadows = true
shadow_resolution = 512
)");
    ASSERT_EQ(scene.lights.size(), 1u);
    const Light& spot = scene.lights[0];
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_EQ(spot.position, glm::vec3(4.0f, 6.0f, 2.0f));
    EXPECT_NEAR(glm::length(spot.direction), 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(spot.inner_angle_degrees, 20.0f);
    EXPECT_FLOAT_EQ(spot.outer_angle_degrees, 30.0f);
    EXPECT_FLOAT_EQ(spot.range, 25.0f);
    EXPECT_FLOAT_EQ(spot.radius, 0.1f);
    EXPECT_FLOAT_EQ(spot.intensity, 40.0f);
    EXPECT_EQ(spot.shadow_resolution, 512u);
    EXPECT_EQ(scene.sun(), nullptr) << "a spot light is not the sun";
}

TEST(SceneLights, PointLightKeys) {
    const Scene scene = testing::parse_scene_text(R"(
[[lights]]
type = "point"
position = [0.0, 3.0, 0.0]
range = 15.0
radius = 0.05
cast_shadows = false
)");
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].type, LightType::Point);
    EXPECT_FLOAT_EQ(scene.lights[0].range, 15.0f);
    EXPECT_FALSE(scene.lights[0].cast_shadows);
    EXPECT_EQ(scene.lights[0].shadow_resolution, 0u) << "0 = the renderer's --local-shadow-resolution";
}

TEST(SceneLights, KeysOfOtherLightTypesAreRejected) {
    EXPECT_THAT(scene_error("[[lights]]\ntype = \"point\"\nouter_angle = 30\n"),
                HasSubstr("scene.toml: lights[0].outer_angle: unknown key \"outer_angle\""));
    EXPECT_THAT(scene_error("[[lights]]\ntype = \"point\"\ndirection = [0, -1, 0]\n"),
                HasSubstr("unknown key \"direction\""));
    EXPECT_THAT(scene_error("[[lights]]\nrange = 3\n"), HasSubstr("unknown key \"range\""));
}

TEST(SceneLights, WideSpotUpTo180Degrees) {
    const Scene scene = testing::parse_scene_text(
        "[[lights]]\ntype = \"spot\"\ninner_angle = 100\nouter_angle = 179.5\nposition = [0, 3, 0]\n");
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_FLOAT_EQ(scene.lights[0].inner_angle_degrees, 100.0f);
    EXPECT_FLOAT_EQ(scene.lights[0].outer_angle_degrees, 179.5f);
}

TEST(SceneLights, OuterAngleSmallerThanInner) {
    EXPECT_EQ(scene_error("[[lights]]\ntype = \"spot\"\ninner_angle = 40\nouter_angle = 30\n"),
              "scene.toml: lights[0].inner_angle: must be between 0 and outer_angle (30) degrees, got 40");
}

TEST(SceneLights, AnglesOf180OrMore) {
    EXPECT_EQ(scene_error("[[lights]]\ntype = \"spot\"\nouter_angle = 180\n"),
              "scene.toml: lights[0].outer_angle: must be between 0 and 180 degrees (exclusive; a half-angle from "
              "the axis), got 180");
    EXPECT_THAT(scene_error("[[lights]]\ntype = \"spot\"\nouter_angle = 240\n"),
                HasSubstr("lights[0].outer_angle: must be between 0 and 180"));
    EXPECT_THAT(scene_error("[[lights]]\ntype = \"spot\"\ninner_angle = 180\nouter_angle = 170\n"),
                HasSubstr("lights[0].inner_angle: must be between 0 and outer_angle (170) degrees, got 180"));
    EXPECT_THAT(scene_error("[[lights]]\ntype = \"spot\"\ninner_angle = 200\nouter_angle = 45\n"),
                HasSubstr("lights[0].inner_angle:"));
    EXPECT_THAT(scene_error("[[lights]]\ntype = \"spot\"\nouter_angle = 0\n"), HasSubstr("lights[0].outer_angle:"));
}

TEST(SceneLights, RangeAndRadius) {
    EXPECT_EQ(scene_error("[[lights]]\ntype = \"point\"\nrange = 0\n"),
              "scene.toml: lights[0].range: must be > 0, got 0");
    EXPECT_EQ(scene_error("[[lights]]\ntype = \"spot\"\nrange = -2\n"),
              "scene.toml: lights[0].range: must be > 0, got -2");
    EXPECT_EQ(scene_error("[[lights]]\ntype = \"point\"\nradius = -0.1\n"),
              "scene.toml: lights[0].radius: must be >= 0, got -0.1");
    EXPECT_THAT(scene_error("[[lights]]\ntype = \"point\"\nshadow_resolution = 8\n"),
                HasSubstr("lights[0].shadow_resolution: must be an integer between 16 and 8192, got 8"));
}

TEST(SceneLights, ErrorNamesTheLightIndex) {
    EXPECT_THAT(scene_error("[[lights]]\n[[lights]]\ntype = \"spot\"\nrange = 0\n"),
                HasSubstr("scene.toml: lights[1].range:"));
}

// The budget: spots take one layer, points six; lights beyond it are counted.
TEST(LocalShadowPlan, BudgetAndLayers) {
    Scene scene;
    scene.lights.push_back(Light{});  // the sun: not a local light
    for (int i = 0; i < 5; ++i) {
        Light light;
        light.type = i % 2 == 0 ? LightType::Spot : LightType::Point;
        scene.lights.push_back(light);
    }
    const LocalShadowPlan plan = plan_local_shadows(scene.lights, {3, 256});
    ASSERT_EQ(plan.slots.size(), 3u);
    EXPECT_EQ(plan.slots[0].light, 1u);
    EXPECT_EQ(plan.slots[1].first_layer, 1u);
    EXPECT_EQ(plan.slots[2].first_layer, 7u);
    EXPECT_EQ(plan.layer_count, 8u);
    EXPECT_EQ(plan.unshadowed, (std::vector<uint32_t>{4, 5}));
    EXPECT_EQ(plan.atlas_resolution, 256u);
}

// Spots up to 60 degrees get one perspective layer; wider ones (up to 180) a cube of six
// faces like a point light, with 90-degree faces.
TEST(LocalShadowPlan, WideSpotsAreShadowedByACube) {
    Scene scene;
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 3.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.range = 10.0f;
    spot.outer_angle_degrees = kMaxPerspectiveSpotAngle;
    scene.lights.push_back(spot);
    spot.outer_angle_degrees = 60.5f;
    scene.lights.push_back(spot);
    spot.outer_angle_degrees = 150.0f;
    scene.lights.push_back(spot);
    EXPECT_FALSE(local_shadow_is_cube(scene.lights[0]));
    EXPECT_TRUE(local_shadow_is_cube(scene.lights[1]));
    EXPECT_TRUE(local_shadow_is_cube(scene.lights[2]));
    EXPECT_FLOAT_EQ(local_shadow_half_fov(scene.lights[0]), glm::radians(60.0f));
    EXPECT_FLOAT_EQ(local_shadow_half_fov(scene.lights[2]), glm::radians(45.0f));

    LocalShadowPlan plan = plan_local_shadows(scene.lights, {8, 256});
    fit_local_shadows(plan, scene.lights, {Aabb{{-10, -1, -10}, {10, 0, 10}}});
    ASSERT_EQ(plan.slots.size(), 3u);
    EXPECT_EQ(plan.slots[0].view_projection.size(), 1u);
    EXPECT_EQ(plan.slots[1].first_layer, 1u);
    EXPECT_EQ(plan.slots[2].first_layer, 7u);
    EXPECT_EQ(plan.layer_count, 13u);
    const auto faces = point_shadow_view_projections(spot.position, plan.slots[2].near_plane, spot.range);
    ASSERT_EQ(plan.slots[2].view_projection.size(), 6u);
    for (size_t face = 0; face < 6; ++face) EXPECT_EQ(plan.slots[2].view_projection[face], faces[face]) << face;
    // The ground 3 m below: the near plane keeps its farthest-off-axis point in the -Y face.
    EXPECT_NEAR(plan.slots[2].near_plane, 3.0f / std::sqrt(3.0f), 1e-4f);
}

// A spot pointing down: with a 120-degree cone, the +Y face (180 degrees from the axis;
// its corner rays 125.3 degrees) is dark; with 130 degrees its corners are lit.
TEST(LocalShadowMath, CubeFacesOutsideAWideConeAreDark) {
    Light spot;
    spot.type = LightType::Spot;
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.outer_angle_degrees = 120.0f;
    for (size_t face : {0u, 1u, 3u, 4u, 5u}) EXPECT_TRUE(cube_face_reaches_cone(spot, face)) << face;
    EXPECT_FALSE(cube_face_reaches_cone(spot, 2));
    spot.outer_angle_degrees = 130.0f;
    EXPECT_TRUE(cube_face_reaches_cone(spot, 2));
    // A spot along a diagonal, 70 degrees: faces +X, +Y, +Z are 54.7 degrees from its axis
    // and lit; -X, -Y, -Z are 125.3 degrees away, 70.5 past their corners: dark.
    spot.direction = glm::normalize(glm::vec3(1.0f));
    spot.outer_angle_degrees = 70.0f;
    for (size_t face : {0u, 2u, 4u}) EXPECT_TRUE(cube_face_reaches_cone(spot, face)) << face;
    for (size_t face : {1u, 3u, 5u}) EXPECT_FALSE(cube_face_reaches_cone(spot, face)) << face;
    spot.outer_angle_degrees = 71.0f;
    EXPECT_TRUE(cube_face_reaches_cone(spot, 1));
    Light point;
    point.type = LightType::Point;
    for (size_t face = 0; face < 6; ++face) EXPECT_TRUE(cube_face_reaches_cone(point, face)) << face;
}

TEST(LocalShadowMath, SpotFrustumCoversTheConeAndCulls) {
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 6.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.outer_angle_degrees = 30.0f;
    spot.range = 25.0f;
    const glm::mat4 view_projection = spot_shadow_view_projection(spot, 1.0f);
    const glm::vec4 below = view_projection * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(below.x / below.w, 0.0f, 1e-5f);
    EXPECT_GT(below.z / below.w, 0.0f);
    EXPECT_LT(below.z / below.w, 1.0f);
    // On the ground 6 m below, the cone's edge lies 6 tan(30 deg) from the axis: NDC x = +-1.
    const glm::vec4 edge = view_projection * glm::vec4(6.0f * std::tan(glm::radians(30.0f)), 0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(std::abs(edge.x / edge.w) + std::abs(edge.y / edge.w), 1.0f, 1e-4f);
    EXPECT_TRUE(caster_may_shadow_frustum(view_projection, Aabb{{-1, 0, -1}, {1, 1, 1}}));
    EXPECT_FALSE(caster_may_shadow_frustum(view_projection, Aabb{{20, 0, 20}, {21, 1, 21}})) << "outside the cone";
    EXPECT_FALSE(caster_may_shadow_frustum(view_projection, Aabb{{-1, 8, -1}, {1, 9, 1}})) << "behind the light";
    EXPECT_FALSE(caster_may_shadow_frustum(view_projection, Aabb{{-1, -30, -1}, {1, -29, 1}})) << "beyond range";
}

TEST(LocalShadowMath, CubeFacesCoverTheirAxes) {
    const auto faces = point_shadow_view_projections(glm::vec3(1.0f, 2.0f, 3.0f), 0.1f, 10.0f);
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int face = 0; face < 6; ++face) {
        const glm::vec4 clip = faces[face] * glm::vec4(glm::vec3(1.0f, 2.0f, 3.0f) + axes[face] * 5.0f, 1.0f);
        EXPECT_NEAR(clip.x / clip.w, 0.0f, 1e-5f) << face;
        EXPECT_NEAR(clip.y / clip.w, 0.0f, 1e-5f) << face;
        EXPECT_GT(clip.w, 0.0f) << face;
    }
    EXPECT_TRUE(caster_may_shadow_sphere(glm::vec3(0.0f), 2.0f, Aabb{{1, 1, 1}, {3, 3, 3}}));
    EXPECT_FALSE(caster_may_shadow_sphere(glm::vec3(0.0f), 1.0f, Aabb{{1, 1, 1}, {3, 3, 3}}));
}

TEST(LocalShadowMath, NearPlaneFromTheNearestCaster) {
    const std::vector<Aabb> boxes{Aabb{{-1, 0, -1}, {1, 2, 1}}, Aabb{{-10, -1, -10}, {10, 0, 10}}};
    EXPECT_FLOAT_EQ(nearest_caster_distance(glm::vec3(0.0f, 6.0f, 0.0f), boxes, 25.0f), 4.0f);
    EXPECT_FLOAT_EQ(nearest_caster_distance(glm::vec3(0.0f, 1.0f, 0.0f), boxes, 25.0f), kMinLocalShadowNear)
        << "inside a caster's bounds";
}

// --- Coverage sizing: a light's map follows its size on the screen. ---

CameraView camera_at(const glm::vec3& eye, const glm::vec3& target) {
    return make_camera_view(Camera{eye, target, {0.0f, 1.0f, 0.0f}, 60.0f, 0.1f, 500.0f}, 16.0f / 9.0f);
}

Light point_light(const glm::vec3& position, float range) {
    Light light;
    light.type = LightType::Point;
    light.position = position;
    light.range = range;
    return light;
}

TEST(LocalShadowSizing, SpotBoundsHoldTheApexAndTheRim) {
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {1.0f, 5.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.outer_angle_degrees = 30.0f;
    spot.range = 10.0f;
    const Sphere bounds = local_light_bounds(spot);
    const float expected = 10.0f / (2.0f * std::cos(glm::radians(30.0f)));
    EXPECT_NEAR(bounds.radius, expected, 1e-4f);
    EXPECT_NEAR(glm::length(bounds.center - spot.position), bounds.radius, 1e-4f) << "the apex is on the sphere";
    const glm::vec3 rim =
        spot.position + 10.0f * glm::vec3(std::sin(glm::radians(30.0f)), -std::cos(glm::radians(30.0f)), 0.0f);
    EXPECT_NEAR(glm::length(bounds.center - rim), bounds.radius, 1e-4f) << "the rim is on the sphere";
    EXPECT_LE(glm::length(bounds.center - (spot.position + glm::vec3(0, -10, 0))), bounds.radius + 1e-4f)
        << "the cap's tip is inside";
    spot.outer_angle_degrees = 75.0f;
    EXPECT_FLOAT_EQ(local_light_bounds(spot).radius, 10.0f) << "wide cones: the range sphere is smaller";
    EXPECT_FLOAT_EQ(local_light_bounds(point_light({0, 0, 0}, 7.0f)).radius, 7.0f);
}

TEST(LocalShadowSizing, ResolutionHalvesWhenTheDistanceDoubles) {
    const Light light = point_light({0.0f, 0.0f, 0.0f}, 1.0f);
    // 1 m radius seen from 20 m with a 60-degree fov on 1080 rows: 2 * 540 / tan(30) * tan(asin(1/20)) = 93.6 px
    // across, 46.8 per cube face -> 64.
    const uint32_t near = coverage_shadow_resolution(light, camera_at({0, 0, 5}, {0, 0, 0}), 1080, 4096);
    const uint32_t mid = coverage_shadow_resolution(light, camera_at({0, 0, 10}, {0, 0, 0}), 1080, 4096);
    const uint32_t far = coverage_shadow_resolution(light, camera_at({0, 0, 20}, {0, 0, 0}), 1080, 4096);
    EXPECT_EQ(near, 256u);  // 383 px across at 5 m, 192 per face
    EXPECT_EQ(mid, 128u);
    EXPECT_EQ(far, 64u);
    EXPECT_EQ(coverage_shadow_resolution(light, camera_at({0, 0, 5}, {0, 0, 0}), 2160, 4096), 2 * near)
        << "twice the pixels, twice the texels";
}

TEST(LocalShadowSizing, ClampsInsideBehindAndAtTheCap) {
    const Light light = point_light({0.0f, 0.0f, 0.0f}, 3.0f);
    EXPECT_EQ(coverage_shadow_resolution(light, camera_at({0, 0, 1}, {0, 0, -5}), 1080, 1024), 1024u)
        << "the camera inside the light's reach";
    EXPECT_EQ(coverage_shadow_resolution(light, camera_at({0, 0, 20}, {0, 0, 40}), 1080, 1024),
              kMinCoverageShadowResolution)
        << "behind the camera";
    EXPECT_EQ(coverage_shadow_resolution(light, camera_at({0, 0, 3.5f}, {0, 0, 0}), 1080, 512), 512u) << "the cap";
    EXPECT_EQ(coverage_shadow_resolution(light, camera_at({0, 0, 20}, {0, 0, 40}), 1080, 32), 32u)
        << "a cap below the minimum wins";
}

TEST(LocalShadowSizing, FixedLightsKeepTheirResolution) {
    Scene scene;
    scene.lights.push_back(point_light({0.0f, 0.0f, 0.0f}, 1.0f));
    scene.lights.push_back(point_light({0.0f, 0.0f, 0.0f}, 1.0f));
    scene.lights[1].shadow_resolution = 512;
    LocalShadowPlan plan = plan_local_shadows(scene.lights, {8, 2048, LocalShadowSizing::Coverage});
    EXPECT_EQ(plan.atlas_resolution, 2048u);
    size_local_shadows(plan, scene.lights, camera_at({0, 0, 20}, {0, 0, 0}), 1080, 2048);
    EXPECT_EQ(plan.slots[0].resolution, 64u);
    EXPECT_EQ(plan.slots[1].resolution, 512u) << "the light's own shadow_resolution";
    LocalShadowPlan fixed = plan_local_shadows(scene.lights, {8, 2048, LocalShadowSizing::Fixed});
    size_local_shadows(fixed, scene.lights, camera_at({0, 0, 20}, {0, 0, 0}), 1080, 2048);
    EXPECT_EQ(fixed.slots[0].resolution, 2048u);
}

// Views sharing the maps: each light gets the largest resolution any view asks of it, and
// a view that sees nothing of it lowers nothing.
TEST(LocalShadowSizing, SharedMapsServeTheViewThatNeedsThemLargest) {
    Scene scene;
    scene.lights.push_back(point_light({0.0f, 0.0f, 0.0f}, 1.0f));
    scene.lights.push_back(point_light({30.0f, 0.0f, 0.0f}, 1.0f));
    const CameraView near_first = camera_at({0, 0, 5}, {0, 0, 0});
    const CameraView near_second = camera_at({30, 0, 5}, {30, 0, 0});
    LocalShadowPlan alone[2] = {plan_local_shadows(scene.lights, {8, 4096, LocalShadowSizing::Coverage}),
                                plan_local_shadows(scene.lights, {8, 4096, LocalShadowSizing::Coverage})};
    size_local_shadows(alone[0], scene.lights, near_first, 1080, 4096);
    size_local_shadows(alone[1], scene.lights, near_second, 1080, 4096);
    ASSERT_GT(alone[0].slots[0].resolution, alone[1].slots[0].resolution) << "each camera is near one light";
    ASSERT_LT(alone[0].slots[1].resolution, alone[1].slots[1].resolution);
    LocalShadowPlan shared = plan_local_shadows(scene.lights, {8, 4096, LocalShadowSizing::Coverage});
    const penumbra::SizedCamera views[2] = {{near_first, 1080}, {near_second, 1080}};
    penumbra::size_local_shadows(shared, to_core(scene.lights), views, 4096);
    EXPECT_EQ(shared.slots[0].resolution, alone[0].slots[0].resolution);
    EXPECT_EQ(shared.slots[1].resolution, alone[1].slots[1].resolution);
}

// A caster off a cube face's axis, near the corner of the -Y face: its nearest point is
// 2.0 m from the light but only 1.2 m deep along the face's axis. The near plane must not
// clip it (it did when the near plane was the nearest caster's distance itself).
TEST(LocalShadowMath, NearPlaneKeepsCastersOffTheAxis) {
    Scene scene;
    scene.lights.push_back(point_light({0.0f, 0.0f, 0.0f}, 10.0f));
    const Aabb box{{1.1f, -1.3f, 1.1f}, {1.3f, -1.2f, 1.3f}};
    LocalShadowPlan plan = plan_local_shadows(scene.lights, {});
    fit_local_shadows(plan, scene.lights, {box});
    ASSERT_EQ(plan.slots.size(), 1u);
    const float nearest = glm::length(glm::vec3(1.1f, -1.2f, 1.1f));
    EXPECT_NEAR(plan.slots[0].near_plane, nearest / std::sqrt(3.0f), 1e-4f);
    const glm::vec4 clip = plan.slots[0].view_projection[3] * glm::vec4(1.1f, -1.2f, 1.1f, 1.0f);  // face -Y
    EXPECT_GT(clip.w, 0.0f);
    EXPECT_LE(clip.z / clip.w, 1.0f) << "the caster's nearest corner is behind the near plane";
    EXPECT_LE(std::abs(clip.x / clip.w), 1.0f);
    EXPECT_LE(std::abs(clip.y / clip.w), 1.0f);
    // A spot: the corner ray of a 30-degree cone is at atan(sqrt(2) tan 30) = 39.2 degrees.
    Light spot;
    spot.type = LightType::Spot;
    spot.outer_angle_degrees = 30.0f;
    const float corner = std::atan(std::sqrt(2.0f) * std::tan(glm::radians(30.0f)));
    EXPECT_NEAR(local_shadow_near_plane(spot, 4.0f), 4.0f * std::cos(corner), 1e-4f);
    EXPECT_FLOAT_EQ(local_shadow_near_plane(spot, 0.01f), kMinLocalShadowNear);
}

}  // namespace
}  // namespace penumbra

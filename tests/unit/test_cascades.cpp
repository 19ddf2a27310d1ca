// Properties of cascade splitting, fitting and caster culling, checked over many random
// cameras and light directions (seeded, so failures reproduce).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/cascade_fitting.hpp"
#include "core/cascades.hpp"
#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

using core::Aabb;
using core::Camera;

constexpr int kRandomCases = 500;

glm::vec3 project(const glm::mat4& view_projection, const glm::vec3& world) {
    const glm::vec4 clip = view_projection * glm::vec4(world, 1.0f);
    return glm::vec3(clip) / clip.w;
}

bool is_finite(const glm::mat4& m) {
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            if (!std::isfinite(m[column][row])) return false;
        }
    }
    return true;
}

float uniform(std::mt19937& rng, float low, float high) {
    return std::uniform_real_distribution<float>(low, high)(rng);
}

glm::vec3 random_unit_vector(std::mt19937& rng) {
    std::normal_distribution<float> normal(0.0f, 1.0f);
    for (;;) {
        const glm::vec3 v(normal(rng), normal(rng), normal(rng));
        if (glm::length(v) > 1e-3f) return glm::normalize(v);
    }
}

// A random light direction; one in eight is the sun straight down, one straight up.
glm::vec3 random_light_direction(std::mt19937& rng) {
    const int pick = std::uniform_int_distribution<int>(0, 7)(rng);
    if (pick == 0) return {0.0f, -1.0f, 0.0f};
    if (pick == 1) return {0.0f, 1.0f, 0.0f};
    return random_unit_vector(rng);
}

struct RandomSetup {
    Camera camera;
    float aspect = 1.0f;
    glm::vec3 light_direction{0.0f, -1.0f, 0.0f};
    CascadeSettings settings;
    Aabb scene_bounds;
};

RandomSetup random_setup(std::mt19937& rng, int case_index) {
    RandomSetup setup;
    setup.camera.eye = {uniform(rng, -50.0f, 50.0f), uniform(rng, 0.5f, 40.0f), uniform(rng, -50.0f, 50.0f)};
    setup.camera.target = setup.camera.eye + random_unit_vector(rng) * uniform(rng, 1.0f, 30.0f);
    setup.camera.fov_y_degrees = uniform(rng, 20.0f, 100.0f);
    setup.camera.near_plane = uniform(rng, 0.05f, 2.0f);
    setup.camera.far_plane = setup.camera.near_plane * uniform(rng, 20.0f, 2000.0f);
    setup.aspect = uniform(rng, 0.5f, 2.5f);
    setup.light_direction = random_light_direction(rng);
    setup.settings.count = 1 + case_index % kMaxCascades;
    setup.settings.split_lambda = uniform(rng, 0.0f, 1.0f);
    setup.settings.max_distance = uniform(rng, 20.0f, 300.0f);
    setup.settings.resolution = 512u << (case_index % 5);  // 512 .. 8192
    setup.settings.filter_padding_texels = uniform(rng, 0.0f, 16.0f);
    if (case_index % 5 != 0) {  // every fifth scene is empty
        const float half = uniform(rng, 20.0f, 400.0f);
        setup.scene_bounds.expand(glm::vec3(-half, -uniform(rng, 0.0f, 10.0f), -half));
        setup.scene_bounds.expand(glm::vec3(half, uniform(rng, 1.0f, 60.0f), half));
    }
    return setup;
}

CascadeSet cascades_for(const RandomSetup& setup) {
    return compute_cascades(make_camera_view(setup.camera, setup.aspect), setup.light_direction, setup.settings,
                            setup.scene_bounds);
}

// ---- Split distances ---------------------------------------------------------------

TEST(CascadeSplits, StrictlyIncreaseAndCoverTheRangeForEveryScheme) {
    std::mt19937 rng(1234);
    for (int i = 0; i < kRandomCases; ++i) {
        const float near_plane = uniform(rng, 0.01f, 5.0f);
        const float far_plane = near_plane * uniform(rng, 2.0f, 10000.0f);
        const int count = 1 + i % kMaxCascades;
        for (const SplitScheme scheme : {SplitScheme::Uniform, SplitScheme::Logarithmic, SplitScheme::Practical}) {
            const std::vector<float> splits =
                compute_split_distances(near_plane, far_plane, count, scheme, uniform(rng, 0.0f, 1.0f));
            ASSERT_EQ(splits.size(), static_cast<size_t>(count + 1));
            EXPECT_EQ(splits.front(), near_plane);
            EXPECT_EQ(splits.back(), far_plane);
            for (int s = 1; s <= count; ++s) {
                EXPECT_LT(splits[s - 1], splits[s]) << "case " << i << " split " << s;
            }
        }
    }
}

TEST(CascadeSplits, LambdaZeroIsUniformAndLambdaOneIsLogarithmic) {
    std::mt19937 rng(99);
    for (int i = 0; i < kRandomCases; ++i) {
        const float n = uniform(rng, 0.01f, 5.0f);
        const float f = n * uniform(rng, 2.0f, 10000.0f);
        const int count = 1 + i % kMaxCascades;
        const std::vector<float> practical0 = compute_split_distances(n, f, count, SplitScheme::Practical, 0.0f);
        const std::vector<float> practical1 = compute_split_distances(n, f, count, SplitScheme::Practical, 1.0f);
        const std::vector<float> uniform_splits = compute_split_distances(n, f, count, SplitScheme::Uniform, 0.5f);
        const std::vector<float> log_splits = compute_split_distances(n, f, count, SplitScheme::Logarithmic, 0.5f);
        for (int s = 0; s <= count; ++s) {
            const float t = static_cast<float>(s) / count;
            const float uniform_formula = n + (f - n) * t;
            const float log_formula = n * std::pow(f / n, t);
            const float eps = 4.0f * std::numeric_limits<float>::epsilon();
            EXPECT_EQ(practical0[s], uniform_splits[s]);
            EXPECT_EQ(practical1[s], log_splits[s]);
            EXPECT_NEAR(practical0[s], uniform_formula, eps * uniform_formula);
            EXPECT_NEAR(practical1[s], log_formula, eps * log_formula);
        }
    }
}

TEST(CascadeSplits, PracticalLiesBetweenLogarithmicAndUniform) {
    const std::vector<float> uniform_splits = compute_split_distances(0.1f, 200.0f, 4, SplitScheme::Uniform, 0.0f);
    const std::vector<float> log_splits = compute_split_distances(0.1f, 200.0f, 4, SplitScheme::Logarithmic, 0.0f);
    const std::vector<float> practical = compute_split_distances(0.1f, 200.0f, 4, SplitScheme::Practical, 0.75f);
    for (int s = 1; s < 4; ++s) {
        EXPECT_GT(practical[s], log_splits[s]);
        EXPECT_LT(practical[s], uniform_splits[s]);
        EXPECT_NEAR(practical[s], 0.75f * log_splits[s] + 0.25f * uniform_splits[s], 1e-4f * practical[s]);
    }
}

TEST(CascadeSplits, ManualSplitsAreUsedVerbatim) {
    const std::vector<float> manual = {2.5f, 7.125f, 31.0f};
    const std::vector<float> splits = compute_split_distances(0.3f, 120.0f, 4, SplitScheme::Manual, 0.75f, manual);
    EXPECT_EQ(splits, (std::vector<float>{0.3f, 2.5f, 7.125f, 31.0f, 120.0f}));
    EXPECT_EQ(compute_split_distances(0.3f, 120.0f, 1, SplitScheme::Manual, 0.75f, {}),
              (std::vector<float>{0.3f, 120.0f}));
}

TEST(CascadeSplits, ManualSplitsOutsideTheShadowDistanceAreInputErrors) {
    EXPECT_THROW(compute_split_distances(0.3f, 20.0f, 3, SplitScheme::Manual, 0.75f, {5.0f, 25.0f}), InputError);
    EXPECT_THROW(compute_split_distances(0.3f, 20.0f, 3, SplitScheme::Manual, 0.75f, {0.2f, 5.0f}), InputError);
    EXPECT_THROW(compute_split_distances(0.3f, 20.0f, 3, SplitScheme::Manual, 0.75f, {5.0f, 5.0f}), InputError);
    EXPECT_THROW(compute_split_distances(0.3f, 20.0f, 3, SplitScheme::Manual, 0.75f, {5.0f}), InputError);
}

TEST(CascadeSplits, CascadeSetCoversNearToShadowDistance) {
    std::mt19937 rng(7);
    for (int i = 0; i < kRandomCases; ++i) {
        const RandomSetup setup = random_setup(rng, i);
        const CascadeSet set = cascades_for(setup);
        ASSERT_EQ(set.cascades.size(), static_cast<size_t>(setup.settings.count));
        EXPECT_EQ(set.shadow_distance, std::min(setup.camera.far_plane, setup.settings.max_distance));
        EXPECT_EQ(set.cascades.front().split_near, setup.camera.near_plane);
        EXPECT_EQ(set.cascades.back().split_far, set.shadow_distance);
        for (size_t c = 0; c < set.cascades.size(); ++c) {
            EXPECT_LT(set.cascades[c].split_near, set.cascades[c].split_far);
            if (c > 0) {
                EXPECT_EQ(set.cascades[c].split_near, set.cascades[c - 1].split_far);
            }
        }
    }
}

TEST(CascadeSplits, MaxDistanceInsideTheNearPlaneIsAnInputError) {
    Camera camera;
    camera.near_plane = 1.0f;
    CascadeSettings settings;
    settings.max_distance = 0.5f;
    EXPECT_THROW(compute_cascades(make_camera_view(camera, 1.0f), {0.0f, -1.0f, 0.0f}, settings, Aabb{}), InputError);
}

// ---- Light view basis ----------------------------------------------------------------

TEST(LightView, IsARotationLookingAlongTheLightForEveryDirection) {
    std::mt19937 rng(42);
    std::vector<glm::vec3> directions = {
        {0.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {1e-4f, -1.0f, 0.0f}, {0.0f, -3.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
    for (int i = 0; i < kRandomCases; ++i) directions.push_back(random_unit_vector(rng) * uniform(rng, 0.1f, 10.0f));
    for (const glm::vec3& direction : directions) {
        const glm::mat4 view = light_view_matrix(direction);
        ASSERT_TRUE(is_finite(view));
        const glm::mat3 rotation(view);
        const glm::mat3 should_be_identity = glm::transpose(rotation) * rotation;
        for (int column = 0; column < 3; ++column) {
            for (int row = 0; row < 3; ++row) {
                EXPECT_NEAR(should_be_identity[column][row], column == row ? 1.0f : 0.0f, 1e-5f);
            }
        }
        EXPECT_NEAR(glm::determinant(rotation), 1.0f, 1e-5f);
        const glm::vec3 light_axis = rotation * glm::normalize(direction);
        EXPECT_NEAR(light_axis.z, -1.0f, 1e-5f);  // the light looks down -Z
    }
}

// ---- Fitting -------------------------------------------------------------------------

// Every slice corner is inside its cascade's window (and its depth range when there is no
// scene to take the range from).
TEST(CascadeFitting, EverySliceCornerIsInsideItsCascadeForBothFitModes) {
    constexpr float kEpsilon = 1e-4f;
    for (const FitMode fit : {FitMode::Stable, FitMode::Tight}) {
        std::mt19937 rng(2024);
        for (int i = 0; i < kRandomCases; ++i) {
            RandomSetup setup = random_setup(rng, i);
            setup.settings.fit = fit;
            const CameraView camera = make_camera_view(setup.camera, setup.aspect);
            const CascadeSet set = compute_cascades(camera, setup.light_direction, setup.settings, setup.scene_bounds);
            for (size_t c = 0; c < set.cascades.size(); ++c) {
                const Cascade& cascade = set.cascades[c];
                ASSERT_TRUE(is_finite(cascade.view_projection)) << "case " << i;
                for (const glm::vec3& corner : frustum_slice_corners(camera, cascade.split_near, cascade.split_far)) {
                    const glm::vec3 ndc = project(cascade.view_projection, corner);
                    EXPECT_LE(std::abs(ndc.x), 1.0f + kEpsilon) << "case " << i << " cascade " << c;
                    EXPECT_LE(std::abs(ndc.y), 1.0f + kEpsilon) << "case " << i << " cascade " << c;
                    // The depth range is the scene's (SceneBoundsAreInsideTheDepthRange):
                    // empty space of the slice beyond it holds nothing to render or shade.
                    if (!setup.scene_bounds.empty()) continue;
                    EXPECT_GE(ndc.z, -kEpsilon) << "case " << i << " cascade " << c;
                    EXPECT_LE(ndc.z, 1.0f + kEpsilon) << "case " << i << " cascade " << c;
                }
            }
        }
    }
}

TEST(CascadeFitting, SceneBoundsAreInsideTheDepthRange) {
    std::mt19937 rng(5);
    for (int i = 0; i < kRandomCases; ++i) {
        RandomSetup setup = random_setup(rng, i);
        if (setup.scene_bounds.empty()) continue;
        setup.settings.fit = i % 2 ? FitMode::Stable : FitMode::Tight;
        const CascadeSet set = cascades_for(setup);
        for (const Cascade& cascade : set.cascades) {
            for (const glm::vec3& corner : setup.scene_bounds.corners()) {
                const float depth = project(cascade.view_projection, corner).z;
                EXPECT_GE(depth, -1e-4f) << "case " << i;
                EXPECT_LE(depth, 1.0f + 1e-4f) << "case " << i;
            }
        }
    }
}

TEST(CascadeFitting, StableSubTexelTranslationMovesTheOriginByWholeTexels) {
    std::mt19937 rng(77);
    for (int i = 0; i < kRandomCases; ++i) {
        RandomSetup setup = random_setup(rng, i);
        setup.settings.fit = FitMode::Stable;
        // Up to 4096 texels the snapped origin (a whole number of texels of a dyadic size)
        // and the projection's translation -2k / resolution are exact floats for these
        // scene sizes; at 8192 texels a cascade 200 m out holds more than 24 bits of
        // texel index and float rounding alone reaches ~0.01 texel.
        setup.settings.resolution = 512u << (i % 4);
        const CascadeSet before = cascades_for(setup);
        const float texel = before.cascades.front().texel_world_size;
        const glm::vec3 step = random_unit_vector(rng) * uniform(rng, 0.05f, 0.95f) * texel;
        setup.camera.eye += step;
        setup.camera.target += step;
        const CascadeSet after = cascades_for(setup);
        for (size_t c = 0; c < before.cascades.size(); ++c) {
            const glm::mat4& p0 = before.cascades[c].projection;
            const glm::mat4& p1 = after.cascades[c].projection;
            ASSERT_EQ(p0[0][0], p1[0][0]) << "case " << i;  // same footprint size
            const float ndc_texel = 2.0f / static_cast<float>(setup.settings.resolution);
            for (int axis = 0; axis < 2; ++axis) {
                const float moved_texels = (p1[3][axis] - p0[3][axis]) / ndc_texel;
                EXPECT_NEAR(moved_texels, std::round(moved_texels), 1e-3f) << "case " << i << " axis " << axis;
            }
        }
    }
}

TEST(CascadeFitting, StableExtentIsUnchangedByCameraRotation) {
    std::mt19937 rng(314);
    for (int i = 0; i < kRandomCases; ++i) {
        RandomSetup setup = random_setup(rng, i);
        setup.settings.fit = FitMode::Stable;
        const CascadeSet before = cascades_for(setup);
        const glm::mat4 rotation = glm::rotate(glm::mat4(1.0f), uniform(rng, -3.14f, 3.14f), random_unit_vector(rng));
        setup.camera.target =
            setup.camera.eye + glm::vec3(rotation * glm::vec4(setup.camera.target - setup.camera.eye, 0.0f));
        const CascadeSet after = cascades_for(setup);
        for (size_t c = 0; c < before.cascades.size(); ++c) {
            EXPECT_EQ(before.cascades[c].light_extent.x, after.cascades[c].light_extent.x) << "case " << i;
            EXPECT_EQ(before.cascades[c].light_extent.y, after.cascades[c].light_extent.y) << "case " << i;
            EXPECT_EQ(before.cascades[c].texel_world_size, after.cascades[c].texel_world_size) << "case " << i;
        }
    }
}

TEST(CascadeFitting, StableExtentIsASquareOfSixteenthsWithMatchingTexelSize) {
    std::mt19937 rng(8);
    for (int i = 0; i < kRandomCases; ++i) {
        RandomSetup setup = random_setup(rng, i);
        setup.settings.fit = FitMode::Stable;
        for (const Cascade& cascade : cascades_for(setup).cascades) {
            EXPECT_EQ(cascade.light_extent.x, cascade.light_extent.y);
            const float diameter_in_sixteenths = cascade.light_extent.x * 16.0f;
            EXPECT_EQ(diameter_in_sixteenths, std::round(diameter_in_sixteenths));
            EXPECT_FLOAT_EQ(cascade.texel_world_size,
                            cascade.light_extent.x / static_cast<float>(setup.settings.resolution));
        }
    }
}

TEST(CascadeFitting, TightTexelSizeIsConsistentAndPaddingIsKept) {
    std::mt19937 rng(11);
    for (int i = 0; i < kRandomCases; ++i) {
        RandomSetup setup = random_setup(rng, i);
        setup.settings.fit = FitMode::Tight;
        const CameraView camera = make_camera_view(setup.camera, setup.aspect);
        const CascadeSet set = compute_cascades(camera, setup.light_direction, setup.settings, setup.scene_bounds);
        const float resolution = static_cast<float>(setup.settings.resolution);
        // The corners keep padding_texels texels from every edge (minus float noise).
        const float inner_limit = 1.0f - 2.0f * setup.settings.filter_padding_texels / resolution + 1e-4f;
        for (const Cascade& cascade : set.cascades) {
            EXPECT_FLOAT_EQ(cascade.texel_world_size,
                            std::max(cascade.light_extent.x, cascade.light_extent.y) / resolution);
            for (const glm::vec3& corner : frustum_slice_corners(camera, cascade.split_near, cascade.split_far)) {
                const glm::vec3 ndc = project(cascade.view_projection, corner);
                EXPECT_LE(std::abs(ndc.x), inner_limit) << "case " << i;
                EXPECT_LE(std::abs(ndc.y), inner_limit) << "case " << i;
            }
        }
    }
}

TEST(CascadeFitting, TightIsNoWiderThanTheSliceBoundsPlusPaddingAndSlack) {
    const std::array<glm::vec3, 8> points = {glm::vec3(-2, -1, -3), glm::vec3(6, 3, -10), glm::vec3(0, 0, -5),
                                             glm::vec3(1, 1, -4),   glm::vec3(1, 2, -4),  glm::vec3(2, 1, -4),
                                             glm::vec3(0, 1, -4),   glm::vec3(1, 0, -4)};
    const LightOrthoBox box = fit_tight_box(points, 1024, 8.0f);
    const glm::vec3 extent = box.extent();
    EXPECT_NEAR(extent.x, 8.0f * 1024.0f / (1024.0f - 17.0f), 1e-4f);
    EXPECT_NEAR(extent.y, 4.0f * 1024.0f / (1024.0f - 17.0f), 1e-4f);
    EXPECT_FLOAT_EQ(box.near_distance, 3.0f);
    EXPECT_FLOAT_EQ(box.far_distance, 10.0f);
}

TEST(CascadeFitting, SliceSphereIsTheSmallestOnTheAxisAndHoldsTheCorners) {
    std::mt19937 rng(3);
    for (int i = 0; i < kRandomCases; ++i) {
        const RandomSetup setup = random_setup(rng, i);
        const CameraView camera = make_camera_view(setup.camera, setup.aspect);
        const float n = setup.camera.near_plane * uniform(rng, 1.0f, 10.0f);
        const float f = n * uniform(rng, 1.01f, 50.0f);
        const BoundingSphere sphere = frustum_slice_bounding_sphere(camera, n, f);
        float farthest = 0.0f;
        for (const glm::vec3& corner : frustum_slice_corners(camera, n, f)) {
            farthest = std::max(farthest, glm::distance(corner, sphere.center));
        }
        // Holds every corner, and touches at least one (it is the minimal sphere on the axis).
        // (The tolerance allows for float noise in world coordinates tens of metres out.)
        EXPECT_LE(farthest, sphere.radius * (1.0f + 1e-5f) + 1e-4f) << "case " << i;
        EXPECT_GE(farthest, sphere.radius * (1.0f - 1e-4f)) << "case " << i;
    }
}

TEST(CascadeFitting, EmptySceneBoundsUseTheSliceAlone) {
    Camera camera;
    CascadeSettings settings;
    const CascadeSet set = compute_cascades(make_camera_view(camera, 1.5f), {0.3f, -1.0f, 0.2f}, settings, Aabb{});
    for (const Cascade& cascade : set.cascades) {
        EXPECT_FLOAT_EQ(cascade.light_extent.z, cascade.light_extent.x);  // the sphere's diameter
    }
}

TEST(CascadeFitting, LightStraightDownOrUpGivesFiniteCascades) {
    for (const glm::vec3 direction : {glm::vec3(0, -1, 0), glm::vec3(0, 1, 0), glm::vec3(1e-6f, -1, 0)}) {
        for (const FitMode fit : {FitMode::Stable, FitMode::Tight}) {
            Camera camera;
            CascadeSettings settings;
            settings.fit = fit;
            Aabb scene;
            scene.expand(glm::vec3(-100, 0, -100));
            scene.expand(glm::vec3(100, 20, 100));
            const CameraView view = make_camera_view(camera, 1.0f);
            const CascadeSet set = compute_cascades(view, direction, settings, scene);
            for (const Cascade& cascade : set.cascades) {
                ASSERT_TRUE(is_finite(cascade.view_projection));
                EXPECT_GT(cascade.texel_world_size, 0.0f);
                for (const glm::vec3& corner : frustum_slice_corners(view, cascade.split_near, cascade.split_far)) {
                    const glm::vec3 ndc = project(cascade.view_projection, corner);
                    EXPECT_LE(std::abs(ndc.x), 1.0f + 1e-4f);
                    EXPECT_LE(std::abs(ndc.y), 1.0f + 1e-4f);
                }
                for (const glm::vec3& corner : scene.corners()) {  // the depth range is the scene's
                    const float depth = project(cascade.view_projection, corner).z;
                    EXPECT_GE(depth, -1e-4f);
                    EXPECT_LE(depth, 1.0f + 1e-4f);
                }
            }
        }
    }
}

TEST(CascadeFitting, ReverseZPointsNearerTheLightHaveLargerDepth) {
    std::mt19937 rng(21);
    for (int i = 0; i < kRandomCases; ++i) {
        const RandomSetup setup = random_setup(rng, i);
        const CascadeSet set = cascades_for(setup);
        const glm::vec3 point = setup.camera.target;
        const glm::vec3 nearer_the_light = point - set.light_direction * 0.5f;
        for (const Cascade& cascade : set.cascades) {
            EXPECT_GT(project(cascade.view_projection, nearer_the_light).z, project(cascade.view_projection, point).z);
        }
    }
}

// ---- Caster culling ------------------------------------------------------------------

struct CullingFixture {
    CameraView camera;
    CascadeSet set;
    glm::vec3 slice_center{0.0f};
    glm::vec3 sideways{0.0f};  // perpendicular to the light

    CullingFixture() {
        Camera description;
        description.eye = {0.0f, 10.0f, 20.0f};
        description.target = {0.0f, 0.0f, 0.0f};
        camera = make_camera_view(description, 16.0f / 9.0f);
        Aabb scene;
        scene.expand(glm::vec3(-50.0f, -1.0f, -50.0f));
        scene.expand(glm::vec3(50.0f, 30.0f, 50.0f));
        set = compute_cascades(camera, {-0.3f, -1.0f, -0.2f}, CascadeSettings{}, scene);
        for (const glm::vec3& corner :
             frustum_slice_corners(camera, set.cascades[0].split_near, set.cascades[0].split_far)) {
            slice_center += corner / 8.0f;
        }
        sideways = glm::normalize(glm::cross(set.light_direction, glm::vec3(1.0f, 0.0f, 0.0f)));
    }

    static Aabb box_around(const glm::vec3& center, float half_size) {
        Aabb box;
        box.expand(center - glm::vec3(half_size));
        box.expand(center + glm::vec3(half_size));
        return box;
    }
};

TEST(CasterCulling, BoxBetweenTheSunAndTheCascadePassesEvenOutsideTheCameraFrustum) {
    const CullingFixture fixture;
    const glm::vec3 center = fixture.slice_center - fixture.set.light_direction * 200.0f;
    const glm::vec4 clip = fixture.camera.view_projection * glm::vec4(center, 1.0f);
    ASSERT_TRUE(std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w) << "the box must be off screen";
    EXPECT_TRUE(caster_may_shadow_cascade(fixture.set.cascades[0], CullingFixture::box_around(center, 0.5f)));
}

TEST(CasterCulling, BoxInsideTheSliceAndBoxStraddlingTheEdgePass) {
    const CullingFixture fixture;
    const Cascade& cascade = fixture.set.cascades[0];
    EXPECT_TRUE(caster_may_shadow_cascade(cascade, CullingFixture::box_around(fixture.slice_center, 0.1f)));
    const float half_width = 0.5f * cascade.light_extent.x;
    const glm::vec3 on_edge = fixture.slice_center + fixture.sideways * (half_width * 1.5f);
    EXPECT_TRUE(caster_may_shadow_cascade(cascade, CullingFixture::box_around(on_edge, half_width)));
}

TEST(CasterCulling, BoxFarOffToTheSideFails) {
    const CullingFixture fixture;
    const glm::vec3 center = fixture.slice_center + fixture.sideways * 1000.0f;
    EXPECT_FALSE(caster_may_shadow_cascade(fixture.set.cascades[0], CullingFixture::box_around(center, 1.0f)));
}

TEST(CasterCulling, BoxBeyondTheReceiversFails) {
    const CullingFixture fixture;
    const glm::vec3 center = fixture.slice_center + fixture.set.light_direction * 1000.0f;
    EXPECT_FALSE(caster_may_shadow_cascade(fixture.set.cascades[0], CullingFixture::box_around(center, 1.0f)));
}

TEST(CasterCulling, EmptyBoxFails) {
    const CullingFixture fixture;
    EXPECT_FALSE(caster_may_shadow_cascade(fixture.set.cascades[0], Aabb{}));
}

}  // namespace
}  // namespace penumbra

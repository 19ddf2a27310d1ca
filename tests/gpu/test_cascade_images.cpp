// Image properties of the cascaded shadow map: the cascade index grows with distance,
// both rendering strategies give the same shadows, and casters outside the view still
// cast into it.
#include <gtest/gtest.h>

#include <set>

#include "penumbra/errors.hpp"
#include "penumbra/scene/loader.hpp"
#include "render_fixture.hpp"
#include "renderer/app_context.hpp"

namespace penumbra::testing {
namespace {

constexpr const char* kLongGround = R"(
[camera]
eye = [0.0, 2.0, 0.0]
target = [0.0, 1.0, -30.0]
fov = 60.0
near = 0.1
far = 150.0

[[lights]]
type = "directional"
direction = [-0.3, -1.0, -0.4]

[[objects]]
type = "plane"
size = [60.0, 300.0]
translation = [0.0, 0.0, -140.0]
)";

TEST(CascadeImages, CascadeIndexGrowsWithDistanceAlongTheGround) {
    const Scene scene = scene_from_toml(kLongGround);
    RenderSettings settings = small_settings(96, 96);
    settings.shadow.cascades.count = 4;
    settings.shadow.cascades.max_distance = 120.0f;
    const RenderedFrame frame = render_with_validation(scene, settings);
    ASSERT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();

    const auto& cascade = frame.images.cascade;
    std::set<int> seen;
    for (uint32_t x = 0; x < settings.width; ++x) {
        int previous = -1;
        // From the bottom row (nearest ground) up towards the horizon.
        for (int y = static_cast<int>(settings.height) - 1; y >= 0; --y) {
            const int index = cascade[static_cast<size_t>(y) * settings.width + x];
            if (index == 255) {
                previous = 256;  // beyond the shadow distance: nothing nearer may follow
                continue;
            }
            EXPECT_GE(index, previous == 256 ? 256 : previous) << "column " << x << " row " << y;
            previous = index;
            seen.insert(index);
        }
    }
    EXPECT_EQ(seen.size(), 4u) << "every cascade should cover part of the ground";
}

constexpr const char* kPoles = R"(
[camera]
eye = [0.0, 4.0, 6.0]
target = [0.0, 0.0, -8.0]
fov = 60.0
near = 0.1
far = 80.0

[[lights]]
type = "directional"
direction = [-0.5, -1.0, 0.2]

[[objects]]
type = "plane"
size = [80.0, 80.0]

[[objects]]
type = "box"
size = [1.0, 2.0, 1.0]
translation = [1.0, 1.0, -2.0]

[[objects]]
type = "cylinder"
radius = 0.15
height = 5.0
translation = [3.0, 2.5, -10.0]

[[objects]]
type = "sphere"
radius = 1.0
translation = [-2.0, 1.5, -20.0]
)";

TEST(CascadeImages, EveryStrategyGivesTheSameShadows) {
    const Scene scene = scene_from_toml(kPoles);
    RenderSettings settings = small_settings(160, 120);
    settings.shadow.strategy = ShadowStrategy::PerCascade;
    const RenderedFrame per_cascade = render_with_validation(scene, settings);
    ASSERT_TRUE(per_cascade.validation_messages.empty()) << per_cascade.validation_messages.front();
    for (const ShadowStrategy strategy : {ShadowStrategy::Multiview, ShadowStrategy::Layered}) {
        settings.shadow.strategy = strategy;
        const RenderedFrame other = render_with_validation(scene, settings);
        ASSERT_TRUE(other.validation_messages.empty()) << other.validation_messages.front();
        size_t differing = 0, shadowed = 0;
        for (size_t i = 0; i < per_cascade.images.visibility.size(); ++i) {
            differing += per_cascade.images.visibility[i] != other.images.visibility[i];
            shadowed += per_cascade.images.visibility[i] < 32768;
        }
        EXPECT_GT(shadowed, 200u);
        EXPECT_LE(differing, per_cascade.images.visibility.size() / 1000)
            << choice_name(kShadowStrategyChoices, strategy) << ": at most 0.1% of pixels may differ";
    }
}

constexpr const char* kOffscreenCaster = R"(
[camera]
eye = [0.0, 6.0, 4.0]
target = [0.0, 0.0, 0.0]
fov = 40.0
near = 0.1
far = 50.0

[[lights]]
type = "directional"
direction = [1.0, -1.0, 0.0]

[[objects]]
type = "plane"
size = [40.0, 40.0]

[[objects]]
type = "box"
size = [2.0, 2.0, 2.0]
translation = [-8.0, 8.0, 0.0]
)";

TEST(CascadeImages, CasterOutsideTheViewStillCasts) {
    // The box floats above and to the left of the view; the sun throws its shadow onto the
    // ground at the centre of the image (x in [-1, 1] around the origin).
    const Scene scene = scene_from_toml(kOffscreenCaster);
    for (const bool cull : {true, false}) {
        RenderSettings settings = small_settings(120, 90);
        settings.shadow.cull_casters = cull;
        const RenderedFrame frame = render_with_validation(scene, settings);
        ASSERT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();
        EXPECT_LT(visibility_at(frame.images, 60, 45), 0.01f) << "cull=" << cull;
        EXPECT_GT(frame.info.cascades[0].draws, 1u) << "the off-screen box must be drawn into cascade 0";
    }
}

}  // namespace
}  // namespace penumbra::testing

namespace penumbra::testing {
namespace {

TEST(CascadeImages, EightCascadesRenderValidationCleanAndMultiviewRespectsTheDeviceViewLimit) {
    const Scene scene = scene_from_toml(kLongGround);
    RenderSettings settings = small_settings(64, 64);
    settings.shadow.cascades.count = 8;
    settings.shadow.cascades.resolution = 512;
    const RenderedFrame frame = render_with_validation(scene, settings);
    ASSERT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();
    EXPECT_EQ(frame.info.cascades.size(), 8u);

    settings.shadow.strategy = ShadowStrategy::Multiview;
    VulkanContextOptions options;
    options.validation = true;
    renderer::AppContext context(options);
    if (context.max_multiview_views() >= 8) {
        renderer::Renderer renderer(context, scene, settings);
        renderer.render(scene.camera);
    } else {
        EXPECT_THROW(renderer::Renderer(context, scene, settings), InputError);
    }
    EXPECT_TRUE(options.validation_log->messages.empty());
}

}  // namespace
}  // namespace penumbra::testing

// The forest's spot and point lights ("builtin:forest?count=N&spots=S&points=P"): the query
// parser's values and one-line errors, and where the lights go: spots above trees aimed down
// at their trunks, points beside trees, spread over the forest, the same at every load.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/local_lights.hpp"
#include "penumbra/scene/loader.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "scene/forest_scene.hpp"
#include "scene_test_support.hpp"
#include "scene_to_core.hpp"

namespace penumbra {
namespace {

using namespace testing;  // the core functions over the scene's types (scene_to_core.hpp)

using testing::input_error_message;

std::vector<const Light*> lights_of_type(const Scene& scene, LightType type) {
    std::vector<const Light*> lights;
    for (const Light& light : scene.lights) {
        if (light.type == type) lights.push_back(&light);
    }
    return lights;
}

TEST(ForestLights, ParsesCountSpotsAndPointsInAnyOrder) {
    const ForestParameters parameters = parse_forest_parameters("points=3&count=40&spots=2", "o");
    EXPECT_EQ(parameters.count, 40u);
    EXPECT_EQ(parameters.spots, 2u);
    EXPECT_EQ(parameters.points, 3u);
    const ForestParameters defaults = parse_forest_parameters("", "o");
    EXPECT_EQ(defaults.count, kForestDefaultCount);
    EXPECT_EQ(defaults.spots, 0u);
    EXPECT_EQ(defaults.points, 0u);
    EXPECT_EQ(parse_forest_parameters("spots=" + std::to_string(kMaxLocalLights), "o").spots, kMaxLocalLights);
}

// spot_angle widens the spots' cones; past 60 degrees each spot is shadowed by a cube.
TEST(ForestLights, SpotAngleSetsTheConesAndWideSpotsTakeCubes) {
    EXPECT_EQ(parse_forest_parameters("", "o").spot_angle, kForestDefaultSpotAngle);
    const Scene scene = load_scene("builtin:forest?count=20&spots=2&spot_angle=100");
    for (const Light* spot : lights_of_type(scene, LightType::Spot)) {
        EXPECT_FLOAT_EQ(spot->outer_angle_degrees, 100.0f);
        EXPECT_FLOAT_EQ(spot->inner_angle_degrees, 90.0f);
    }
    EXPECT_EQ(plan_local_shadows(scene.lights, LocalShadowSettings{}).layer_count, 2u * 6u);
    EXPECT_EQ(input_error_message([] { load_scene("builtin:forest?spot_angle=180"); }),
              "builtin:forest?spot_angle=180: spot_angle: expected an integer from 1 to 179, got \"180\"");
}

TEST(ForestLights, BadParametersAreOneLineErrorsNamingKeyAndValue) {
    const auto message = [](const std::string& query) {
        return input_error_message([&] { load_scene("builtin:forest?" + query); });
    };
    const std::string limit = std::to_string(kMaxLocalLights);  // lit local lights
    const std::string too_many = std::to_string(kMaxLocalLights + 1);
    EXPECT_EQ(message("spots=" + too_many), "builtin:forest?spots=" + too_many +
                                                ": spots: expected an integer from 0 to " + limit + ", got \"" +
                                                too_many + "\"");
    EXPECT_EQ(message("count=5&points=x"),
              "builtin:forest?count=5&points=x: points: expected an integer from 0 to " + limit + ", got \"x\"");
    EXPECT_EQ(message("points=-1"),
              "builtin:forest?points=-1: points: expected an integer from 0 to " + limit + ", got \"-1\"");
    EXPECT_EQ(message("spots="), "builtin:forest?spots=: spots: expected an integer from 0 to " + limit + ", got \"\"");
    EXPECT_EQ(message("count=0"), "builtin:forest?count=0: count: expected an integer from 1 to 100000, got \"0\"");
    EXPECT_EQ(message("spots=2&spots=3"), "builtin:forest?spots=2&spots=3: spots: given twice");
    EXPECT_EQ(message("lamps=2"),
              "builtin:forest?lamps=2: expected count=N, spots=N, points=N, spot_angle=N or movers=N joined by '&', "
              "got \"lamps=2\"");
    EXPECT_EQ(message("spots"),
              "builtin:forest?spots: expected count=N, spots=N, points=N, spot_angle=N or movers=N joined by '&', got "
              "\"spots\"");
    EXPECT_EQ(message("count=4&&spots=1"),
              "builtin:forest?count=4&&spots=1: expected count=N, spots=N, points=N, spot_angle=N or movers=N joined "
              "by '&', got \"\"");
    EXPECT_EQ(
        message("count=4&"),
        "builtin:forest?count=4&: expected count=N, spots=N, points=N, spot_angle=N or movers=N after the last '&'");
    const std::string half = std::to_string(kMaxLocalLights / 2);
    const std::string over_half = std::to_string(kMaxLocalLights / 2 + 1);
    const std::string sum = "spots=" + half + "&points=" + over_half;
    EXPECT_EQ(message(sum), "builtin:forest?" + sum + ": spots + points: at most " + limit +
                                " spot and point lights are lit, got " + half + " + " + over_half);
    for (const std::string& query :
         {"spots=" + too_many, std::string("lamps=2"), std::string("spots=2&spots=3"), sum}) {
        EXPECT_EQ(message(query).find('\n'), std::string::npos) << query;
    }
}

TEST(ForestLights, SunFirstThenSpotsThenPointsAllCastingShadows) {
    const Scene scene = load_scene("builtin:forest?count=20&spots=3&points=2");
    ASSERT_EQ(scene.lights.size(), 6u);
    EXPECT_EQ(scene.lights[0].type, LightType::Directional);
    for (size_t i = 1; i <= 3; ++i) EXPECT_EQ(scene.lights[i].type, LightType::Spot) << i;
    for (size_t i = 4; i <= 5; ++i) EXPECT_EQ(scene.lights[i].type, LightType::Point) << i;
    for (const Light& light : scene.lights) EXPECT_TRUE(light.cast_shadows);
    EXPECT_EQ(scene.instances.size(), 1 + 3 * size_t{20}) << "lights add no geometry";
    const LocalShadowPlan plan = plan_local_shadows(scene.lights, LocalShadowSettings{});
    EXPECT_EQ(plan.slots.size(), 5u);
    EXPECT_EQ(plan.layer_count, 3u + 2u * 6u);
}

TEST(ForestLights, SpotsHangAboveTheTreesAndAimAtATrunk) {
    const Scene scene = make_forest_scene(ForestParameters{50, 6, 0});
    const Aabb trees = scene.world_bounds();
    for (const Light* spot : lights_of_type(scene, LightType::Spot)) {
        EXPECT_GT(spot->position.y, trees.max.y * 0.5f);
        EXPECT_LT(spot->direction.y, -0.7f) << "aimed down";
        EXPECT_LT(spot->outer_angle_degrees, 90.0f);
        EXPECT_LE(spot->inner_angle_degrees, spot->outer_angle_degrees);
        // Its axis passes through the middle of a trunk (mesh 1 is the trunk cylinder).
        bool hits_a_trunk = false;
        for (const Instance& instance : scene.instances) {
            if (instance.mesh != 1) continue;
            const glm::vec3 trunk_center(instance.world[3]);
            const float t = (trunk_center.y - spot->position.y) / spot->direction.y;
            const glm::vec3 on_axis = spot->position + t * spot->direction;
            const float radius = glm::length(glm::vec3(instance.world[0]));
            hits_a_trunk |= glm::length(glm::vec2(on_axis.x - trunk_center.x, on_axis.z - trunk_center.z)) < radius;
        }
        EXPECT_TRUE(hits_a_trunk);
        EXPECT_GT(spot->range, spot->position.y / std::cos(glm::radians(spot->outer_angle_degrees + 20.0f)))
            << "the cone reaches the ground";
    }
}

TEST(ForestLights, LightsSpreadOverTheForestAndRepeat) {
    const Scene scene = load_scene("builtin:forest?count=1000&spots=4&points=4");
    for (const LightType type : {LightType::Spot, LightType::Point}) {
        Aabb spread;
        for (const Light* light : lights_of_type(scene, type)) spread.expand(light->position);
        EXPECT_GT(std::max(spread.extent().x, spread.extent().z), 0.5f * kForestSize);
    }
    for (const Light* point : lights_of_type(scene, LightType::Point)) {
        EXPECT_FLOAT_EQ(point->position.y, 2.5f);
        EXPECT_GT(point->range, 0.0f);
    }
    const Scene again = load_scene("builtin:forest?count=1000&spots=4&points=4");
    ASSERT_EQ(again.lights.size(), scene.lights.size());
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        EXPECT_EQ(again.lights[i].position, scene.lights[i].position);
        EXPECT_EQ(again.lights[i].direction, scene.lights[i].direction);
    }
}

TEST(ForestLights, MoreLightsThanTreesShareTrees) {
    const Scene scene = make_forest_scene(ForestParameters{1, 2, 2});
    EXPECT_EQ(lights_of_type(scene, LightType::Spot).size(), 2u);
    EXPECT_EQ(lights_of_type(scene, LightType::Point).size(), 2u);
}

TEST(ForestLights, MoversAreDynamicCrownsInView) {
    const Scene plain = load_scene("builtin:forest?count=20");
    const Scene scene = load_scene("builtin:forest?count=20&movers=4");
    ASSERT_EQ(scene.instances.size(), plain.instances.size() + 4);
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        EXPECT_EQ(instance.dynamic, i >= plain.instances.size()) << "instance " << i;
        if (!instance.dynamic) continue;
        // On the ring about the point the camera looks at, above the ground.
        const glm::vec3 place(instance.world[3]);
        EXPECT_NEAR(glm::length(glm::vec2(place.x, place.z)), 25.0f, 1e-3f);
        EXPECT_GT(place.y, 0.0f);
    }
    EXPECT_EQ(input_error_message([] { load_scene("builtin:forest?movers=1001"); }),
              "builtin:forest?movers=1001: movers: expected an integer from 0 to 1000, got \"1001\"");
}

}  // namespace
}  // namespace penumbra

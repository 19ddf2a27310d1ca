// The open-world scene ("builtin:terrain?size=S&trees=N"): its documented triangle count,
// casters in every octave of distance from the camera (the fence within 10 m, trees from 6 m
// to kilometres, buildings to the horizon), trees and buildings standing on the height
// field, flat ground around the camera, the same scene at every load, one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "penumbra/scene/loader.hpp"
#include "scene/terrain_scene.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

using testing::input_error_message;

// Horizontal distance from the camera to the centre of each instance but the ground's tiles.
std::vector<float> caster_distances(const Scene& scene) {
    std::vector<float> distances;
    for (size_t i = kTerrainTiles * kTerrainTiles; i < scene.instances.size(); ++i) {
        const glm::vec3 centre = glm::vec3(scene.instances[i].world[3]);
        distances.push_back(glm::length(glm::vec2(centre.x - scene.camera.eye.x, centre.z - scene.camera.eye.z)));
    }
    return distances;
}

TEST(TerrainScene, HasTheDocumentedTriangleCount) {
    const Scene scene = load_scene("builtin:terrain");
    EXPECT_EQ(scene.triangle_count(), 1121652u);
    EXPECT_EQ(scene.triangle_count(), kTerrainGroundTriangles + kTerrainFenceTriangles +
                                          kTerrainTrianglesPerTree * kTerrainDefaultTrees + 12 * kTerrainBuildings);
    EXPECT_EQ(load_scene("builtin:terrain?trees=0").triangle_count(),
              kTerrainGroundTriangles + kTerrainFenceTriangles + 12 * kTerrainBuildings);
    EXPECT_EQ(scene.instances.size(),
              kTerrainTiles * kTerrainTiles + kTerrainFencePosts + 2 + 2 * kTerrainDefaultTrees + kTerrainBuildings);
}

TEST(TerrainScene, HasCastersInEveryOctaveOfDistance) {
    const Scene scene = load_scene("builtin:terrain");
    const std::vector<float> distances = caster_distances(scene);
    // The fence a few metres in front of the camera, and in every octave from 16 m to 8 km
    // (trees, then buildings too) a good share of the 2,200 casters.
    for (size_t fence = 0; fence < kTerrainFencePosts + 2; ++fence) EXPECT_LE(distances[fence], 10.01f);
    const auto near_trees =
        std::count_if(distances.begin() + kTerrainFencePosts + 2, distances.end(), [](float d) { return d < 24.0f; });
    EXPECT_GE(near_trees, 2 * 60);  // trunks and crowns
    for (float nearest = 16.0f; nearest < 8000.0f; nearest *= 2.0f) {
        const auto in_octave = std::count_if(distances.begin(), distances.end(),
                                             [&](float d) { return d >= nearest && d < 2.0f * nearest; });
        EXPECT_GE(in_octave, 100) << "between " << nearest << " and " << 2.0f * nearest << " m";
    }
    EXPECT_LE(*std::max_element(distances.begin(), distances.end()), 0.45f * kTerrainDefaultSize + 30.0f);
    EXPECT_FLOAT_EQ(scene.camera.far_plane, static_cast<float>(kTerrainDefaultSize));
}

TEST(TerrainScene, CastersStandOnTheGroundWhichIsFlatAroundTheCamera) {
    const float size = 20000.0f;
    for (const float x : {0.0f, 150.0f, -280.0f}) EXPECT_EQ(terrain_height(x, -x, size), 0.0f);  // within 400 m
    float highest = 0.0f;
    for (float x = -9000.0f; x <= 9000.0f; x += 500.0f) {
        for (float z = -9000.0f; z <= 9000.0f; z += 500.0f)
            highest = std::max(highest, std::abs(terrain_height(x, z, size)));
    }
    EXPECT_GT(highest, 0.005f * size);  // hills, kilometres away
    EXPECT_LE(highest, 0.012f * size);
    // Every trunk (after the tiles and the fence) stands on the height field; its mesh is a
    // unit cylinder centred on its origin, so its foot is half its height below its centre.
    const Scene scene = load_scene("builtin:terrain");
    const size_t first_trunk = kTerrainTiles * kTerrainTiles + kTerrainFencePosts + 2;
    for (size_t i = first_trunk; i < first_trunk + 2 * kTerrainDefaultTrees; i += 2) {
        const glm::mat4& trunk = scene.instances[i].world;
        const float foot = trunk[3].y - 0.5f * trunk[1].y;
        EXPECT_NEAR(foot, terrain_height(trunk[3].x, trunk[3].z, size), 1e-3f * std::max(1.0f, std::abs(foot)));
    }
    EXPECT_GT(scene.camera.eye.y, terrain_height(scene.camera.eye.x, scene.camera.eye.z, size));
}

TEST(TerrainScene, IsTheSameAtEveryLoadAndScalesWithItsSize) {
    const Scene first = load_scene("builtin:terrain?size=5000&trees=200");
    const Scene second = load_scene("builtin:terrain?trees=200&size=5000");
    ASSERT_EQ(first.instances.size(), second.instances.size());
    for (size_t i = 0; i < first.instances.size(); ++i) EXPECT_EQ(first.instances[i].world, second.instances[i].world);
    const std::vector<float> distances = caster_distances(first);
    EXPECT_LE(*std::max_element(distances.begin(), distances.end()), 0.45f * 5000.0f + 30.0f);
    EXPECT_FLOAT_EQ(first.camera.far_plane, 5000.0f);
}

TEST(TerrainScene, BadParametersAreOneLineErrors) {
    EXPECT_EQ(input_error_message([] { load_scene("builtin:terrain?size=10"); }),
              "builtin:terrain?size=10: size: expected an integer from 1000 to 40000, got \"10\"");
    EXPECT_EQ(input_error_message([] { load_scene("builtin:terrain?count=5"); }),
              "builtin:terrain?count=5: expected size=N or trees=N joined by '&', got \"count=5\"");
    EXPECT_EQ(input_error_message([] { load_scene("builtin:terrain?trees=1&trees=2"); }),
              "builtin:terrain?trees=1&trees=2: trees: given twice");
}

}  // namespace
}  // namespace penumbra

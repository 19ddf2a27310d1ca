// Sky boxes and domes that shadow the whole image are found by what the camera sees
// (quality::find_enclosing_casters), named as exclude_casters accepts them, and rooms lit
// through a window are left alone.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "gltf_writer.hpp"
#include "penumbra/scene/loader.hpp"
#include "quality/enclosing_casters.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

using ::testing::HasSubstr;
using namespace penumbra::testing;
namespace fs = std::filesystem;

constexpr float kPi = 3.14159265f;

// A sky as a public city scene has it: one node whose mesh holds 8 primitives, each a
// 45-degree wedge of a closed prism of radius 50 m and height 60 m, around the origin.
GltfTestNode wedge_sky(const std::string& node_name, const std::string& mesh_name) {
    GltfTestNode sky{node_name, mesh_name, {}};
    for (int wedge = 0; wedge < 8; ++wedge) {
        const float a0 = static_cast<float>(wedge) * kPi / 4.0f;
        const float a1 = static_cast<float>(wedge + 1) * kPi / 4.0f;
        const glm::vec3 p0{50.0f * std::cos(a0), 0.0f, 50.0f * std::sin(a0)};
        const glm::vec3 p1{50.0f * std::cos(a1), 0.0f, 50.0f * std::sin(a1)};
        const glm::vec3 up{0.0f, 30.0f, 0.0f};
        GltfTestPrimitive primitive;
        add_test_quad(primitive, p0 - up, p1 - up, p1 + up, p0 + up);
        primitive.positions.insert(primitive.positions.end(), {up, p0 + up, p1 + up, -up, p1 - up, p0 - up});
        primitive.indices.insert(primitive.indices.end(), {4, 5, 6, 7, 8, 9});
        sky.primitives.push_back(primitive);
    }
    return sky;
}

// A room of 8 x 3 x 8 m in one node, its ceiling open over a 3 x 3 m window or closed.
GltfTestNode room(bool window) {
    GltfTestPrimitive walls;
    const auto corner = [](float x, float y, float z) { return glm::vec3{x, y, z}; };
    add_test_quad(walls, corner(-4, 0, -4), corner(-4, 0, 4), corner(4, 0, 4), corner(4, 0, -4));
    add_test_quad(walls, corner(-4, 0, -4), corner(4, 0, -4), corner(4, 3, -4), corner(-4, 3, -4));
    add_test_quad(walls, corner(-4, 0, 4), corner(-4, 3, 4), corner(4, 3, 4), corner(4, 0, 4));
    add_test_quad(walls, corner(-4, 0, -4), corner(-4, 3, -4), corner(-4, 3, 4), corner(-4, 0, 4));
    add_test_quad(walls, corner(4, 0, -4), corner(4, 0, 4), corner(4, 3, 4), corner(4, 3, -4));
    const float hole = window ? 1.5f : 0.0f;
    add_test_quad(walls, corner(-4, 3, -4), corner(4, 3, -4), corner(4, 3, -hole), corner(-4, 3, -hole));
    add_test_quad(walls, corner(-4, 3, hole), corner(4, 3, hole), corner(4, 3, 4), corner(-4, 3, 4));
    add_test_quad(walls, corner(-4, 3, -hole), corner(-hole, 3, -hole), corner(-hole, 3, hole), corner(-4, 3, hole));
    add_test_quad(walls, corner(hole, 3, -hole), corner(4, 3, -hole), corner(4, 3, hole), corner(hole, 3, hole));
    return {"Room", "RoomMesh", {walls}};
}

constexpr const char* kOutdoor = R"toml(
[camera]
eye = [0.0, 6.0, 12.0]
target = [0.0, 0.0, 0.0]

[[lights]]
type = "directional"
direction = [-0.4, -1.0, -0.3]

[[objects]]
type = "plane"
size = [120.0, 120.0]

[[objects]]
type = "box"
size = [2.0, 2.0, 2.0]
translation = [0.0, 1.0, 0.0]
)toml";

constexpr const char* kIndoor = R"toml(
[camera]
eye = [0.0, 1.6, 3.5]
target = [0.0, 0.0, -1.0]

[[lights]]
type = "directional"
direction = [-0.2, -1.0, -0.1]

[[objects]]
type = "box"
size = [1.0, 0.8, 1.0]
translation = [2.5, 0.4, -2.5]

[[objects]]
type = "gltf"
file = "room.gltf"
)toml";

class EnclosingCasters : public ScratchFolderTest {
protected:
    std::vector<quality::EnclosingCaster> find(const std::string& scene_text) const {
        const Scene scene = parse_scene_toml(scene_text, "scene.toml", dir_);
        return quality::find_enclosing_casters(scene, scene.camera, 4.0f / 3.0f);
    }
};

TEST_F(EnclosingCasters, ASkyOfManyPrimitivesIsOneCasterNamedAsExcludeCastersTakesIt) {
    // The ground (120 m) pokes 10 m out of the sky on every side.
    write_test_gltf(dir_ / "sky.gltf", {wedge_sky("", "skbox")});
    const std::string scene = std::string(kOutdoor) + "\n[[objects]]\ntype = \"gltf\"\nfile = \"sky.gltf\"\n";
    const auto found = find(scene);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].entry.instances.size(), 8u);
    EXPECT_EQ(exclusion_name(found[0].entry.origin), "skbox");
    EXPECT_GE(found[0].shadowed_share, 0.999);
    const std::string warning = quality::enclosing_casters_warning(found);
    EXPECT_THAT(warning, HasSubstr("\"skbox\" encloses the camera and the scene and shadows 100% of what"));
    EXPECT_THAT(warning, HasSubstr("exclude_casters = [\"skbox\"] in objects[2]"));
    // The advice, followed, silences it.
    EXPECT_TRUE(find(scene + "exclude_casters = [\"skbox\"]\n").empty());
}

TEST_F(EnclosingCasters, AnUnnamedSkyIsNamedByItsNodeIndex) {
    write_test_gltf(dir_ / "sky.gltf", {wedge_sky("", "")});
    const std::string scene = std::string(kOutdoor) + "\n[[objects]]\ntype = \"gltf\"\nfile = \"sky.gltf\"\n";
    const auto found = find(scene);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_THAT(quality::enclosing_casters_warning(found), HasSubstr("exclude_casters = [\"nodes[0]\"] in objects[2]"));
    EXPECT_TRUE(find(scene + "exclude_casters = [\"nodes[0]\"]\n").empty());
}

TEST_F(EnclosingCasters, AClosedBoxObjectIsNamedWithItsCastShadowsKey) {
    const std::string scene = std::string(kOutdoor) + "\n[[objects]]\ntype = \"box\"\nsize = [200.0, 200.0, 200.0]\n";
    const auto found = find(scene);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_THAT(quality::enclosing_casters_warning(found),
                HasSubstr("\"objects[2] (box)\" encloses the camera and the scene and shadows 100%"));
    EXPECT_THAT(quality::enclosing_casters_warning(found), HasSubstr("cast_shadows = false in objects[2]"));
    EXPECT_TRUE(find(scene + "cast_shadows = false\n").empty());
    // Small and away from the camera, the same box is just a box.
    EXPECT_TRUE(find(std::string(kOutdoor) + "\n[[objects]]\ntype = \"box\"\ntranslation = [5.0, 1.0, 0.0]\n").empty());
}

// A room around the camera and its furniture, in shadow but for the patch its roof window
// lets in, is what the user built: no warning. Closing the window makes it one.
TEST_F(EnclosingCasters, ARoomLitThroughItsWindowIsNotReported) {
    write_test_gltf(dir_ / "room.gltf", {room(true)});
    EXPECT_TRUE(find(kIndoor).empty());
    write_test_gltf(dir_ / "room.gltf", {room(false)});
    const auto closed = find(kIndoor);
    ASSERT_EQ(closed.size(), 1u);
    EXPECT_EQ(exclusion_name(closed[0].entry.origin), "Room");
}

// Without a sun that casts shadows there is nothing to warn about.
TEST_F(EnclosingCasters, NoSunNoWarning) {
    write_test_gltf(dir_ / "sky.gltf", {wedge_sky("Sky", "")});
    std::string scene = std::string(kOutdoor) + "\n[[objects]]\ntype = \"gltf\"\nfile = \"sky.gltf\"\n";
    ASSERT_EQ(find(scene).size(), 1u);
    scene.replace(scene.find("direction = [-0.4, -1.0, -0.3]"), 30,
                  "direction = [-0.4, -1.0, -0.3]\ncast_shadows = false");
    EXPECT_TRUE(find(scene).empty());
}

// Nothing in the scenes Penumbra ships or measures with is a sky: no warning on the built-in
// scenes, and none on bench/scenes (the oaks and terrain of ../shared/assets, Debian's
// assimp-testmodels) when their assets are present.
TEST(EnclosingCastersInRealScenes, NoneInTheBuiltInAndBenchScenes) {
    for (const std::string& name : builtin_scene_names()) {
        const Scene scene = load_scene("builtin:" + name);
        EXPECT_TRUE(quality::find_enclosing_casters(scene, scene.camera, 16.0f / 9.0f).empty()) << name;
    }
    const fs::path shared = PENUMBRA_SHARED_ASSETS_DIR;
    if (!fs::exists(shared / "oaktree") || !fs::exists("/usr/share/assimp/models/glTF2")) {
        GTEST_SKIP() << "bench/scenes not checked: ../shared/assets or assimp-testmodels is absent";
    }
    for (const auto& file : fs::directory_iterator(fs::path(PENUMBRA_SOURCE_DIR) / "bench" / "scenes")) {
        if (file.path().extension() != ".toml") continue;
        const Scene scene = load_scene(file.path().string());
        EXPECT_TRUE(quality::find_enclosing_casters(scene, scene.camera, 16.0f / 9.0f).empty()) << file.path();
    }
}

}  // namespace
}  // namespace penumbra

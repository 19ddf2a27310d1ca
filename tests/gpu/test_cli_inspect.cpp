// `penumbra inspect`: every object and glTF node of a scene with the names its settings
// take, and the sky warning of `render`, whose advice works as printed.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "cli_runner.hpp"
#include "gltf_writer.hpp"

namespace {

using Cli = penumbra::testing::CliTest;
using penumbra::testing::add_test_box_face;
using penumbra::testing::GltfTestNode;
using penumbra::testing::GltfTestPrimitive;
using penumbra::testing::write_test_gltf;

constexpr const char* kScene = R"(
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
type = "gltf"
file = "model.gltf"
)";

// A closed box of half-size `half` around `center`, its faces split over `pieces` primitives.
std::vector<GltfTestPrimitive> box_primitives(glm::vec3 center, float half, int pieces) {
    std::vector<GltfTestPrimitive> primitives(static_cast<size_t>(pieces));
    for (int face = 0; face < 6; ++face)
        add_test_box_face(primitives[static_cast<size_t>(face % pieces)], center, half, face);
    return primitives;
}

// A sky of six primitives (mesh "skbox", node unnamed) 100 m across, smaller than the
// 120 m ground, and a named crate.
void write_model(const std::filesystem::path& file) {
    write_test_gltf(file, {GltfTestNode{"", "skbox", box_primitives({0.0f, 0.0f, 0.0f}, 50.0f, 6)},
                           GltfTestNode{"Crate", "", box_primitives({0.0f, 1.0f, 0.0f}, 1.0f, 1)}});
}

TEST_F(Cli, InspectListsEveryNodeByTheNamesExcludeCastersTakes) {
    write_model(dir_ / "model.gltf");
    write_file("scene.toml", kScene);
    const auto listed = run("inspect scene.toml");
    ASSERT_EQ(listed.exit_code, 0) << listed.err;
    EXPECT_NE(listed.out.find("objects[0] plane\n"), std::string::npos) << listed.out;
    EXPECT_NE(
        listed.out.find("objects[1] gltf model.gltf  node nodes[0] (unnamed)  mesh meshes[0] \"skbox\"  "
                        "exclude_casters \"skbox\"\n    6 primitive(s), 1 placement(s), 12 triangles; casts: all"),
        std::string::npos)
        << listed.out;
    EXPECT_NE(listed.out.find("node nodes[1] \"Crate\"  mesh meshes[1] (unnamed)  exclude_casters \"Crate\""),
              std::string::npos)
        << listed.out;
    EXPECT_NE(listed.out.find("lights[0] directional toward"), std::string::npos) << listed.out;

    const auto json_run = run("inspect scene.toml --json");
    ASSERT_EQ(json_run.exit_code, 0) << json_run.err;
    const nlohmann::json document = nlohmann::json::parse(json_run.out);
    ASSERT_EQ(document["objects"].size(), 3u);
    EXPECT_EQ(document["triangles"].get<int>(), document["objects"][0]["triangles"].get<int>() + 12 + 12);
    const nlohmann::json& sky = document["objects"][1];
    EXPECT_EQ(sky["mesh_name"], "skbox");
    EXPECT_EQ(sky["node_name"], "");
    EXPECT_EQ(sky["exclude_casters"], "skbox");
    EXPECT_EQ(sky["primitives"], 6);
    EXPECT_EQ(sky["bounds"]["max"][0], 50.0);
    EXPECT_EQ(document["objects"][2]["exclude_casters"], "Crate");

    // Every name it prints is taken as printed.
    for (const std::string name : {"skbox", "Crate", "nodes[0]", "meshes[1]"}) {
        write_file("excluding.toml", std::string(kScene) + "exclude_casters = [\"" + name + "\"]\n");
        const auto excluded = run("inspect excluding.toml --json");
        ASSERT_EQ(excluded.exit_code, 0) << name << ": " << excluded.err;
    }
    const auto missing = run("inspect nothing.toml");
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("nothing.toml"), std::string::npos) << missing.err;
}

// The public city scene's case: a sky of several primitives, smaller than the ground, in
// an unnamed node; render names its mesh, and the advice works as printed.
TEST_F(Cli, ASkyOfSeveralPrimitivesIsNamedAndItsAdviceWorksAsPrinted) {
    write_model(dir_ / "model.gltf");
    write_file("scene.toml", kScene);
    const auto warned = run("render scene.toml --validate --aov shadow --width 48 --height 32 -o warned.png");
    ASSERT_EQ(warned.exit_code, 0) << warned.err;
    EXPECT_NE(warned.err.find("warning: \"skbox\" encloses the camera and the scene and shadows 100% of what the "
                              "camera sees (a sky box or dome?): exclude_casters = [\"skbox\"] in objects[1]"),
              std::string::npos)
        << warned.err;
    write_file("excluded.toml", std::string(kScene) + "exclude_casters = [\"skbox\"]\n");
    const auto excluded = run("render excluded.toml --validate --aov shadow --width 48 --height 32 -o excluded.png");
    ASSERT_EQ(excluded.exit_code, 0) << excluded.err;
    EXPECT_TRUE(excluded.err.empty()) << excluded.err;
}

}  // namespace

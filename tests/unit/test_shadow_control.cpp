// Which instances cast and receive shadows (issue 16): cast_shadows and receive_shadows per
// scene object and per glTF instance, exclude_casters by node or mesh name (with '*'), glTF
// materials that are unlit (the sky-box warning: test_enclosing_casters.cpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "gltf_writer.hpp"
#include "penumbra/scene/loader.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::parse_scene_text;
using testing::scene_error;
using testing::test_data;

std::string named_model(const std::string& keys) {
    return "[[objects]]\ntype = \"gltf\"\nfile = \"" + test_data("gltf/named.gltf").string() + "\"\n" + keys;
}

std::vector<bool> casts(const Scene& scene) {
    std::vector<bool> flags;
    for (const Instance& instance : scene.instances) flags.push_back(instance.cast_shadows);
    return flags;
}

TEST(ShadowControl, SceneObjectsCastAndReceiveUnlessTold) {
    const Scene scene = parse_scene_text(
        "[[objects]]\ntype = \"plane\"\nreceive_shadows = false\n\n"
        "[[objects]]\ntype = \"box\"\ncast_shadows = false\n\n[[objects]]\ntype = \"sphere\"\n");
    ASSERT_EQ(scene.instances.size(), 3u);
    EXPECT_TRUE(scene.instances[0].cast_shadows);
    EXPECT_FALSE(scene.instances[0].receive_shadows);
    EXPECT_FALSE(scene.instances[1].cast_shadows);
    EXPECT_TRUE(scene.instances[1].receive_shadows);
    EXPECT_TRUE(scene.instances[2].cast_shadows && scene.instances[2].receive_shadows);
    EXPECT_EQ(scene.instances[1].name, "objects[1] (box)");
    EXPECT_THAT(scene_error("[[objects]]\ntype = \"box\"\ncast_shadows = 0\n"), HasSubstr("objects[0].cast_shadows"));
}

// The unlit card never casts; names and patterns exclude the rest.
TEST(ShadowControl, GltfExclusionsByNodeOrMeshNameAndUnlitMaterials) {
    EXPECT_THAT(casts(parse_scene_text(named_model(""))), ElementsAre(true, true, false));
    EXPECT_THAT(casts(parse_scene_text(named_model("exclude_casters = [\"sky dome\"]\n"))),
                ElementsAre(true, false, false));
    EXPECT_THAT(casts(parse_scene_text(named_model("exclude_casters = [\"floor\"]\n"))),
                ElementsAre(false, true, false));
    EXPECT_THAT(casts(parse_scene_text(named_model("exclude_casters = [\"sky*\"]\n"))),
                ElementsAre(true, false, false));
    const Scene scene = parse_scene_text(named_model(""));
    EXPECT_EQ(scene.instances[1].name, "sky dome");
    EXPECT_THAT(scene_error(named_model("exclude_casters = [\"skbox\"]\n")),
                HasSubstr("exclude_casters[0]: \"skbox\" matches no node or mesh name of the model"));
    EXPECT_THAT(scene_error(named_model("exclude_casters = \"sky\"\n")),
                HasSubstr("objects[0].exclude_casters: expected an array of strings"));
}

// "nodes[i]" and "meshes[j]" name an element by its index, as printed for unnamed nodes
// (Instance::name, the sky-box warning's advice), not as a shell pattern ("[1]" would be a
// character class matching nothing here).
TEST(ShadowControl, GltfExclusionsByIndexAsTheWarningPrintsThem) {
    EXPECT_THAT(casts(parse_scene_text(named_model("exclude_casters = [\"nodes[1]\"]\n"))),
                ElementsAre(true, false, false));
    EXPECT_THAT(casts(parse_scene_text(named_model("exclude_casters = [\"meshes[0]\"]\n"))),
                ElementsAre(false, true, false));
    EXPECT_THAT(scene_error(named_model("exclude_casters = [\"nodes[3]\"]\n")),
                HasSubstr("exclude_casters[0]: \"nodes[3]\" names no node (the model has 3)"));
    EXPECT_THAT(scene_error(named_model("exclude_casters = [\"floor\", \"meshes[9]\"]\n")),
                HasSubstr("exclude_casters[1]: \"meshes[9]\" names no mesh (the model has 3)"));
}

TEST(ShadowControl, GltfObjectAndInstanceFlags) {
    const Scene scene = parse_scene_text(
        named_model("cast_shadows = false\ninstances = [{ translation = [1.0, 0.0, 0.0] },\n"
                    "  { translation = [2.0, 0.0, 0.0], cast_shadows = true, receive_shadows = false }]\n"));
    ASSERT_EQ(scene.instances.size(), 6u);
    EXPECT_THAT(casts(scene), ElementsAre(false, false, false, true, true, false));
    EXPECT_TRUE(scene.instances[0].receive_shadows);
    EXPECT_FALSE(scene.instances[3].receive_shadows);
}

// `dynamic` (cached cascades draw such instances every frame): per object, per glTF
// object and per placement, false unless given.
TEST(ShadowControl, DynamicFlagsPerObjectAndPlacement) {
    const Scene objects =
        parse_scene_text("[[objects]]\ntype = \"box\"\ndynamic = true\n\n[[objects]]\ntype = \"plane\"\n");
    ASSERT_EQ(objects.instances.size(), 2u);
    EXPECT_TRUE(objects.instances[0].dynamic);
    EXPECT_FALSE(objects.instances[1].dynamic);
    const Scene model =
        parse_scene_text(named_model("dynamic = true\ninstances = [{ translation = [1.0, 0.0, 0.0] },\n"
                                     "  { translation = [2.0, 0.0, 0.0], dynamic = false }]\n"));
    ASSERT_EQ(model.instances.size(), 6u);
    std::vector<bool> dynamic;
    for (const Instance& instance : model.instances) dynamic.push_back(instance.dynamic);
    EXPECT_THAT(dynamic, ElementsAre(true, true, true, false, false, false));
    EXPECT_THAT(scene_error("[[objects]]\ntype = \"box\"\ndynamic = 1\n"), HasSubstr("objects[0].dynamic"));
}

// The pattern scene-format.md prints, against a model whose sky node is called "SkyDome":
// it matches as printed; patterns are case-sensitive, so "sky*" names nothing and says so.
TEST(ShadowControl, TheDocumentedSkyPatternWorksAsPrinted) {
    const std::filesystem::path folder = std::filesystem::temp_directory_path() / "penumbra_sky_pattern";
    std::filesystem::create_directories(folder);
    testing::write_test_gltf(folder / "model.gltf", {{"SkyDome", "", {testing::test_box(glm::vec3{0.0f}, 50.0f)}},
                                                     {"Crate", "", {testing::test_box(glm::vec3{0.0f}, 1.0f)}}});
    const auto scene = [&](const std::string& pattern) {
        return parse_scene_toml(
            "[[objects]]\ntype = \"gltf\"\nfile = \"model.gltf\"\nexclude_casters = [\"" + pattern + "\"]\n",
            "scene.toml", folder);
    };
    EXPECT_THAT(casts(scene("Sky*")), ElementsAre(false, true));
    EXPECT_THAT(testing::input_error_message([&] { scene("sky*"); }),
                HasSubstr("\"sky*\" matches no node or mesh name of the model"));
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace penumbra

// Every problem a user can put in a scene file is one InputError line naming the file, the
// key and the offending value.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "penumbra/scene/loader.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

using ::testing::HasSubstr;
using testing::input_error_message;
using testing::scene_error;
using ::testing::StartsWith;
using testing::test_data;

TEST(SceneErrors, MissingFile) {
    const std::string message = input_error_message([] { load_scene("no/such/scene.toml"); });
    EXPECT_EQ(message, "no/such/scene.toml: scene file not found");
}

TEST(SceneErrors, UnreadableFile) {
    const std::string folder = test_data("scenes").string();
    EXPECT_EQ(input_error_message([&] { load_scene(folder); }), folder + ": not a regular file");
}

TEST(SceneErrors, MalformedTomlNamesLineAndColumn) {
    const std::string message = scene_error("[camera]\nfov = 60\neye = [0, 1\n");
    EXPECT_THAT(message, StartsWith("scene.toml:3:"));
    EXPECT_THAT(message, HasSubstr("malformed TOML: "));
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(SceneErrors, StringWhereNumberExpected) {
    EXPECT_EQ(scene_error("[camera]\nfov = \"wide\"\n"),
              "scene.toml: camera.fov: expected a number, got a string \"wide\"");
}

TEST(SceneErrors, ArrayOfWrongLength) {
    EXPECT_EQ(scene_error("[camera]\neye = [1, 2]\n"),
              "scene.toml: camera.eye: expected an array of 3 numbers, got an array [1, 2]");
}

TEST(SceneErrors, ArrayWithNonNumbers) {
    EXPECT_THAT(scene_error("[camera]\ntarget = [1, \"x\", 2]\n"),
                HasSubstr("camera.target: expected an array of 3 numbers, got an array [1, \"x\", 2]"));
}

TEST(SceneErrors, ColourOfWrongLength) {
    EXPECT_EQ(scene_error("[[objects]]\ntype = \"box\"\ncolor = [1, 1]\n"),
              "scene.toml: objects[0].color: expected an array of 3 to 4 numbers, got an array [1, 1]");
}

TEST(SceneErrors, NumberWhereBooleanExpected) {
    EXPECT_EQ(scene_error("[[lights]]\ncast_shadows = 1\n"),
              "scene.toml: lights[0].cast_shadows: expected true or false, got a number 1");
}

TEST(SceneErrors, TableWhereArrayOfTablesExpected) {
    EXPECT_THAT(scene_error("lights = 3\n"), HasSubstr("scene.toml: lights: expected an array of tables"));
    EXPECT_THAT(scene_error("objects = [1]\n"), HasSubstr("scene.toml: objects[0]: expected a table, got a number 1"));
    EXPECT_THAT(scene_error("camera = 5\n"), HasSubstr("scene.toml: camera: expected a table, got a number 5"));
}

TEST(SceneErrors, NonFiniteNumber) {
    EXPECT_EQ(scene_error("[camera]\nfov = nan\n"), "scene.toml: camera.fov: expected a finite number, got nan");
}

TEST(SceneErrors, UnknownObjectType) {
    EXPECT_EQ(
        scene_error("[[objects]]\ntype = \"box\"\n[[objects]]\ntype = \"box\"\n[[objects]]\ntype = \"cone\"\n"),
        "scene.toml: objects[2].type: unknown object type \"cone\" (expected plane, box, sphere, cylinder or gltf)");
}

TEST(SceneErrors, MissingObjectType) {
    EXPECT_EQ(scene_error("[[objects]]\nsize = [1, 1, 1]\n"),
              "scene.toml: objects[0].type: missing (a string is required)");
}

TEST(SceneErrors, UnknownTopLevelTable) {
    EXPECT_THAT(scene_error("[sky]\ncolor = [0, 0, 1]\n"),
                StartsWith("scene.toml: sky: unknown key \"sky\" (expected "));
}

TEST(SceneErrors, UnknownKeyInEveryTable) {
    EXPECT_THAT(scene_error("[camera]\nfovy = 60\n"), StartsWith("scene.toml: camera.fovy: unknown key \"fovy\""));
    EXPECT_THAT(scene_error("[[lights]]\ncolour = [1, 1, 1]\n"),
                StartsWith("scene.toml: lights[0].colour: unknown key"));
    EXPECT_THAT(scene_error("[ambient]\nintensity = 2\n"), StartsWith("scene.toml: ambient.intensity: unknown key"));
    // A key that belongs to another object type is unknown too.
    EXPECT_THAT(scene_error("[[objects]]\ntype = \"box\"\nradius = 1\n"),
                StartsWith("scene.toml: objects[0].radius: unknown key \"radius\""));
    EXPECT_THAT(scene_error("[[objects]]\ntype = \"gltf\"\nfile = \"../gltf/quad.gltf\"\ncolor = [1, 1, 1]\n"),
                StartsWith("scene.toml: objects[0].color: unknown key"));
    EXPECT_THAT(scene_error("[[objects]]\ntype = \"gltf\"\nfile = \"../gltf/quad.gltf\"\ninstances = [{ scal = 2 }]\n"),
                StartsWith("scene.toml: objects[0].instances[0].scal: unknown key"));
}

// Numbers a double holds but the float math cannot carry are refused at the key that holds
// them (issue 17): the image would otherwise be silently wrong (a sky-only or black frame).
TEST(SceneErrors, NumbersBeyondTheFloatMath) {
    EXPECT_THAT(scene_error("[[lights]]\ntype = \"directional\"\nintensity = 1e308\n"),
                StartsWith("scene.toml: lights[0].intensity: 1e+308 is beyond 1e9 in magnitude"));
    EXPECT_THAT(scene_error("[[objects]]\ntype = \"sphere\"\nradius = 1e308\n"),
                StartsWith("scene.toml: objects[0].radius: 1e+308 is beyond 1e9"));
    EXPECT_THAT(scene_error("[[objects]]\ntype = \"box\"\nscale = 1e300\n"),
                StartsWith("scene.toml: objects[0].scale: 1e+300 is beyond 1e9"));
    EXPECT_THAT(scene_error("[[objects]]\ntype = \"box\"\nrotation = [0, 1e308, 0]\n"),
                StartsWith("scene.toml: objects[0].rotation: 1e+308 is beyond 1e9"));
    EXPECT_THAT(scene_error("[camera]\nfar = 1e39\n"), StartsWith("scene.toml: camera.far: 1e+39 is beyond 1e9"));
    // The limit itself is fine.
    EXPECT_NO_THROW(testing::parse_scene_text("[camera]\nfar = 1e9\n"));
}

// Integers a double cannot hold exactly (beyond 2^53) are refused by the same rule, at their
// key, in plain numbers and in arrays (issue 32: they were read through an empty optional).
TEST(SceneErrors, IntegersADoubleCannotHold) {
    EXPECT_EQ(scene_error("[camera]\nfov = 9223372036854775807\n"),
              "scene.toml: camera.fov: 9223372036854775807 is beyond 1e9 in magnitude, the largest Penumbra's 32-bit "
              "float math carries");
    EXPECT_THAT(scene_error("[[lights]]\ntype = \"directional\"\ndirection = [0, -9007199254740993, 0]\n"),
                StartsWith("scene.toml: lights[0].direction: -9007199254740993 is beyond 1e9"));
    EXPECT_THAT(scene_error("[[objects]]\ntype = \"box\"\nscale = -9223372036854775808\n"),
                StartsWith("scene.toml: objects[0].scale: -9223372036854775808 is beyond 1e9"));
    EXPECT_THAT(scene_error("[[lights]]\ntype = \"directional\"\nintensity = 9007199254740993\n"),
                StartsWith("scene.toml: lights[0].intensity: 9007199254740993 is beyond 1e9"));
}

// More lights than a ShadowSystem takes is the scene file's error, naming it and the key
// (issue 32, item 10), not the library's later "ShadowSystem::set_lights: 301 lights".
TEST(SceneErrors, MoreLightsThanAShadowSystemTakes) {
    std::string text;
    for (int i = 0; i < 301; ++i) text += "[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\n";
    EXPECT_EQ(scene_error(text), "scene.toml: lights: 301 lights, at most 256 (the lights one ShadowSystem takes)");
    std::string most;
    for (int i = 0; i < 256; ++i) most += "[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\n";
    EXPECT_EQ(testing::parse_scene_text(most).lights.size(), 256u);
}

TEST(SceneErrors, UnknownKeyListsTheValidOnes) {
    EXPECT_THAT(scene_error("[camera]\nfovy = 60\n"), HasSubstr("(expected eye, target, up, fov, near, far)"));
}

TEST(SceneErrors, ZeroLengthLightDirection) {
    EXPECT_EQ(scene_error("[[lights]]\ndirection = [0, 0, 0]\n"),
              "scene.toml: lights[0].direction: zero-length vector [0, 0, 0]");
}

TEST(SceneErrors, EyeEqualToTarget) {
    EXPECT_EQ(scene_error("[camera]\neye = [1, 2, 3]\ntarget = [1, 2, 3]\n"),
              "scene.toml: camera.target: equals eye [1, 2, 3], so the camera has no view direction");
}

TEST(SceneErrors, ZeroLengthUp) {
    EXPECT_EQ(scene_error("[camera]\nup = [0, 0, 0]\n"), "scene.toml: camera.up: zero-length vector [0, 0, 0]");
}

class FieldOfViewError : public ::testing::TestWithParam<const char*> {};

TEST_P(FieldOfViewError, IsRejected) {
    EXPECT_EQ(scene_error(std::string("[camera]\nfov = ") + GetParam() + "\n"),
              std::string("scene.toml: camera.fov: must be between 0 and 180 degrees (exclusive), got ") + GetParam());
}

INSTANTIATE_TEST_SUITE_P(SceneErrors, FieldOfViewError, ::testing::Values("0", "-5", "180", "200.5"));

TEST(SceneErrors, NearNotPositive) {
    EXPECT_EQ(scene_error("[camera]\nnear = 0\n"), "scene.toml: camera.near: must be > 0, got 0");
    EXPECT_EQ(scene_error("[camera]\nnear = -1\n"), "scene.toml: camera.near: must be > 0, got -1");
}

TEST(SceneErrors, FarNotBeyondNear) {
    EXPECT_EQ(scene_error("[camera]\nnear = 5\nfar = 5\n"),
              "scene.toml: camera.far: must be greater than near (5), got 5");
    EXPECT_EQ(scene_error("[camera]\nfar = 0.05\n"),
              "scene.toml: camera.far: must be greater than near (0.1), got 0.05");
}

struct ObjectErrorCase {
    const char* name;
    const char* toml;
    const char* message;
};

void PrintTo(const ObjectErrorCase& error_case, std::ostream* out) { *out << error_case.name; }

class ObjectError : public ::testing::TestWithParam<ObjectErrorCase> {};

TEST_P(ObjectError, IsRejectedWithTheOffendingValue) { EXPECT_EQ(scene_error(GetParam().toml), GetParam().message); }

INSTANTIATE_TEST_SUITE_P(
    SceneErrors, ObjectError,
    ::testing::Values(
        ObjectErrorCase{"plane_size", "[[objects]]\ntype = \"plane\"\nsize = [0, 4]\n",
                        "scene.toml: objects[0].size: every component must be > 0, got [0, 4]"},
        ObjectErrorCase{"box_size", "[[objects]]\ntype = \"box\"\nsize = [1, -1, 1]\n",
                        "scene.toml: objects[0].size: every component must be > 0, got [1, -1, 1]"},
        ObjectErrorCase{"sphere_radius", "[[objects]]\ntype = \"sphere\"\nradius = 0\n",
                        "scene.toml: objects[0].radius: must be > 0, got 0"},
        ObjectErrorCase{"cylinder_radius", "[[objects]]\ntype = \"cylinder\"\nradius = -0.5\n",
                        "scene.toml: objects[0].radius: must be > 0, got -0.5"},
        ObjectErrorCase{"cylinder_height", "[[objects]]\ntype = \"cylinder\"\nheight = 0\n",
                        "scene.toml: objects[0].height: must be > 0, got 0"},
        ObjectErrorCase{"zero_scale", "[[objects]]\ntype = \"box\"\nscale = [1, 0, 1]\n",
                        "scene.toml: objects[0].scale: every component must be > 0, got [1, 0, 1]"},
        ObjectErrorCase{"negative_scale", "[[objects]]\ntype = \"box\"\nscale = -2\n",
                        "scene.toml: objects[0].scale: every component must be > 0, got [-2, -2, -2]"},
        ObjectErrorCase{
            "instance_scale",
            "[[objects]]\ntype = \"gltf\"\nfile = \"../gltf/quad.gltf\"\ninstances = [{}, { scale = [1, 1, 0] }]\n",
            "scene.toml: objects[0].instances[1].scale: every component must be > 0, got [1, 1, 0]"},
        ObjectErrorCase{"texture", "[[objects]]\ntype = \"box\"\ntexture = \"bricks\"\n",
                        "scene.toml: objects[0].texture: unknown procedural texture \"bricks\" (expected checker, "
                        "checker_holes or round_holes)"},
        ObjectErrorCase{"alpha_mode", "[[objects]]\ntype = \"box\"\nalpha_mode = \"cutout\"\n",
                        "scene.toml: objects[0].alpha_mode: unknown alpha mode \"cutout\" (expected opaque, mask or "
                        "blend)"},
        ObjectErrorCase{"alpha_cutoff", "[[objects]]\ntype = \"box\"\nalpha_cutoff = 1.5\n",
                        "scene.toml: objects[0].alpha_cutoff: must be between 0 and 1, got 1.5"},
        ObjectErrorCase{"roughness", "[[objects]]\ntype = \"box\"\nroughness = -0.1\n",
                        "scene.toml: objects[0].roughness: must be between 0 and 1, got -0.1"},
        ObjectErrorCase{"negative_emissive", "[[objects]]\ntype = \"box\"\nemissive = [0, -2, 1]\n",
                        "scene.toml: objects[0].emissive: components must be >= 0, got [0, -2, 1]"},
        ObjectErrorCase{"negative_colour", "[[objects]]\ntype = \"box\"\ncolor = [1, -1, 1]\n",
                        "scene.toml: objects[0].color: components must be >= 0 and alpha at most 1, got [1, -1, 1, 1]"},
        ObjectErrorCase{"gltf_without_file", "[[objects]]\ntype = \"gltf\"\n",
                        "scene.toml: objects[0].file: missing (a string is required)"},
        ObjectErrorCase{"empty_instances",
                        "[[objects]]\ntype = \"gltf\"\nfile = \"../gltf/quad.gltf\"\ninstances = []\n",
                        "scene.toml: objects[0].instances: empty array (leave the key out for one instance at the "
                        "object's transform)"}),
    [](const auto& test_info) { return std::string(test_info.param.name); });

TEST(SceneErrors, UnknownLightType) {
    EXPECT_EQ(scene_error("[[lights]]\ntype = \"area\"\n"),
              "scene.toml: lights[0].type: unknown light type \"area\" (expected directional, spot or point)");
}

TEST(SceneErrors, LightValueRanges) {
    EXPECT_EQ(scene_error("[[lights]]\nintensity = -1\n"), "scene.toml: lights[0].intensity: must be >= 0, got -1");
    EXPECT_EQ(scene_error("[[lights]]\nangular_diameter = 50\n"),
              "scene.toml: lights[0].angular_diameter: must be between 0 and 45 degrees, got 50");
    EXPECT_EQ(scene_error("[ambient]\ncolor = [0, -0.5, 0]\n"),
              "scene.toml: ambient.color: components must be >= 0, got [0, -0.5, 0]");
}

TEST(SceneErrors, MissingGltfFileNamesTheObjectAndThePath) {
    const std::string message = scene_error("[[objects]]\ntype = \"gltf\"\nfile = \"models/none.gltf\"\n");
    EXPECT_THAT(message, StartsWith("scene.toml: objects[0].file: "));
    EXPECT_THAT(message, HasSubstr("models/none.gltf: file not found"));
}

TEST(SceneErrors, GltfWithUnsupportedExtension) {
    EXPECT_THAT(scene_error("[[objects]]\ntype = \"gltf\"\nfile = \"tree.obj\"\n"),
                HasSubstr("tree.obj: unsupported model extension \".obj\" (expected .gltf or .glb)"));
}

TEST(SceneErrors, BrokenGltfIsReportedThroughTheObject) {
    const std::string message =
        scene_error("[[objects]]\ntype = \"gltf\"\nfile = \"../gltf/index_out_of_range.gltf\"\n");
    EXPECT_THAT(message, StartsWith("scene.toml: objects[0].file: "));
    EXPECT_THAT(message, HasSubstr("index 7"));
}

}  // namespace
}  // namespace penumbra

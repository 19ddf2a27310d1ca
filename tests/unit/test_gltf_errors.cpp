// Malformed glTF files are InputErrors naming the file and the offending part, never a
// crash or an out-of-bounds read (tests/data/gltf/make_fixtures.py writes these files).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "penumbra/scene/loader.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

using ::testing::HasSubstr;
using testing::input_error_message;
using ::testing::StartsWith;
using testing::test_data;

std::string gltf_error(const std::string& name) {
    const std::string path = test_data("gltf/" + name).string();
    const std::string message = input_error_message([&] {
        Scene scene;
        append_gltf(scene, path, {glm::mat4{1.0f}});
    });
    EXPECT_THAT(message, StartsWith(path + ": "));
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
}

struct GltfErrorCase {
    const char* file;
    const char* expected;  // a distinctive part of the message
};

void PrintTo(const GltfErrorCase& error_case, std::ostream* out) { *out << error_case.file; }

class GltfError : public ::testing::TestWithParam<GltfErrorCase> {};

TEST_P(GltfError, IsAnInputErrorNamingTheProblem) {
    EXPECT_THAT(gltf_error(GetParam().file), HasSubstr(GetParam().expected));
}

INSTANTIATE_TEST_SUITE_P(
    GltfErrors, GltfError,
    ::testing::Values(
        GltfErrorCase{"does_not_exist.gltf", "file not found"}, GltfErrorCase{"malformed.gltf", "cannot load glTF: "},
        GltfErrorCase{"truncated.glb", "the GLB header says 1204 bytes, the file has 602 (truncated?)"},
        GltfErrorCase{"truncated_buffer.gltf",
                      "buffers[0].uri \"truncated.bin\": the file is not the buffer's byteLength (140 bytes) long"},
        GltfErrorCase{"missing_buffer.gltf", "does_not_exist.bin"},
        GltfErrorCase{"basisu_required.gltf",
                      "extensionsRequired: the file requires KHR_texture_basisu (an image format), "
                      "which Penumbra does not support"},
        GltfErrorCase{"accessor_out_of_range.gltf",
                      "attributes.POSITION (accessors[0]): 1000 elements of 12 bytes at offset 0 (stride 12) overrun "
                      "bufferViews[0] of 48 bytes"},
        GltfErrorCase{"accessor_offset_out_of_range.gltf", "attributes.NORMAL (accessors[1]): 4 elements"},
        GltfErrorCase{"buffer_view_out_of_range.gltf", "bufferViews[3] spans bytes 128..4224 of a buffer of 140 bytes"},
        GltfErrorCase{"index_out_of_range.gltf",
                      "meshes[0].primitives[0].indices: index 7 at position 5 is out of range (the primitive has 4 "
                      "vertices)"},
        GltfErrorCase{"missing_accessor.gltf", "accessor 42 does not exist"},
        GltfErrorCase{"no_position.gltf", "no POSITION attribute"},
        GltfErrorCase{"wrong_position_type.gltf",
                      "3 components of UNSIGNED_SHORT needs the KHR_mesh_quantization extension, which the file does "
                      "not declare"},
        GltfErrorCase{"unknown_mode.gltf", "meshes[0].primitives[0].mode: unknown primitive mode 9"},
        GltfErrorCase{"node_cycle.gltf", "nodes[1]: node is its own ancestor (the node hierarchy has a cycle)"},
        GltfErrorCase{"node_two_parents.gltf", "nodes[2]: is a child of both nodes[0] and nodes[1]"},
        GltfErrorCase{"node_listed_twice.gltf", "nodes[0].children: lists node 1 twice"},
        GltfErrorCase{"node_own_child.gltf", "nodes[0]: node is its own child"},
        GltfErrorCase{"root_listed_twice.gltf", "scenes[0].nodes: lists node 0 twice"},
        GltfErrorCase{"root_with_parent.gltf", "scenes[0].nodes: node 1 is a root but also a child of nodes[0]"},
        GltfErrorCase{"byte_stride_negative.gltf", "bufferViews[0].byteStride: expected an integer >= 4, got -4"},
        GltfErrorCase{"mesh_not_an_index.gltf", "nodes[0].mesh: expected an index (an integer >= 0), got \"zero\""},
        GltfErrorCase{"scene_not_an_index.gltf", ": scene: expected an index (an integer >= 0), got \"hello\""},
        GltfErrorCase{"missing_material.gltf", "material 5 does not exist"},
        GltfErrorCase{"bad_alpha_mode.gltf",
                      "materials[0].alphaMode: expected one of OPAQUE, MASK, BLEND, got \"CUTOUT\""},
        GltfErrorCase{"partial_triangle.gltf", "5 vertex indices do not form whole triangles"},
        GltfErrorCase{"missing_image.gltf", "images[0] \"missing.png\": could not be read or decoded"}),
    [](const auto& test_info) {
        std::string name = test_info.param.file;
        return name.substr(0, name.find('.'));
    });

TEST(GltfErrors, UnsupportedExtension) {
    EXPECT_THAT(gltf_error("make_fixtures.py"), HasSubstr("unsupported model extension \".py\""));
}

// One rule for images that did not load: the ones Penumbra reads stop the load (above:
// a base colour texture), every other one is named in a warning with what refers to it.
TEST(GltfErrors, AnImageThatIsNotReadIsNamedInAWarningNotRefused) {
    nlohmann::json model = nlohmann::json::parse(std::ifstream(test_data("gltf/missing_image.gltf")));
    nlohmann::json& material = model["materials"][0];
    material["normalTexture"] = material["pbrMetallicRoughness"]["baseColorTexture"];
    material["pbrMetallicRoughness"].erase("baseColorTexture");
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "penumbra_unread_missing_image.gltf";
    std::ofstream(file) << model.dump();
    Scene scene;
    append_gltf(scene, file, {glm::mat4{1.0f}});
    std::filesystem::remove(file);
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_THAT(scene.warnings[0], HasSubstr("images[0] \"missing.png\" could not be read (missing file?); Penumbra "
                                             "does not use it (normalTexture of materials[0])"));
    EXPECT_EQ(scene.instances.size(), 1u);
}

TEST(GltfErrors, FailedLoadLeavesTheSceneUntouched) {
    Scene scene;
    append_gltf(scene, test_data("gltf/quad.gltf"), {glm::mat4{1.0f}});
    // The first mesh, material and instance of this file load before its second mesh fails.
    const std::string message =
        input_error_message([&] { append_gltf(scene, test_data("gltf/second_mesh_broken.gltf"), {glm::mat4{1.0f}}); });
    EXPECT_THAT(message, HasSubstr("meshes[1].primitives[0].material: material 5 does not exist"));
    EXPECT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.instances.size(), 1u);
}

}  // namespace
}  // namespace penumbra

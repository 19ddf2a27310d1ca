// glTF values of the wrong JSON type or outside the range the glTF 2.0 specification gives
// them, which tinygltf would skip as absent or use as they are: one InputError naming the
// file and the JSON path, with what was expected and what was found.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "scene_test_support.hpp"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::input_error_message;
using ::testing::StartsWith;
using testing::test_data;

struct ValueCase {
    const char* name;
    const char* pointer;     // a JSON pointer into the quad fixture
    const char* value_json;  // the value put there
    const char* expected;    // the message after "<file>: "
};

void PrintTo(const ValueCase& value_case, std::ostream* out) { *out << value_case.name; }

class GltfValue : public ::testing::TestWithParam<ValueCase> {};

TEST_P(GltfValue, IsAnInputErrorNamingItsPath) {
    std::ifstream fixture(test_data("gltf/quad.gltf"));
    nlohmann::json document = nlohmann::json::parse(fixture);
    document[nlohmann::json::json_pointer(GetParam().pointer)] = nlohmann::json::parse(GetParam().value_json);
    const fs::path file = fs::temp_directory_path() /
                          ("penumbra_gltf_value_" + std::to_string(::getpid()) + "_" + GetParam().name + ".gltf");
    std::ofstream(file) << document.dump(1);
    const std::string message = input_error_message([&] {
        Scene scene;
        append_gltf(scene, file, {glm::mat4{1.0f}});
    });
    fs::remove(file);
    EXPECT_EQ(message, file.string() + ": " + GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(
    WrongTypesAndRanges, GltfValue,
    ::testing::Values(
        ValueCase{"translation_string", "/nodes/0/translation", R"(["1", 0, 0])",
                  R"(nodes[0].translation[0]: expected a number, got "1")"},
        ValueCase{"rotation_string", "/nodes/0/rotation", R"("spin")",
                  R"(nodes[0].rotation: expected an array of 4 numbers, got "spin")"},
        ValueCase{"rotation_outside_unit", "/nodes/0/rotation", "[0, 0, 0, 2]",
                  "nodes[0].rotation[3]: expected a number in [-1.0, 1.0], got 2"},
        ValueCase{"matrix_short", "/nodes/0/matrix", "[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0]",
                  "nodes[0].matrix: expected an array of 16 numbers, got [1,0,0,0,0,1,0,0,0,0,1,0,0,0,0]"},
        ValueCase{"base_colour_string", "/materials/0/pbrMetallicRoughness/baseColorFactor", R"("red")",
                  R"(materials[0].pbrMetallicRoughness.baseColorFactor: expected an array of 4 numbers, got "red")"},
        ValueCase{"base_colour_above_one", "/materials/0/pbrMetallicRoughness/baseColorFactor", "[1.5, 0, 0, 1]",
                  "materials[0].pbrMetallicRoughness.baseColorFactor[0]: expected a number in [0.0, 1.0], got 1.5"},
        ValueCase{"alpha_mode_number", "/materials/0/alphaMode", "1",
                  "materials[0].alphaMode: expected one of OPAQUE, MASK, BLEND, got 1"},
        ValueCase{"double_sided_string", "/materials/0/doubleSided", R"("yes")",
                  R"(materials[0].doubleSided: expected true or false, got "yes")"},
        ValueCase{"alpha_cutoff_negative", "/materials/0/alphaCutoff", "-5",
                  "materials[0].alphaCutoff: expected a number >= 0.0, got -5"},
        ValueCase{"light_range_zero", "/extensions",
                  R"({"KHR_lights_punctual": {"lights": [{"type": "point", "range": 0}]}})",
                  "extensions.KHR_lights_punctual.lights[0].range: expected a number > 0.0, got 0"},
        ValueCase{"light_without_type", "/extensions", R"({"KHR_lights_punctual": {"lights": [{"intensity": 2}]}})",
                  "extensions.KHR_lights_punctual.lights[0].type: missing (directional, point or spot)"},
        ValueCase{"spot_inner_beyond_outer", "/extensions",
                  R"({"KHR_lights_punctual": {"lights": [{"type": "spot",
                      "spot": {"innerConeAngle": 0.6, "outerConeAngle": 0.5}}]}})",
                  "extensions.KHR_lights_punctual.lights[0].spot.innerConeAngle: expected less than "
                  "outerConeAngle (0.5), got 0.6"},
        ValueCase{"sampler_wrap", "/samplers", R"([{"wrapS": 5}])",
                  "samplers[0].wrapS: expected one of 33071, 33648, 10497, got 5"},
        ValueCase{"asset_version_one", "/asset/version", R"("1.0")",
                  R"(asset.version: Penumbra reads glTF 2.x files, this one is version "1.0")"}),
    [](const ::testing::TestParamInfo<ValueCase>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace penumbra

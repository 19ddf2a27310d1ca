// The tools' preview reads glTF's shading inputs: COLOR_0 multiplies the base colour, the
// metallic-roughness texture multiplies the factors, the occlusion texture darkens the
// ambient light. Each is checked against an equivalent model without it (same image).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <string>

#include "cli_runner.hpp"
#include "gltf_writer.hpp"
#include "image/png_io.hpp"

namespace {

using penumbra::testing::GltfTestNode;
using penumbra::testing::GltfTestPrimitive;
using penumbra::testing::test_box;
using penumbra::testing::write_test_gltf;

constexpr const char* kScene = R"(
[camera]
eye = [3.0, 2.5, 4.0]
target = [0.0, 0.5, 0.0]

[[lights]]
type = "directional"
direction = [-0.5, -1.0, -0.2]

[[objects]]
type = "plane"
size = [20.0, 20.0]

[[objects]]
type = "gltf"
file = "model.gltf"
)";

nlohmann::json material(const nlohmann::json& pbr) { return {{"pbrMetallicRoughness", pbr}}; }

// Renders the scene with a model of one node; returns the colour image's samples.
class Preview : public penumbra::testing::CliTest {
protected:
    std::vector<uint16_t> render(const GltfTestNode& node, const std::string& name,
                                 const std::vector<std::string>& images = {}) const {
        write_test_gltf(dir_ / "model.gltf", {node}, images);
        write_file("scene.toml", kScene);
        const auto result = run("render scene.toml --validate --width 64 --height 48 -o " + name + ".png");
        EXPECT_EQ(result.exit_code, 0) << name << ": " << result.err;
        return penumbra::read_png(dir_ / (name + ".png")).samples;
    }

    // One texel of RGBA8 as a PNG beside the model.
    void write_texel(const std::string& name, uint8_t r, uint8_t g, uint8_t b) const {
        penumbra::write_png_rgba8(dir_ / name, 1, 1, {r, g, b, 255});
    }
};

// How two colour images differ: the largest per-sample difference, and how many samples
// differ by more than 8 levels with the mean signed difference (a - b) over those.
struct Difference {
    int largest = 0;
    size_t changed = 0;
    double mean_change = 0.0;
};

Difference difference(const std::vector<uint16_t>& a, const std::vector<uint16_t>& b) {
    EXPECT_EQ(a.size(), b.size());
    Difference result;
    double sum = 0.0;
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        const int d = int(a[i]) - int(b[i]);
        result.largest = std::max(result.largest, std::abs(d));
        if (std::abs(d) <= 8) continue;
        ++result.changed;
        sum += d;
    }
    result.mean_change = result.changed ? sum / static_cast<double>(result.changed) : 0.0;
    return result;
}

TEST_F(Preview, PreviewMultipliesTheBaseColourByColor0) {
    GltfTestPrimitive coloured = test_box({0.0f, 0.5f, 0.0f}, 0.5f);
    coloured.colors.assign(coloured.positions.size(), glm::vec4{0.8f, 0.2f, 0.4f, 1.0f});
    const auto by_vertex = render({"Box", "", {coloured}, material({{"metallicFactor", 0.0}})}, "vertex");
    const auto by_factor = render({"Box",
                                   "",
                                   {test_box({0.0f, 0.5f, 0.0f}, 0.5f)},
                                   material({{"metallicFactor", 0.0}, {"baseColorFactor", {0.8, 0.2, 0.4, 1.0}}})},
                                  "factor");
    const auto white =
        render({"Box", "", {test_box({0.0f, 0.5f, 0.0f}, 0.5f)}, material({{"metallicFactor", 0.0}})}, "white");
    EXPECT_LE(difference(by_vertex, by_factor).largest, 1);
    // The box covers a few hundred pixels; COLOR_0 darkens green and blue there.
    const Difference coloured_change = difference(white, by_vertex);
    EXPECT_GT(coloured_change.changed, 200u) << "COLOR_0 was not applied";
    EXPECT_GT(coloured_change.mean_change, 0.0);
}

TEST_F(Preview, PreviewReadsTheMetallicRoughnessTexture) {
    // Roughness in G (255: the factor as is), metallic in B (0: a dielectric whatever the factor).
    write_texel("mr.png", 0, 255, 0);
    const auto box = test_box({0.0f, 0.5f, 0.0f}, 0.5f);
    const auto textured = render(
        {"Box",
         "",
         {box},
         material({{"metallicFactor", 1.0}, {"roughnessFactor", 0.5}, {"metallicRoughnessTexture", {{"index", 0}}}})},
        "textured", {"mr.png"});
    const auto dielectric =
        render({"Box", "", {box}, material({{"metallicFactor", 0.0}, {"roughnessFactor", 0.5}})}, "dielectric");
    const auto metal =
        render({"Box", "", {box}, material({{"metallicFactor", 1.0}, {"roughnessFactor", 0.5}})}, "metal");
    EXPECT_LE(difference(textured, dielectric).largest, 1);
    // A metal of this base colour reflects no diffuse light: darker than the dielectric.
    const Difference metal_change = difference(dielectric, metal);
    EXPECT_GT(metal_change.changed, 200u) << "the metallic-roughness texture was not applied";
    EXPECT_GT(metal_change.mean_change, 0.0);
}

TEST_F(Preview, PreviewDarkensAmbientLightByTheOcclusionTexture) {
    write_texel("ao.png", 0, 0, 0);
    const auto box = test_box({0.0f, 0.5f, 0.0f}, 0.5f);
    const nlohmann::json pbr = {{"metallicFactor", 0.0}};
    const auto none = render({"Box", "", {box}, material(pbr)}, "none");
    nlohmann::json occluded = material(pbr);
    occluded["occlusionTexture"] = {{"index", 0}, {"strength", 0.0}};
    EXPECT_LE(difference(render({"Box", "", {box}, occluded}, "strength0", {"ao.png"}), none).largest, 1);
    occluded["occlusionTexture"]["strength"] = 1.0;
    // Only the ambient term goes: the box's shadowed sides darken, its sunlit ones barely.
    const Difference occluded_change = difference(render({"Box", "", {box}, occluded}, "strength1", {"ao.png"}), none);
    EXPECT_GT(occluded_change.changed, 50u);
    EXPECT_LT(occluded_change.mean_change, 0.0);
}

}  // namespace

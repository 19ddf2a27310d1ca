// `penumbra bench` with spot and point lights: the report lists every shadowed local light
// (type, layers, resolution, near plane, draws and triangles equal to what the scene
// submits), times their pass as "shadow_local" like the other passes, and follows the
// local shadow budget. Timings are only checked for being present and positive.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "cli_runner.hpp"
#include "penumbra/scene/loader.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "scene/forest_scene.hpp"

using nlohmann::json;
using penumbra::testing::read_text;
using penumbra::testing::RunResult;

namespace {

// Four trees, two spots aimed down at trees, one point light: lights 1, 2 and 3.
constexpr const char* kForestSpec = "builtin:forest?count=4&spots=2&points=1";
// Small and quick on lavapipe; --validate makes any validation message fail the run.
constexpr const char* kSmall =
    " --frames 3 --warmup 1 --width 96 --height 64 --shadow-resolution 512 --local-shadow-resolution 64 --validate";

// Triangles the renderer submits for one pass over every instance, counted from the meshes.
uint64_t triangles_submitted_by(const penumbra::Scene& scene) {
    uint64_t triangles = 0;
    for (const penumbra::Instance& instance : scene.instances) {
        triangles += scene.meshes[instance.mesh].indices.size() / 3;
    }
    return triangles;
}

class BenchLocalLights : public penumbra::testing::CliTest {
protected:
    // Runs `bench` on the forest with `options` and --json; returns the parsed report and
    // keeps the run's output in `last_`.
    json run_report(const std::string& options) {
        last_ = run(std::string("bench '") + kForestSpec + "'" + kSmall + options + " --json report.json");
        EXPECT_EQ(last_.exit_code, 0) << last_.err;
        if (last_.exit_code != 0) return json::object();
        return json::parse(read_text(dir_ / "report.json"));
    }

    RunResult last_;
};

void expect_counts(const json& counts, uint64_t expected) {
    EXPECT_EQ(counts["min"].get<uint64_t>(), expected);
    EXPECT_EQ(counts["max"].get<uint64_t>(), expected);
    EXPECT_DOUBLE_EQ(counts["mean"].get<double>(), static_cast<double>(expected));
}

// Without culling every layer of every light submits every draw, so each light's triangles
// are its layer count times the scene's triangles, counted independently from the meshes.
TEST_F(BenchLocalLights, ReportsEveryShadowedLightWithItsLayersAndTriangles) {
    const penumbra::Scene scene = penumbra::load_scene(kForestSpec);
    const uint64_t triangles = triangles_submitted_by(scene);
    const json report = run_report(" --no-cull");
    ASSERT_FALSE(report.empty());

    const json& local = report["local_shadows"];
    ASSERT_EQ(local["shadowed_lights"].get<int>(), 3) << local.dump();
    EXPECT_EQ(local["layers"].get<int>(), 1 + 1 + 6);
    const std::vector<std::tuple<int, std::string, uint64_t>> expected{{1, "spot", 1}, {2, "spot", 1}, {3, "point", 6}};
    ASSERT_EQ(local["lights"].size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        const auto& [index, type, layers] = expected[i];
        const json& light = local["lights"][i];
        SCOPED_TRACE(light.dump());
        EXPECT_EQ(light["light"].get<int>(), index);
        EXPECT_EQ(light["type"].get<std::string>(), type);
        EXPECT_EQ(light["layers"].get<uint64_t>(), layers);
        expect_counts(light["resolution"], 64);
        EXPECT_GE(light["near_plane"].get<double>(), 0.05 - 1e-6);
        // The nearest caster is no farther than the ground below the light.
        EXPECT_LE(light["near_plane"].get<double>(), scene.lights[index].position.y + 1e-3);
        expect_counts(light["draws"], layers * scene.instances.size());
        expect_counts(light["triangles"], layers * triangles);
    }
    EXPECT_EQ(report["settings"]["local_shadow_budget"], 8);
    EXPECT_EQ(report["settings"]["local_shadow_resolution"], 64);

    const json& shadow_local = report["gpu_ms"]["shadow_local"];
    ASSERT_TRUE(shadow_local.is_object()) << report["gpu_ms"].dump();
    EXPECT_GT(shadow_local["median"].get<double>(), 0.0);
    EXPECT_GT(shadow_local["min"].get<double>(), 0.0);
    EXPECT_EQ(shadow_local["samples"].get<int>(), 3);
    // Cascades (4 x 512^2 D32) and the local lights' 8 layers of 64^2 D32, at least.
    EXPECT_GE(report["shadow_map_bytes"].get<uint64_t>(), uint64_t{4} * 512 * 512 * 4 + uint64_t{8} * 64 * 64 * 4);

    for (const char* needle :
         {"shadow_local", "3 shadowed spot/point light(s) (budget 8)", "point", "layers included"}) {
        EXPECT_NE(last_.out.find(needle), std::string::npos) << needle << " in\n" << last_.out;
    }
}

// Budget 1: only the first shadow-casting local light (a spot) has a map, with the renderer's
// one warning line. With culling on, the spot renders the ground and the tree it is aimed at
// but not the whole forest.
TEST_F(BenchLocalLights, BudgetOneReportsOnlyTheFirstLight) {
    const json report = run_report(" --local-shadow-budget 1");
    ASSERT_FALSE(report.empty());
    const json& local = report["local_shadows"];
    ASSERT_EQ(local["shadowed_lights"].get<int>(), 1) << local.dump();
    ASSERT_EQ(local["lights"].size(), 1u);
    EXPECT_EQ(local["lights"][0]["light"].get<int>(), 1);
    EXPECT_EQ(local["lights"][0]["type"].get<std::string>(), "spot");
    EXPECT_EQ(report["settings"]["local_shadow_budget"], 1);
    EXPECT_NE(last_.err.find("2 shadow-casting spot/point light(s) beyond the local shadow budget of 1"),
              std::string::npos)
        << last_.err;
    EXPECT_EQ(std::count(last_.err.begin(), last_.err.end(), '\n'), 1) << last_.err;

    const uint64_t triangles = triangles_submitted_by(penumbra::load_scene(kForestSpec));
    const uint64_t ground_and_tree = penumbra::kForestGroundTriangles + 900 + 88;  // crown, trunk
    const json& spot_triangles = local["lights"][0]["triangles"];
    EXPECT_GE(spot_triangles["min"].get<uint64_t>(), ground_and_tree);
    EXPECT_LT(spot_triangles["max"].get<uint64_t>(), triangles);
}

TEST_F(BenchLocalLights, WithoutLocalLightsThereIsNoLocalPass) {
    last_ = run(std::string("bench 'builtin:forest?count=4'") + kSmall + " --json report.json");
    ASSERT_EQ(last_.exit_code, 0) << last_.err;
    const json report = json::parse(read_text(dir_ / "report.json"));
    EXPECT_EQ(report["local_shadows"]["shadowed_lights"].get<int>(), 0);
    EXPECT_TRUE(report["local_shadows"]["lights"].empty());
    EXPECT_FALSE(report["gpu_ms"].contains("shadow_local"));
    EXPECT_EQ(last_.out.find("spot/point"), std::string::npos) << last_.out;
}

TEST_F(BenchLocalLights, BadLightCountIsOneLineAndExitTwo) {
    const std::string too_many = std::to_string(penumbra::kMaxLocalLights + 1);
    const RunResult result = run("bench 'builtin:forest?count=4&spots=" + too_many + "' --json report.json");
    expect_failure(result, 2,
                   "spots: expected an integer from 0 to " + std::to_string(penumbra::kMaxLocalLights) + ", got \"" +
                       too_many + "\"");
    EXPECT_FALSE(std::filesystem::exists(dir_ / "report.json"));
}

}  // namespace

// `penumbra compare --light N` for spot and point lights: the renderer's shadow term agrees
// with segments traced to the light point (a spot over a box, a point light in a room with
// a cube), a wrong shadow raises the error, and bad --light values fail with one line and
// exit code 2.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "cli_runner.hpp"
#include "compare/compare_job.hpp"
#include "render_fixture.hpp"

namespace penumbra::testing {
namespace {

// The spot over a box of tests/gpu/test_local_lights.cpp (kSpotScene).
const char* kSpotScene = R"(
[camera]
eye = [0.0, 12.0, 6.0]
target = [0.0, 0.0, 0.0]
fov = 55.0
far = 60.0

[[lights]]
type = "spot"
position = [0.8, 6.0, 0.5]
direction = [-0.1, -1.0, 0.05]
inner_angle = 33.0
outer_angle = 35.0
range = 25.0
radius = 0.0
intensity = 40.0

[[objects]]
type = "plane"
size = [30.0, 30.0]

[[objects]]
type = "box"
size = [1.5, 0.5, 1.0]
translation = [0.0, 2.0, 0.0]
)";

// A closed 6 x 4 x 6 m room seen from a corner, a point light near the opposite corner and
// a 1.2 m cube standing on the floor between them, its shadow on the floor toward the camera.
const char* kRoomScene = R"(
[camera]
eye = [2.7, 3.6, 2.7]
target = [-3.0, 0.0, -3.0]
fov = 80.0
near = 0.05
far = 30.0

[[lights]]
type = "point"
position = [-2.2, 3.0, -2.0]
range = 15.0
radius = 0.0
intensity = 30.0

[[objects]]
type = "box"
size = [6.4, 0.2, 6.4]
translation = [0.0, -0.1, 0.0]
[[objects]]
type = "box"
size = [6.4, 0.2, 6.4]
translation = [0.0, 4.1, 0.0]
[[objects]]
type = "box"
size = [0.2, 4.0, 6.0]
translation = [3.1, 2.0, 0.0]
[[objects]]
type = "box"
size = [0.2, 4.0, 6.0]
translation = [-3.1, 2.0, 0.0]
[[objects]]
type = "box"
size = [6.0, 4.0, 0.2]
translation = [0.0, 2.0, 3.1]
[[objects]]
type = "box"
size = [6.0, 4.0, 0.2]
translation = [0.0, 2.0, -3.1]

[[objects]]
type = "box"
size = 1.2
translation = [-0.6, 0.6, -0.7]
)";

RenderSettings hard_settings() {
    RenderSettings settings = small_settings(240, 180);
    settings.shadow.filter.mode = ShadowFilter::Hard;
    return settings;
}

compare::CompareResult compare_light(const std::string& text, const RenderSettings& settings, int32_t light,
                                     uint32_t rays = 1) {
    compare::CompareJob job;
    job.rays = rays;
    job.light = light;
    job.render.device.validation = true;  // any message throws ValidationFailure
    return compare::compare_prepared(job, {scene_from_toml(text), settings}, "test.toml");
}

void print_result(const char* name, const compare::CompareResult& result) {
    std::printf(
        "%s: %llu evaluated, %llu outside the light, %llu boundary px; false shadow %.3f%% (%.3f%% outside "
        "edges), false lit %.3f%% (%.3f%% outside edges)\n",
        name, static_cast<unsigned long long>(result.pixels.evaluated),
        static_cast<unsigned long long>(result.pixels.outside_light),
        static_cast<unsigned long long>(result.hard.boundary_pixels), result.hard.false_shadow.percent(),
        result.hard.false_shadow_outside_edges.percent(), result.hard.false_lit.percent(),
        result.hard.false_lit_outside_edges.percent());
}

void expect_agreement(const compare::CompareResult& result) {
    EXPECT_GT(result.pixels.evaluated, 5000u);
    EXPECT_GT(result.hard.false_lit.truth_pixels, 300u) << "no shadow in the reference";
    EXPECT_GT(result.hard.boundary_pixels, 80u);
    EXPECT_LE(result.hard.false_shadow_outside_edges.percent(), 0.5);
    EXPECT_LE(result.hard.false_lit_outside_edges.percent(), 0.5);
    EXPECT_LT(result.stability.frames, 2u) << "stability applies to the sun's cascades only";
    EXPECT_FALSE(result.stability_note.empty());
}

TEST(CompareLocalLight, SpotOverABoxMatchesTheTracedSegments) {
    const compare::CompareResult result = compare_light(kSpotScene, hard_settings(), 0);
    print_result("spot", result);
    ASSERT_TRUE(result.local_light.has_value());
    EXPECT_EQ(result.local_light->type, LightType::Spot);
    EXPECT_GT(result.pixels.outside_light, 1000u) << "the ground outside the cone is not evaluated";
    expect_agreement(result);
}

TEST(CompareLocalLight, PointLightInARoomMatchesTheTracedSegments) {
    const compare::CompareResult result = compare_light(kRoomScene, hard_settings(), 0);
    print_result("point", result);
    ASSERT_TRUE(result.local_light.has_value());
    EXPECT_EQ(result.local_light->type, LightType::Point);
    expect_agreement(result);
}

TEST(CompareLocalLight, NoDepthBiasRaisesFalseShadow) {
    RenderSettings settings = hard_settings();
    settings.shadow.bias.constant = 0.0f;
    settings.shadow.bias.slope = 0.0f;
    settings.shadow.bias.normal_offset = 0.0f;
    const compare::CompareResult result = compare_light(kSpotScene, settings, 0);
    print_result("spot without bias", result);
    EXPECT_GT(result.hard.false_shadow_outside_edges.percent(), 2.0) << "no acne without any bias?";
}

TEST(CompareLocalLight, HugeNormalOffsetRaisesFalseLit) {
    RenderSettings settings = hard_settings();
    settings.shadow.bias.normal_offset = 10.0f;  // the largest the settings allow
    const compare::CompareResult result = compare_light(kRoomScene, settings, 0);
    print_result("point with a huge normal offset", result);
    EXPECT_GT(result.hard.false_lit_outside_edges.percent(), 2.0) << "the contact shadow should detach";
}

TEST(CompareLocalLight, AreaLightSoftReferenceHasAPenumbra) {
    std::string text = kSpotScene;
    const std::string key = "radius = 0.0";
    text.replace(text.find(key), key.size(), "radius = 0.3");
    RenderSettings settings = small_settings(240, 180);
    settings.shadow.filter.mode = ShadowFilter::Pcss;
    const compare::CompareResult result = compare_light(text, settings, 0, 16);
    std::printf("pcss spot, radius 0.3: penumbra width %.2f px (reference %.2f), mean |error| %.4f\n",
                result.soft.penumbra_width_render_px, result.soft.penumbra_width_reference_px,
                result.soft.mean_abs_error);
    EXPECT_GT(result.soft.penumbra_width_reference_px, 2.0);
    EXPECT_LT(result.soft.mean_abs_error, 0.05);
}

// The command line: bad --light values fail before anything is rendered or written.
class CompareLightCli : public CliTest {
protected:
    void expect_one_line_failure(const std::string& arguments, const std::string& needle) const {
        expect_failure(run(arguments), 2, needle);
        EXPECT_FALSE(std::filesystem::exists(dir_ / "out")) << "output left behind";
    }
};

TEST_F(CompareLightCli, IndexOutOfRangeIsRejected) {
    write_file("spot.toml", kSpotScene);
    expect_one_line_failure("compare spot.toml --light 1 --out-dir out", "--light 1");
}

TEST_F(CompareLightCli, NegativeOrNonNumericIndexIsRejected) {
    write_file("spot.toml", kSpotScene);
    expect_one_line_failure("compare spot.toml --light=-1 --out-dir out", "--light");
    expect_one_line_failure("compare spot.toml --light sun --out-dir out", "--light");
}

TEST_F(CompareLightCli, LightWithoutShadowsIsRejected) {
    write_file("spot.toml", std::string(kSpotScene) +
                                "\n[[lights]]\ntype = \"point\"\nposition = [0.0, 3.0, 0.0]\n"
                                "cast_shadows = false\n");
    expect_one_line_failure("compare spot.toml --light 1 --out-dir out", "casts no shadows");
}

TEST_F(CompareLightCli, LightBeyondTheShadowBudgetIsRejected) {
    write_file("spot.toml", kSpotScene);
    expect_one_line_failure("compare spot.toml --light 0 --local-shadow-budget 0 --out-dir out", "budget");
}

TEST_F(CompareLightCli, WritesTheReportNamingTheLight) {
    write_file("spot.toml", kSpotScene);
    const RunResult result = run("compare spot.toml --light 0 --width 96 --height 64 --rays 4 --out-dir out");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("spot light 0"), std::string::npos) << result.out;
    const std::string json = read_text(dir_ / "out" / "compare.json");
    EXPECT_NE(json.find("\"type\": \"spot\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"stability_note\": \"not measured"), std::string::npos) << json;
}

}  // namespace
}  // namespace penumbra::testing

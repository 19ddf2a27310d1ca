// `penumbra bench`: the JSON report (every pass timed, triangle counts equal to what the
// scene submits, culling lowering them), the ceiling modes, bad input, and the pure
// pieces behind it (statistics, camera and light paths, the forest scene). Timings are
// only checked for being present and positive: lavapipe's numbers mean nothing here.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "bench/bench_job.hpp"
#include "bench/paths.hpp"
#include "bench/statistics.hpp"
#include "cli_runner.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/scene/loader.hpp"
#include "scene/forest_scene.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using penumbra::testing::read_text;
using penumbra::testing::RunResult;

namespace {

constexpr const char* kForest = "'builtin:forest?count=30'";
// Small and quick on lavapipe; --validate makes any validation message fail the run.
constexpr const char* kSmall = " --frames 3 --warmup 1 --width 96 --height 64 --shadow-resolution 512 --validate";

// Triangles the renderer submits for one pass over every instance, counted from the meshes.
uint64_t triangles_submitted_by(const penumbra::Scene& scene) {
    uint64_t triangles = 0;
    for (const penumbra::Instance& instance : scene.instances) {
        triangles += scene.meshes[instance.mesh].indices.size() / 3;
    }
    return triangles;
}

class BenchCli : public penumbra::testing::CliTest {
protected:
    // Runs `bench` with --json and returns the parsed report (fails the test on error).
    json run_json(const std::string& arguments) const {
        const RunResult result = run("bench " + arguments + " --json report.json");
        EXPECT_EQ(result.exit_code, 0) << result.err;
        if (result.exit_code != 0) return json::object();
        return json::parse(read_text(dir_ / "report.json"));
    }

    void expect_usage_error(const std::string& arguments, const std::string& needle) const {
        expect_failure(run("bench " + arguments + " --json report.json"), 2, needle);
        EXPECT_FALSE(fs::exists(dir_ / "report.json"));
    }
};

void expect_positive_timings(const json& timings, const std::vector<std::string>& names) {
    for (const std::string& name : names) {
        SCOPED_TRACE(name);
        ASSERT_TRUE(timings.contains(name)) << timings.dump();
        EXPECT_GT(timings[name]["median"].get<double>(), 0.0);
        EXPECT_GT(timings[name]["min"].get<double>(), 0.0);
        EXPECT_GE(timings[name]["p95"].get<double>(), timings[name]["median"].get<double>());
        EXPECT_EQ(timings[name]["samples"].get<int>(), 3);
    }
}

TEST_F(BenchCli, ReportsEveryPassWithAPositiveTime) {
    const json report = run_json(std::string(kForest) + kSmall + " --cascades 3");
    ASSERT_FALSE(report.empty());
    EXPECT_EQ(report["schema"], "penumbra-bench/1");
    EXPECT_FALSE(report["device"]["name"].get<std::string>().empty());
    EXPECT_GT(report["device"]["timestamp_valid_bits"].get<int>(), 0);
    expect_positive_timings(report["gpu_ms"],
                            {"shadow_cascade_0", "shadow_cascade_1", "shadow_cascade_2", "lighting", "frame"});
    expect_positive_timings(report["cpu_ms"], {"cascade_setup", "culling", "recording", "submit_wait", "frame_wall"});
    EXPECT_EQ(report["frames_without_gpu_times"], 0);
    EXPECT_EQ(report["settings"]["cascades"], 3);
    EXPECT_GE(report["shadow_map_bytes"].get<uint64_t>(), uint64_t{512} * 512 * 3 * 4);
    ASSERT_EQ(report["cascades"].size(), 3u);
    EXPECT_TRUE(report["ceiling"].is_null());
}

// Contact shadows are traced inside the resolve: with them (deferred) every measured frame
// is rendered again with the trace's lights off and "contact" is the difference of the two
// `visibility` scopes, one sample per frame; the frames' other scopes are the first render's.
TEST_F(BenchCli, ReportsTheContactShadowsCostInsideTheResolve) {
    const json with = run_json(std::string(kForest) + kSmall + " --resolve deferred --contact-shadows");
    ASSERT_FALSE(with.empty());
    ASSERT_TRUE(with["gpu_ms"].contains("contact")) << with["gpu_ms"].dump();
    EXPECT_EQ(with["gpu_ms"]["contact"]["samples"], 3);
    EXPECT_EQ(with["gpu_ms"]["visibility"]["samples"], 3) << "the second render is not counted";
    const json without = run_json(std::string(kForest) + kSmall + " --resolve deferred");
    ASSERT_FALSE(without.empty());
    EXPECT_FALSE(without["gpu_ms"].contains("contact"));
}

// --shadow-cache: a still camera reuses every cascade after the first frame and draws
// nothing more (the forest is static); without it every texel is drawn every frame.
TEST_F(BenchCli, ShadowCacheReportsTheTexelsItDrawsAndCopies) {
    const json cached = run_json(std::string(kForest) + kSmall + " --shadow-cache --camera-path still");
    ASSERT_FALSE(cached.empty());
    EXPECT_EQ(cached["settings"]["shadow_cache"], true);
    EXPECT_EQ(cached["run"]["camera_path"], "still");
    const json uncached = run_json(std::string(kForest) + kSmall + " --camera-path still");
    ASSERT_FALSE(uncached.empty());
    ASSERT_EQ(cached["cascades"].size(), uncached["cascades"].size());
    for (size_t c = 0; c < cached["cascades"].size(); ++c) {
        const json& with = cached["cascades"][c];
        const json& without = uncached["cascades"][c];
        const uint64_t layer = uint64_t{512} * 512;
        EXPECT_EQ(without["texels_rendered"]["min"].get<uint64_t>(), layer) << "cascade " << c;
        EXPECT_EQ(without["cache_reused_frames"].get<uint64_t>(), 0u);
        EXPECT_EQ(with["texels_rendered"]["max"].get<uint64_t>(), 0u) << "the warm-up filled the cache";
        EXPECT_EQ(with["cache_reused_frames"].get<uint64_t>(), 3u) << "every measured frame";
    }
    expect_positive_timings(cached["gpu_ms"], {"lighting", "frame"});
}

// --toggle: every measured frame changes the filter live (a Resource change: the maps are
// made again in prepare()), under validation; the renderer's and the system's CPU costs are
// reported. What a renderer creates once cannot be toggled.
TEST_F(BenchCli, ToggledSettingsAreTimedLive) {
    const json report = run_json(std::string(kForest) + kSmall + " --toggle 'shadow.filter=\"pcss\"'");
    ASSERT_FALSE(report.empty());
    EXPECT_EQ(report["run"]["toggle"], "shadow.filter=\"pcss\"");
    expect_positive_timings(report["cpu_ms"], {"update_settings", "settings_rebuild"});
    fs::remove(dir_ / "report.json");
    expect_usage_error(std::string(kForest) + kSmall + " --toggle output.width=200", "cannot be toggled live");
    expect_usage_error(std::string(kForest) + kSmall + " --toggle shadow", "--toggle: expected TABLE.KEY=VALUE");
}

TEST_F(BenchCli, AnimatedDynamicInstancesAreDrawnOverTheCacheEveryFrame) {
    // Three dynamic crowns circling in view, a still camera: the static casters stay
    // cached; the movers are drawn every frame, and the static texels they covered last
    // frame are copied back from the cache (which holds every static texel since the
    // warm-up: nothing is stored while nothing static is redrawn).
    const json report = run_json(std::string("'builtin:forest?count=30&movers=3'") + kSmall +
                                 " --shadow-cache --camera-path still --animate-dynamic");
    ASSERT_FALSE(report.empty());
    EXPECT_EQ(report["run"]["animate_dynamic"], true);
    uint64_t dynamic_draws = 0;
    for (const json& cascade : report["cascades"]) {
        EXPECT_EQ(cascade["texels_rendered"]["max"].get<uint64_t>(), 0u) << "no static caster drawn again";
        if (cascade["draws"]["min"].get<uint64_t>() == 0) continue;
        dynamic_draws += cascade["draws"]["min"].get<uint64_t>();
        EXPECT_GT(cascade["texels_copied"]["min"].get<uint64_t>(), 0u) << "the static texels under the movers";
        EXPECT_LT(cascade["texels_copied"]["max"].get<uint64_t>(), uint64_t{2} * 512 * 512)
            << "only their footprints, not whole layers";
    }
    EXPECT_GT(dynamic_draws, 0u);
    expect_positive_timings(report["gpu_ms"], {"shadow_dynamic", "shadow_cache_restore"});
    EXPECT_FALSE(report["gpu_ms"].contains("shadow_cache_store"));
    // Frame by frame, for plots along the path: one value per measured frame.
    for (const char* scope : {"shadow_sun", "lighting", "frame"}) {
        ASSERT_TRUE(report["gpu_ms_per_frame"].contains(scope)) << scope;
        EXPECT_EQ(report["gpu_ms_per_frame"][scope].size(), 3u) << scope;
    }
}

TEST_F(BenchCli, PrintsATableOfMedianP95AndMin) {
    const RunResult result = run(std::string("bench ") + kForest + kSmall + " --camera-path flythrough");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_TRUE(result.err.empty()) << "no progress bar without a terminal: " << result.err;
    for (const char* needle : {"median ms", "p95 ms", "min ms", "shadow_cascade_0", "lighting", "frame_wall"}) {
        EXPECT_NE(result.out.find(needle), std::string::npos) << needle << " in\n" << result.out;
    }
}

// Face culling (--caster-culling) happens in the rasteriser: it changes no draw list.
TEST_F(BenchCli, WithoutCullingEveryCascadeGetsEveryTriangle) {
    const penumbra::Scene scene = penumbra::load_scene("builtin:forest?count=30");
    const uint64_t triangles = triangles_submitted_by(scene);
    const json report = run_json(std::string(kForest) + kSmall + " --no-cull --caster-culling front");
    ASSERT_FALSE(report.empty());
    EXPECT_EQ(report["settings"]["caster_culling"], "front");
    EXPECT_EQ(report["scene"]["triangles"].get<uint64_t>(), triangles);
    EXPECT_EQ(report["scene"]["instances"].get<size_t>(), scene.instances.size());
    ASSERT_EQ(report["cascades"].size(), 4u);
    // Per-cascade passes wrap a cascade around its layer (toroidal): its window is drawn
    // as one, two or four tiles, and without culling each tile draws every caster.
    for (const json& cascade : report["cascades"]) {
        const uint64_t least = cascade["triangles"]["min"].get<uint64_t>();
        EXPECT_EQ(least % triangles, 0u) << least;
        const uint64_t tiles = least / triangles;
        EXPECT_TRUE(tiles == 1 || tiles == 2 || tiles == 4) << tiles;
        EXPECT_EQ(cascade["draws"]["min"].get<size_t>(), tiles * scene.instances.size());
        EXPECT_LE(cascade["triangles"]["max"].get<uint64_t>(), 4 * triangles);
    }
}

TEST_F(BenchCli, PerCascadeCullingLowersTheSubmittedTriangles) {
    // The forest covers 400 m; the cascades cover 150 m from a camera inside it, so most
    // trees cast into no cascade and the near cascades see only a few. Compared with the
    // same frames unculled (the same tiles of the toroidal cascades: a caster that crosses
    // a cascade's wrap is drawn into both tiles either way).
    const json culled = run_json(std::string(kForest) + kSmall);
    const json unculled = run_json(std::string(kForest) + kSmall + " --no-cull");
    ASSERT_FALSE(culled.empty());
    ASSERT_FALSE(unculled.empty());
    double culled_total = 0.0, unculled_total = 0.0;
    for (const json& cascade : culled["cascades"]) culled_total += cascade["triangles"]["mean"].get<double>();
    for (const json& cascade : unculled["cascades"]) unculled_total += cascade["triangles"]["mean"].get<double>();
    EXPECT_LT(culled_total, 0.8 * unculled_total);
    EXPECT_LT(culled["cascades"][0]["triangles"]["mean"].get<double>(),
              unculled["cascades"][0]["triangles"]["mean"].get<double>());
}

TEST_F(BenchCli, MultiviewIsOneTimedShadowPass) {
    const json report = run_json(std::string(kForest) + kSmall + " --shadow-strategy multiview --light-path rotate");
    ASSERT_FALSE(report.empty());
    expect_positive_timings(report["gpu_ms"], {"shadow_multiview", "lighting", "frame"});
    EXPECT_FALSE(report["gpu_ms"].contains("shadow_cascade_0"));
    EXPECT_EQ(report["run"]["light_path"], "rotate");
}

// The layered strategy: the GPU's culling and the one layered pass are timed; the CPU
// culls no cascade, and the draws per cascade are the GPU's counts (read back a frame later).
TEST_F(BenchCli, LayeredIsAGpuCullAndOneLayeredPass) {
    const json report = run_json(std::string(kForest) + kSmall + " --shadow-strategy layered");
    ASSERT_FALSE(report.empty());
    expect_positive_timings(report["gpu_ms"], {"shadow_cull", "shadow_layered", "lighting", "frame"});
    EXPECT_FALSE(report["gpu_ms"].contains("shadow_cascade_0"));
    EXPECT_FALSE(report["gpu_ms"].contains("shadow_multiview"));
    for (const json& cascade : report["cascades"]) EXPECT_GT(cascade["draws"]["max"].get<double>(), 0.0);
}

TEST_F(BenchCli, TriangleCeilingCountsEveryTriangleInEveryCascade) {
    const uint64_t triangles = triangles_submitted_by(penumbra::load_scene("builtin:forest?count=30"));
    const json report = run_json(std::string(kForest) + kSmall + " --ceiling triangles");
    ASSERT_FALSE(report.empty());
    ASSERT_FALSE(report["ceiling"].is_null());
    EXPECT_EQ(report["ceiling"]["mode"], "triangles");
    EXPECT_EQ(report["ceiling"]["work_per_frame"].get<uint64_t>(), 4 * triangles);
    EXPECT_GT(report["ceiling"]["per_second"].get<double>(), 0.0);
    EXPECT_EQ(report["settings"]["shadow_resolution"], penumbra::bench::kCeilingShadowResolution);
    EXPECT_EQ(report["settings"]["cull_casters"], false);
}

TEST_F(BenchCli, TapCeilingTimesTheFullScreenPass) {
    const json report = run_json(std::string(kForest) + kSmall + " --ceiling taps --taps 8");
    ASSERT_FALSE(report.empty());
    expect_positive_timings(report["gpu_ms"], {"taps", "frame"});
    EXPECT_EQ(report["ceiling"]["work_per_frame"].get<uint64_t>(), uint64_t{96} * 64 * 8);
    EXPECT_GT(report["ceiling"]["per_second"].get<double>(), 0.0);
}

TEST_F(BenchCli, ComputeTapCeilingTimesTheSameTapsInCompute) {
    const json report = run_json(std::string(kForest) + kSmall + " --ceiling compute-taps --taps 8");
    ASSERT_FALSE(report.empty());
    expect_positive_timings(report["gpu_ms"], {"taps", "frame"});
    EXPECT_EQ(report["ceiling"]["mode"], "compute-taps");
    EXPECT_EQ(report["ceiling"]["work_per_frame"].get<uint64_t>(), uint64_t{96} * 64 * 8);
    EXPECT_GT(report["ceiling"]["per_second"].get<double>(), 0.0);
}

TEST_F(BenchCli, LayerStartCeilingTimesEveryWayToClearTheCascades) {
    const json report = run_json(std::string(kForest) + kSmall + " --ceiling layer-start --cascades 2");
    ASSERT_FALSE(report.empty());
    expect_positive_timings(report["gpu_ms"], {"start_render_pass_clear", "start_clear_image", "start_copy_cleared",
                                               "start_clear_quarter", "frame"});
    EXPECT_EQ(report["ceiling"]["mode"], "layer-start");
    EXPECT_EQ(report["ceiling"]["work_per_frame"].get<uint64_t>(), uint64_t{2} * 512 * 512);
}

TEST_F(BenchCli, DeferredResolveTimesThePrepassAndTheResolve) {
    const json report = run_json(std::string(kForest) + kSmall + " --resolve deferred");
    ASSERT_FALSE(report.empty());
    expect_positive_timings(report["gpu_ms"], {"prepass", "visibility", "lighting", "frame"});
    EXPECT_EQ(report["settings"]["resolve"], "deferred");
    // auto names the path it took: forward for the default hard filter without local lights.
    EXPECT_EQ(run_json(std::string(kForest) + kSmall)["settings"]["resolve"], "forward");
}

TEST_F(BenchCli, BadInputIsOneLineAndExitTwo) {
    expect_usage_error(std::string(kForest) + " --frames 0", "--frames");
    expect_usage_error(std::string(kForest) + " --camera-path spiral", "--camera-path: unknown value \"spiral\"");
    expect_usage_error(std::string(kForest) + " --light-path wobble", "--light-path");
    expect_usage_error(std::string(kForest) + " --ceiling pixels", "--ceiling");
    expect_usage_error("'builtin:forest?count=0'", "count");
    expect_usage_error("'builtin:forest?trees=5'", "expected count=N");
}

TEST(BenchStatistics, MedianPercentileAndMin) {
    std::vector<double> samples;
    for (int i = 100; i >= 1; --i) samples.push_back(i);
    const penumbra::bench::Summary summary = penumbra::bench::summarize(samples);
    EXPECT_DOUBLE_EQ(summary.median, 50.5);
    EXPECT_DOUBLE_EQ(summary.p95, 95.0);
    EXPECT_DOUBLE_EQ(summary.min, 1.0);
    EXPECT_DOUBLE_EQ(summary.max, 100.0);
    EXPECT_DOUBLE_EQ(summary.mean, 50.5);
    EXPECT_EQ(penumbra::bench::summarize({}).samples, 0u);
    EXPECT_DOUBLE_EQ(penumbra::bench::summarize({7.0}).p95, 7.0);
}

// The path's starting camera.
penumbra::Camera camera_at(const glm::vec3& eye, const glm::vec3& target) {
    penumbra::Camera camera;
    camera.eye = eye;
    camera.target = target;
    return camera;
}

TEST(BenchPaths, OrbitCirclesTheTargetAtTheCameraDistance) {
    const penumbra::Camera start = camera_at({0.0f, 20.0f, 90.0f}, {0.0f, 3.0f, 0.0f});
    using penumbra::bench::CameraPath;
    for (const float t : {0.0f, 0.25f, 0.5f, 0.9f}) {
        const penumbra::Camera camera = penumbra::bench::camera_on_path(CameraPath::Orbit, start, t, 100);
        EXPECT_NEAR(glm::length(camera.eye - camera.target), glm::length(start.eye - start.target), 1e-3f);
        EXPECT_EQ(camera.target, start.target);
        EXPECT_NEAR(camera.eye.y, start.eye.y, 1e-4f);
    }
    EXPECT_NEAR(penumbra::bench::camera_on_path(CameraPath::Orbit, start, 0.5f, 100).eye.z, -90.0f, 1e-3f);
}

TEST(BenchPaths, FlythroughKeepsTheViewDirectionAndMovesAhead) {
    const penumbra::Camera start = camera_at({0.0f, 20.0f, 90.0f}, {0.0f, 3.0f, 0.0f});
    using penumbra::bench::CameraPath;
    const penumbra::Camera half = penumbra::bench::camera_on_path(CameraPath::Flythrough, start, 0.5f, 100);
    EXPECT_NEAR(half.eye.z, 0.0f, 1e-3f);  // over the target halfway
    const glm::vec3 view = half.target - half.eye;
    const glm::vec3 start_view = start.target - start.eye;
    EXPECT_NEAR(glm::length(view - start_view), 0.0f, 1e-3f);
}

TEST(BenchPaths, WalkGoesAheadAtWalkingSpeedAndStillStaysPut) {
    const penumbra::Camera start = camera_at({0.0f, 1.7f, 10.0f}, {0.0f, 1.0f, 0.0f});
    using penumbra::bench::CameraPath;
    // Frame 30 of 60 at 1.4 m/s and 60 frames a second: 0.7 m ahead, looking the same way.
    const penumbra::Camera walked = penumbra::bench::camera_on_path(CameraPath::Walk, start, 0.5f, 60);
    EXPECT_NEAR(walked.eye.z, 10.0f - 0.7f, 1e-4f);
    EXPECT_NEAR(walked.eye.y, 1.7f, 1e-6f);
    EXPECT_NEAR(glm::length((walked.target - walked.eye) - (start.target - start.eye)), 0.0f, 1e-5f);
    const penumbra::Camera still = penumbra::bench::camera_on_path(CameraPath::Still, start, 0.7f, 60);
    EXPECT_EQ(still.eye, start.eye);
    EXPECT_EQ(still.target, start.target);
}

TEST(BenchPaths, RotatingSunKeepsItsElevation) {
    const glm::vec3 start = glm::normalize(glm::vec3{-0.4f, -1.0f, -0.3f});
    using penumbra::bench::LightPath;
    EXPECT_EQ(penumbra::bench::sun_on_path(LightPath::Fixed, start, 0.3f), start);
    const glm::vec3 turned = penumbra::bench::sun_on_path(LightPath::Rotate, start, 0.3f);
    EXPECT_NEAR(turned.y, start.y, 1e-6f);
    EXPECT_NEAR(glm::length(turned), 1.0f, 1e-5f);
    EXPECT_GT(glm::length(turned - start), 0.1f);
}

TEST(ForestScene, TrianglesAreAThousandPerTreePlusTheGround) {
    for (const uint32_t count : {1u, 100u, 1000u}) {
        const penumbra::Scene scene = penumbra::make_forest_scene(count);
        EXPECT_EQ(scene.meshes[0].indices.size() / 3, penumbra::kForestGroundTriangles);
        EXPECT_EQ(scene.triangle_count(),
                  uint64_t{penumbra::kForestTrianglesPerTree} * count + penumbra::kForestGroundTriangles);
        EXPECT_EQ(scene.meshes.size(), 4u) << "one mesh per kind, shared by the instances";
        EXPECT_EQ(scene.instances.size(), 1 + 3 * size_t{count});
    }
}

TEST(ForestScene, SpreadsOverTheWholeSquareAtAnyCount) {
    for (const uint32_t count : {10u, 1000u}) {
        const penumbra::Aabb bounds = penumbra::make_forest_scene(count).world_bounds();
        EXPECT_GT(bounds.max.x - bounds.min.x, 0.5f * penumbra::kForestSize);
        EXPECT_GT(bounds.max.z - bounds.min.z, 0.5f * penumbra::kForestSize);
    }
}

TEST(ForestScene, IsDeterministicAndParsesItsCount) {
    EXPECT_EQ(penumbra::make_forest_scene(50).instances[7].world, penumbra::make_forest_scene(50).instances[7].world);
    EXPECT_EQ(penumbra::load_scene("builtin:forest").instances.size(), 1 + 3 * size_t{penumbra::kForestDefaultCount});
    EXPECT_EQ(penumbra::load_scene("builtin:forest?count=12").instances.size(), 37u);
    EXPECT_THROW(penumbra::load_scene("builtin:forest?count=100001"), penumbra::InputError);
    EXPECT_THROW(penumbra::load_scene("builtin:forest?count=-3"), penumbra::InputError);
    EXPECT_THROW(penumbra::load_scene("builtin:default?count=3"), penumbra::InputError);
}

}  // namespace

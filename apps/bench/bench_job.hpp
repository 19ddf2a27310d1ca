#pragma once
// The library entry point behind `penumbra bench`: render N frames of a scene (after a
// warm-up) along a deterministic camera path, without reading images back, and
// collect per-pass GPU times (timestamp queries), per-step CPU times, and the draw and
// triangle counts of every cascade and every shadowed spot/point light. Ceiling modes
// measure the same pipeline state at its limits instead: triangle rate (the shadow pass
// at a tiny resolution, no culling) or texture sampling rate (a full-screen pass of N
// shadow-map taps). docs/bench.md.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench/paths.hpp"
#include "bench/statistics.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/settings_overrides.hpp"
#include "renderer/render_job.hpp"

namespace penumbra::bench {

enum class Ceiling {
    None,
    Triangles,    // shadow pass at kCeilingShadowResolution, every caster in every cascade
    Taps,         // full-screen fragment pass of `taps` comparison taps per pixel
    ComputeTaps,  // the same taps in a compute dispatch, one thread per pixel
    LayerStart,   // the ways to start (clear) the cascades' layers, timed side by side
};

inline constexpr ChoiceName<Ceiling> kCeilingChoices[] = {{"none", Ceiling::None},
                                                          {"triangles", Ceiling::Triangles},
                                                          {"taps", Ceiling::Taps},
                                                          {"compute-taps", Ceiling::ComputeTaps},
                                                          {"layer-start", Ceiling::LayerStart}};

constexpr bool is_tap_ceiling(Ceiling ceiling) { return ceiling == Ceiling::Taps || ceiling == Ceiling::ComputeTaps; }

// The smallest cascade map the library accepts: rasterisation costs little next to the
// triangles themselves.
constexpr uint32_t kCeilingShadowResolution = 512;
constexpr uint32_t kMaxTaps = 4096;

struct BenchJob {
    RenderJob render;  // scene, config, overrides, device, validation; output and aov unused
    uint32_t frames = 100;
    uint32_t warmup = 10;
    CameraPath camera_path = CameraPath::Orbit;
    LightPath light_path = LightPath::Fixed;
    Ceiling ceiling = Ceiling::None;
    uint32_t taps = 16;     // per pixel, for Ceiling::Taps and Ceiling::ComputeTaps
    bool readback = false;  // read the images back every frame, as `render` does
    // Moves every dynamic instance of the scene each frame: a 2 m circle about its place
    // and a turn about its vertical axis, one turn per 120 frames (cached cascades with
    // moving casters).
    bool animate_dynamic = false;
    // Measured frames alternate between the settings and these changed ones (a live
    // ShadowSystem::update_settings() before every frame): the renderer's call is the
    // "update_settings" CPU step (its own pipelines included), the rebuild it leaves to the
    // next prepare() "settings_rebuild", and the maps it empties are redrawn in the frame's
    // GPU scopes. Empty: no change.
    SettingsOverrides toggle;
    std::string toggle_text;  // as given (--toggle), for the report
    std::optional<std::filesystem::path> json;
    // Called after every frame (warm-up included) with frames done and the total.
    std::function<void(uint32_t done, uint32_t total)> progress;
};

struct DeviceReport {
    std::string name;
    std::string driver;
    std::string type;
    std::string api_version;
    uint32_t timestamp_valid_bits = 0;
    double timestamp_period_ns = 0.0;
};

struct SceneReport {
    std::string spec;
    size_t meshes = 0;
    size_t materials = 0;
    size_t instances = 0;  // = draws per pass without culling
    uint64_t triangles = 0;
    uint64_t vertices = 0;  // stored once per mesh
};

struct CountSummary {
    double mean = 0.0;
    uint64_t min = 0;
    uint64_t max = 0;
};

struct CascadeReport {
    CountSummary draws;      // per frame
    CountSummary triangles;  // per frame
    // With cached static casters (--shadow-cache): texels drawn and copied per frame, and
    // the frames that reused the cache (without: every texel drawn, nothing copied).
    CountSummary texels_rendered;
    CountSummary texels_copied;
    uint64_t cache_reused_frames = 0;
};

// The sun's virtual shadow map (--shadow-technique virtual), over the measured frames: the
// GPU's page counts (FrameInfo::virtual_map, of the frame frames-in-flight earlier).
struct VirtualReport {
    std::vector<float> texel_world_size;  // metres per texel of each level
    uint32_t pool_pages = 0;
    uint64_t pool_bytes = 0;
    CountSummary pages_requested;  // per frame
    CountSummary pages_rendered;
    CountSummary pages_cached;
    CountSummary pages_unserved;
    CountSummary pages_resident;
    CountSummary pages_evicted;
    CountSummary page_draws;
    CountSummary page_draw_triangles;
    CountSummary dropped_page_draws;  // beyond Settings::shadow.virtual_maps.page_draws
    CountSummary pages_deferred;      // left stale for a later frame after dropped draws
    uint64_t invalidated_all_frames = 0;
};

// One shadowed spot or point light (renderer::LocalShadowStats), over the measured frames.
struct LocalShadowReport {
    uint32_t light = 0;  // index into the scene's lights
    std::string type;    // "spot" or "point"
    uint32_t layers = 0;
    // Texels per side of each of its layers, per frame: the renderer may size a light's map
    // by its screen coverage, which changes along the camera path.
    CountSummary resolution;
    float near_plane = 0.0f;   // metres, the smallest of the frames (lights and casters stand still)
    CountSummary draws;        // per frame, over all its layers
    CountSummary triangles;    // per frame, over all its layers
    CountSummary layers_kept;  // per frame: its layers a cached frame did not render (--shadow-cache)
};

struct CeilingReport {
    std::string mode;  // "triangles" or "taps"
    std::string unit;  // what work_per_frame counts
    uint64_t work_per_frame = 0;
    double per_second = 0.0;  // work_per_frame / median time of the measured passes
};

struct BenchResult {
    std::string version;
    DeviceReport device;
    SceneReport scene;
    RenderSettings settings;
    BenchJob job;                             // without the progress callback
    std::vector<std::string> gpu_pass_order;  // first-seen order, "frame" last
    std::map<std::string, Summary> gpu_ms;
    // shadow_sun, shadow_local, lighting and frame, per measured frame with timestamps, in
    // order (plots of time along a camera path).
    std::map<std::string, std::vector<double>> gpu_ms_per_frame;
    std::vector<std::string> cpu_step_order;
    std::map<std::string, Summary> cpu_ms;
    std::vector<CascadeReport> cascades;
    std::optional<VirtualReport> virtual_map;      // --shadow-technique virtual
    std::vector<LocalShadowReport> local_shadows;  // shadowed local lights, in light order
    // Every shadow map: the cascades, the moments maps of a moment filter and the shared
    // layered map of the shadowed local lights (not the placeholder without any).
    uint64_t shadow_map_bytes = 0;
    uint32_t frames_without_gpu_times = 0;  // timestamps unsupported or not ready
    std::optional<CeilingReport> ceiling;
};

// Throws InputError (bad job or scene), DeviceError (no device) or ValidationFailure.
BenchResult run_bench_job(const BenchJob& job);

}  // namespace penumbra::bench

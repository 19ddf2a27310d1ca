// run_bench_job: the frame loops of `penumbra bench` and the collection of their samples.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string_view>

#include <glm/gtc/matrix_transform.hpp>
#include "bench/bench_job.hpp"
#include "bench/layer_start_pass.hpp"
#include "bench/tap_ceiling_pass.hpp"
#include "image/output_files.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/gpu/frame_commands.hpp"
#include "penumbra/gpu/timestamps.hpp"
#include "penumbra/scene/loader.hpp"
#include "penumbra/scene/settings_overrides.hpp"
#include "renderer/renderer.hpp"

namespace penumbra::bench {
namespace {

using Clock = std::chrono::steady_clock;

// GPU scopes reported frame by frame (BenchResult::gpu_ms_per_frame): present in every
// frame that has timestamps, so that their series line up.
constexpr const char* kPerFrameScopes[] = {"shadow_sun", "shadow_local", "lighting", "frame"};

double milliseconds_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Named samples, remembering the order in which names first appeared.
class SampleSet {
public:
    void add(const std::string& name, double value) {
        auto [entry, inserted] = samples_.try_emplace(name);
        if (inserted) order_.push_back(name);
        entry->second.push_back(value);
    }

    // `last` (when present) goes to the end of the order: totals read best after their parts.
    void summarize_into(std::vector<std::string>& order, std::map<std::string, Summary>& summaries,
                        const std::string& last = "") const {
        for (const std::string& name : order_) {
            if (name != last) order.push_back(name);
        }
        if (samples_.contains(last)) order.push_back(last);
        for (const auto& [name, values] : samples_) summaries[name] = summarize(values);
    }

    // Every sample of `name` in frame order (empty when it never appeared).
    std::vector<double> series(const std::string& name) const {
        const auto found = samples_.find(name);
        return found == samples_.end() ? std::vector<double>{} : found->second;
    }

private:
    std::vector<std::string> order_;
    std::map<std::string, std::vector<double>> samples_;
};

// One shadowed local light's counts, frame after frame. Which lights are shadowed is fixed
// when the Renderer is created, so every frame reports the same lights in the same order.
struct LocalShadowSamples {
    uint32_t light = 0;  // index into the scene's lights
    uint32_t layers = 0;
    float near_plane = std::numeric_limits<float>::infinity();
    std::vector<uint64_t> resolution;  // [frame]
    std::vector<uint64_t> draws;
    std::vector<uint64_t> triangles;
    std::vector<uint64_t> layers_kept;  // cached local shadows
};

struct FrameSamples {
    SampleSet gpu;
    SampleSet cpu;
    std::vector<std::vector<uint64_t>> cascade_draws;  // [cascade][frame]
    std::vector<std::vector<uint64_t>> cascade_triangles;
    std::vector<std::vector<uint64_t>> cascade_texels_rendered;
    std::vector<std::vector<uint64_t>> cascade_texels_copied;
    std::vector<uint64_t> cascade_reused;
    std::vector<LocalShadowSamples> local_shadows;
    // The virtual shadow map's counts, per frame whose counts had arrived.
    std::optional<VirtualShadowInfo> virtual_map;  // the last frame's (levels, pool)
    std::map<std::string, std::vector<uint64_t>> virtual_counts;
    uint64_t virtual_invalidated_all = 0;
    uint32_t frames_without_gpu_times = 0;

    void add_gpu_times(const std::vector<gpu::ScopeTime>& times) {
        if (times.empty()) ++frames_without_gpu_times;
        for (const gpu::ScopeTime& time : times) gpu.add(time.name, time.milliseconds);
    }
};

// The sun's whole shadow work of a frame: its cascades' passes, the cache's copies and
// dynamic casters, the moments conversion (0 for a cached frame that drew nothing). The
// spot/point lights' pass ("shadow_local") is not the sun's.
double sun_shadow_ms(const std::vector<gpu::ScopeTime>& times) {
    double total = 0.0;
    for (const gpu::ScopeTime& time : times) {
        if (time.name.starts_with("shadow_") && time.name != "shadow_local") total += time.milliseconds;
    }
    return total;
}

CountSummary summarize_counts(const std::vector<uint64_t>& counts) {
    CountSummary summary;
    if (counts.empty()) return summary;
    summary.min = *std::min_element(counts.begin(), counts.end());
    summary.max = *std::max_element(counts.begin(), counts.end());
    double total = 0.0;
    for (const uint64_t count : counts) total += static_cast<double>(count);
    summary.mean = total / static_cast<double>(counts.size());
    return summary;
}

void validate_job(const BenchJob& job) {
    if (job.frames == 0) throw InputError("--frames: must be at least 1, got 0");
    if (is_tap_ceiling(job.ceiling) && (job.taps == 0 || job.taps > kMaxTaps)) {
        throw InputError("--taps: must be between 1 and " + std::to_string(kMaxTaps) + ", got " +
                         std::to_string(job.taps));
    }
}

// Path parameter of frame `index`: warm-up frames repeat the first measured frame.
float path_parameter(const BenchJob& job, uint32_t index) {
    if (index < job.warmup) return 0.0f;
    return static_cast<float>(index - job.warmup) / static_cast<float>(job.frames);
}

DeviceReport describe_device(const renderer::AppContext& context, const gpu::GpuTimer& timer) {
    const PhysicalDeviceInfo& info = context.physical_device_info();
    DeviceReport report;
    report.name = info.name;
    report.driver = info.driver;
    report.type = info.type;
    report.api_version = vulkan_version_string(info.api_version);
    report.timestamp_valid_bits = timer.valid_bits();
    report.timestamp_period_ns = timer.period_ns();
    return report;
}

SceneReport describe_scene(const std::string& spec, const Scene& scene) {
    SceneReport report;
    report.spec = spec.empty() ? std::string(kDefaultSceneName) : spec;
    report.meshes = scene.meshes.size();
    report.materials = scene.materials.size();
    report.instances = scene.instances.size();
    report.triangles = scene.triangle_count();
    for (const Mesh& mesh : scene.meshes) report.vertices += mesh.vertices.size();
    return report;
}

void record_renderer_frame(const renderer::FrameInfo& frame, double wall_ms, FrameSamples& samples) {
    samples.add_gpu_times(frame.gpu_times);
    if (!frame.gpu_times.empty()) samples.gpu.add("shadow_sun", sun_shadow_ms(frame.gpu_times));
    samples.cpu.add("cascade_setup", frame.cpu_times.cascade_setup_ms);
    samples.cpu.add("culling", frame.cpu_times.culling_ms);
    samples.cpu.add("settings_rebuild", frame.cpu_times.settings_ms);
    samples.cpu.add("recording", frame.cpu_times.recording_ms);
    samples.cpu.add("submit_wait", frame.cpu_times.submit_wait_ms);
    samples.cpu.add("frame_wall", wall_ms);
    samples.cascade_draws.resize(frame.cascades.size());
    samples.cascade_triangles.resize(frame.cascades.size());
    samples.cascade_texels_rendered.resize(frame.cascades.size());
    samples.cascade_texels_copied.resize(frame.cascades.size());
    samples.cascade_reused.resize(frame.cascades.size());
    for (size_t c = 0; c < frame.cascades.size(); ++c) {
        samples.cascade_draws[c].push_back(frame.cascades[c].draws);
        samples.cascade_triangles[c].push_back(frame.cascades[c].triangles);
        samples.cascade_texels_rendered[c].push_back(frame.cascades[c].texels_rendered);
        samples.cascade_texels_copied[c].push_back(frame.cascades[c].texels_copied);
        samples.cascade_reused[c] += frame.cascades[c].cache_reused ? 1 : 0;
    }
    if (frame.virtual_map) {
        const VirtualShadowInfo& v = *frame.virtual_map;
        samples.virtual_map = v;
        samples.virtual_invalidated_all += v.invalidated_all ? 1 : 0;
        if (v.counted_frame > 0) {
            const std::pair<const char*, uint64_t> counts[] = {{"pages_requested", v.pages_requested},
                                                               {"pages_rendered", v.pages_rendered},
                                                               {"pages_cached", v.pages_cached},
                                                               {"pages_unserved", v.pages_unserved},
                                                               {"pages_resident", v.pages_resident},
                                                               {"pages_evicted", v.pages_evicted},
                                                               {"page_draws", v.page_draws},
                                                               {"page_draw_triangles", v.page_draw_triangles},
                                                               {"dropped_page_draws", v.dropped_page_draws},
                                                               {"pages_deferred", v.pages_deferred}};
            for (const auto& [name, value] : counts) samples.virtual_counts[name].push_back(value);
        }
    }
    samples.local_shadows.resize(frame.local_shadows.size());
    for (size_t i = 0; i < frame.local_shadows.size(); ++i) {
        const LocalShadowInfo& stats = frame.local_shadows[i];
        LocalShadowSamples& light = samples.local_shadows[i];
        light.light = stats.light;
        light.layers = stats.layers;
        light.near_plane = std::min(light.near_plane, stats.near_plane);
        light.resolution.push_back(stats.resolution);
        light.draws.push_back(stats.draws);
        light.triangles.push_back(stats.triangles);
        light.layers_kept.push_back(stats.layers_kept);
    }
}

Light* find_sun(Scene& scene) {
    for (Light& light : scene.lights) {
        if (light.type == LightType::Directional) return &light;
    }
    return nullptr;
}

// --animate-dynamic: frame `index` of every dynamic instance's motion, a 2 m circle about its
// place with a turn about its vertical axis, one turn per 120 frames (phases spread by
// instance, so that neighbours do not move in step).
void move_dynamic_instances(renderer::Renderer& renderer, const Scene& scene, uint32_t index) {
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        if (!instance.dynamic) continue;
        const float angle = 6.2831853f * static_cast<float>(index) / 120.0f + static_cast<float>(i);
        const glm::vec3 place(instance.world[3]);
        const glm::mat4 about_place = glm::translate(glm::mat4(1.0f), place) *
                                      glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0.0f, 1.0f, 0.0f)) *
                                      glm::translate(glm::mat4(1.0f), -place);
        const glm::vec3 circle(2.0f * std::cos(angle), 0.0f, 2.0f * std::sin(angle));
        renderer.move_instance(i, glm::translate(glm::mat4(1.0f), circle) * about_place * instance.world);
    }
}

// A scope's time in one frame's GPU times, if it was timed.
std::optional<double> scope_ms(const std::vector<gpu::ScopeTime>& times, std::string_view name) {
    for (const gpu::ScopeTime& time : times) {
        if (time.name == name) return time.milliseconds;
    }
    return std::nullopt;
}

// Contact shadows are traced inside the compute resolve, sharing its reconstruction of the
// surface, so no scope of their own times them. With them on (deferred), each measured frame
// is rendered once more at the same camera and sun with the trace's lights switched off (a
// live uniform change) and the "contact" sample is the difference of the two `visibility`
// scopes: their cost over the resolve, frame by frame.
void record_contact_cost(renderer::Renderer& renderer, const Camera& camera, renderer::ReadbackMode readback,
                         FrameSamples& samples) {
    const std::optional<double> with = scope_ms(renderer.last_frame().gpu_times, "visibility");
    RenderSettings without = renderer.settings();
    const RenderSettings traced = without;
    without.contact.sun = false;
    without.contact.local_lights = false;
    renderer.update_settings(without);
    renderer.render(camera, readback);
    const std::optional<double> without_ms = scope_ms(renderer.last_frame().gpu_times, "visibility");
    renderer.update_settings(traced);
    if (with && without_ms) samples.gpu.add("contact", *with - *without_ms);
}

// --toggle: the settings and the changed ones; refused when the change is not one a live
// renderer takes (the image size, the resolve path, the pre-pass).
std::optional<std::pair<RenderSettings, RenderSettings>> toggled_settings(const BenchJob& job,
                                                                          const renderer::Renderer& renderer) {
    if (job.toggle_text.empty()) return std::nullopt;
    RenderSettings changed = renderer.settings();
    apply_overrides(job.toggle, changed);
    validate_settings(changed, "--toggle");
    if (renderer.needs_new_renderer(changed)) {
        throw InputError("--toggle: " + job.toggle_text +
                         " changes what a renderer creates once (the image size, the resolve path, the pre-pass, "
                         "contact shadows): it cannot be toggled live");
    }
    return std::pair{renderer.settings(), changed};
}

// The renderer's frames along the camera and light paths. The Renderer keeps a reference
// to `prepared.scene` and reads its sun every frame, so moving the sun here moves it there.
FrameSamples run_renderer_frames(const renderer::AppContext& context, const BenchJob& job, PreparedJob& prepared,
                                 BenchResult& result) {
    renderer::Renderer renderer(context, prepared.scene, prepared.settings);
    result.settings.resolve = renderer.resolve();  // the report names the path measured, not "auto"
    result.device = describe_device(context, renderer.gpu_timer());
    const Camera start_camera = prepared.scene.camera;
    Light* sun = find_sun(prepared.scene);
    const glm::vec3 start_sun = sun ? sun->direction : glm::vec3{0.0f, -1.0f, 0.0f};
    const auto readback = job.readback ? renderer::ReadbackMode::Images : renderer::ReadbackMode::None;

    const bool time_contact = prepared.settings.contact.enabled &&
                              (prepared.settings.contact.sun || prepared.settings.contact.local_lights) &&
                              renderer.resolve() == ShadowResolve::Deferred;
    FrameSamples samples;
    const std::optional<std::pair<RenderSettings, RenderSettings>> toggled = toggled_settings(job, renderer);
    const uint32_t total = job.warmup + job.frames;
    for (uint32_t index = 0; index < total; ++index) {
        const float t = path_parameter(job, index);
        if (sun) sun->direction = glm::normalize(sun_on_path(job.light_path, start_sun, t));
        if (job.animate_dynamic) move_dynamic_instances(renderer, prepared.scene, index);
        if (toggled && index >= job.warmup) {
            const Clock::time_point change = Clock::now();
            renderer.update_settings((index - job.warmup) % 2 == 0 ? toggled->second : toggled->first);
            samples.cpu.add("update_settings", milliseconds_since(change));
        }
        const Camera camera = camera_on_path(job.camera_path, start_camera, t, job.frames);
        const Clock::time_point start = Clock::now();
        renderer.render(camera, readback);
        const double wall_ms = milliseconds_since(start);
        if (index >= job.warmup) record_renderer_frame(renderer.last_frame(), wall_ms, samples);
        if (index >= job.warmup && time_contact) record_contact_cost(renderer, camera, readback, samples);
        if (job.progress) job.progress(index + 1, total);
    }
    // The maps as the last frame's lights sized them (spot/point maps follow the lights).
    result.shadow_map_bytes = renderer.shadow_map_bytes();
    return samples;
}

// The frames of a ceiling that renders no scene: warm-up and measured frames of `record`
// inside the "frame" scope, with their GPU scopes and CPU recording and wall times.
FrameSamples run_pass_frames(const BenchJob& job, gpu::FrameCommands& commands, gpu::GpuTimer& timer,
                             const std::function<void(VkCommandBuffer)>& record) {
    FrameSamples samples;
    const uint32_t total = job.warmup + job.frames;
    for (uint32_t index = 0; index < total; ++index) {
        double recording_ms = 0.0;
        const Clock::time_point start = Clock::now();
        commands.submit_and_wait([&](VkCommandBuffer cmd) {
            const Clock::time_point record_start = Clock::now();
            timer.begin_frame(cmd);
            gpu::TimedScope frame_scope(timer, cmd, "frame");
            record(cmd);
            recording_ms = milliseconds_since(record_start);
        });
        const double wall_ms = milliseconds_since(start);
        if (index >= job.warmup) {
            samples.add_gpu_times(timer.read().value_or(std::vector<gpu::ScopeTime>{}));
            samples.cpu.add("recording", recording_ms);
            samples.cpu.add("frame_wall", wall_ms);
        }
        if (job.progress) job.progress(index + 1, total);
    }
    return samples;
}

// The sampling-rate ceilings: no scene rendering, only the tap pass (fragment or compute).
FrameSamples run_tap_frames(const renderer::AppContext& context, const BenchJob& job, const RenderSettings& settings,
                            BenchResult& result) {
    const TapCeilingUnits units =
        job.ceiling == Ceiling::ComputeTaps ? TapCeilingUnits::Compute : TapCeilingUnits::Fragment;
    const TapCeilingPass pass(context, {settings.width, settings.height, settings.shadow.cascades.resolution,
                                        static_cast<uint32_t>(settings.shadow.cascades.count), job.taps, units});
    gpu::FrameCommands commands(context);
    gpu::GpuTimer timer(context, 2);
    result.device = describe_device(context, timer);
    result.shadow_map_bytes = pass.shadow_map_bytes();
    context.submit_and_wait([&](VkCommandBuffer cmd) { pass.record_setup(cmd); });

    const FrameSamples samples = run_pass_frames(job, commands, timer, [&](VkCommandBuffer cmd) {
        gpu::TimedScope taps_scope(timer, cmd, "taps");
        pass.record(cmd);
    });
    result.ceiling = CeilingReport{units == TapCeilingUnits::Compute ? "compute-taps" : "taps", "texture taps",
                                   pass.taps_per_frame(), 0.0};
    return samples;
}

// The ways to start a layer (bench/layer_start_pass.hpp): no scene, the cascades' layers
// started four ways per frame.
FrameSamples run_layer_start_frames(const renderer::AppContext& context, const BenchJob& job,
                                    const RenderSettings& settings, BenchResult& result) {
    const LayerStartPass pass(context, settings.shadow.cascades.resolution,
                              static_cast<uint32_t>(settings.shadow.cascades.count));
    gpu::FrameCommands commands(context);
    gpu::GpuTimer timer(context, 5);
    result.device = describe_device(context, timer);
    result.shadow_map_bytes = pass.map_bytes();
    context.submit_and_wait([&](VkCommandBuffer cmd) { pass.record_setup(cmd); });

    const FrameSamples samples =
        run_pass_frames(job, commands, timer, [&](VkCommandBuffer cmd) { pass.record(cmd, timer); });
    result.ceiling =
        CeilingReport{"layer-start", "depth texels cleared by a render-pass clear", pass.texels_per_way(), 0.0};
    return samples;
}

// The triangle-rate ceiling renders the same casters with the same pipelines into a map so
// small that rasterisation costs nothing, with every caster in every cascade.
void apply_triangle_ceiling(RenderSettings& settings) {
    settings.shadow.cascades.resolution = kCeilingShadowResolution;
    settings.shadow.cull_casters = false;
    settings.width = kCeilingShadowResolution;
    settings.height = kCeilingShadowResolution;
}

// The cascades' shadow passes: the triangle ceiling counts cascade triangles only, so the
// spot/point lights' passes ("shadow_local...") are timed but not part of the rate.
double cascade_shadow_median_ms(const BenchResult& result) {
    double total = 0.0;
    for (const auto& [name, summary] : result.gpu_ms) {
        if (name.starts_with("shadow_") && !name.starts_with("shadow_local")) total += summary.median;
    }
    return total;
}

LocalShadowReport summarize_local_shadow(const LocalShadowSamples& samples, const Scene& scene) {
    LocalShadowReport report;
    report.light = samples.light;
    report.type = scene.lights.at(samples.light).type == LightType::Spot ? "spot" : "point";
    report.layers = samples.layers;
    report.resolution = summarize_counts(samples.resolution);
    report.near_plane = samples.near_plane;
    report.draws = summarize_counts(samples.draws);
    report.triangles = summarize_counts(samples.triangles);
    report.layers_kept = summarize_counts(samples.layers_kept);
    return report;
}

void summarize_samples(const FrameSamples& samples, const Scene& scene, BenchResult& result) {
    samples.gpu.summarize_into(result.gpu_pass_order, result.gpu_ms, "frame");
    for (const char* name : kPerFrameScopes) {
        std::vector<double> series = samples.gpu.series(name);
        if (!series.empty()) result.gpu_ms_per_frame[name] = std::move(series);
    }
    samples.cpu.summarize_into(result.cpu_step_order, result.cpu_ms, "frame_wall");
    for (size_t c = 0; c < samples.cascade_draws.size(); ++c) {
        result.cascades.push_back({summarize_counts(samples.cascade_draws[c]),
                                   summarize_counts(samples.cascade_triangles[c]),
                                   summarize_counts(samples.cascade_texels_rendered[c]),
                                   summarize_counts(samples.cascade_texels_copied[c]), samples.cascade_reused[c]});
    }
    for (const LocalShadowSamples& light : samples.local_shadows) {
        result.local_shadows.push_back(summarize_local_shadow(light, scene));
    }
    if (samples.virtual_map) {
        VirtualReport report;
        report.texel_world_size = samples.virtual_map->texel_world_size;
        report.pool_pages = samples.virtual_map->pool_pages;
        report.pool_bytes = samples.virtual_map->pool_bytes;
        const auto counts = [&](const char* name) {
            const auto found = samples.virtual_counts.find(name);
            return found == samples.virtual_counts.end() ? CountSummary{} : summarize_counts(found->second);
        };
        report.pages_requested = counts("pages_requested");
        report.pages_rendered = counts("pages_rendered");
        report.pages_cached = counts("pages_cached");
        report.pages_unserved = counts("pages_unserved");
        report.pages_resident = counts("pages_resident");
        report.pages_evicted = counts("pages_evicted");
        report.page_draws = counts("page_draws");
        report.page_draw_triangles = counts("page_draw_triangles");
        report.dropped_page_draws = counts("dropped_page_draws");
        report.pages_deferred = counts("pages_deferred");
        report.invalidated_all_frames = samples.virtual_invalidated_all;
        result.virtual_map = report;
    }
    result.frames_without_gpu_times = samples.frames_without_gpu_times;
}

void finish_ceiling(const BenchJob& job, const Scene& scene, const RenderSettings& settings, BenchResult& result) {
    if (job.ceiling == Ceiling::Triangles) {
        const uint64_t work = scene.triangle_count() * static_cast<uint64_t>(settings.shadow.cascades.count);
        const double ms = cascade_shadow_median_ms(result);
        result.ceiling = CeilingReport{"triangles", "cascade triangles", work, ms > 0.0 ? work / (ms * 1e-3) : 0.0};
    } else if ((is_tap_ceiling(job.ceiling) || job.ceiling == Ceiling::LayerStart) && result.ceiling) {
        const char* scope = job.ceiling == Ceiling::LayerStart ? "start_render_pass_clear" : "taps";
        const double ms = result.gpu_ms.contains(scope) ? result.gpu_ms.at(scope).median : 0.0;
        result.ceiling->per_second = ms > 0.0 ? static_cast<double>(result.ceiling->work_per_frame) / (ms * 1e-3) : 0.0;
    }
}

}  // namespace

BenchResult run_bench_job(const BenchJob& job) {
    validate_job(job);
    if (job.json) checked_output_path(*job.json);  // before the frames are measured
    PreparedJob prepared = prepare_render_job(job.render);
    if (job.ceiling == Ceiling::Triangles) apply_triangle_ceiling(prepared.settings);

    BenchResult result;
    result.version = PENUMBRA_VERSION;
    result.job = job;
    result.job.progress = nullptr;
    result.settings = prepared.settings;
    result.scene = describe_scene(job.render.scene, prepared.scene);
    VulkanContextOptions device_options = job.render.device;
    device_options.validation_log = std::make_shared<ValidationLog>();
    {
        renderer::AppContext context(device_options);
        const FrameSamples samples =
            is_tap_ceiling(job.ceiling)          ? run_tap_frames(context, job, prepared.settings, result)
            : job.ceiling == Ceiling::LayerStart ? run_layer_start_frames(context, job, prepared.settings, result)
                                                 : run_renderer_frames(context, job, prepared, result);
        summarize_samples(samples, prepared.scene, result);
    }
    // Checked after the device and instance are gone, so leak reports count too.
    check_validation(*device_options.validation_log);
    finish_ceiling(job, prepared.scene, prepared.settings, result);
    return result;
}

}  // namespace penumbra::bench

#include "cli.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

#include "choice_help.hpp"
#include "compare_options.hpp"
#include "number_checks.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/scene/settings_files.hpp"
#include "setting_options.hpp"
#include "view_options.hpp"

namespace penumbra::cli {
namespace {

// Raw option values as typed; converted after parsing so errors can name the flag.
struct RawRenderOptions {
    std::string eye, target, up, light_dir, aov, debug;
    std::string config;
    RawSettingOptions settings;  // the ShadowSystem's settings, one flag each
};

struct RawBenchOptions {
    std::string camera_path, light_path, ceiling, json, toggle;
};

glm::vec3 parse_vec3(const std::string& text, const std::string& flag) {
    std::stringstream stream(text);
    glm::vec3 value{0.0f};
    char separator = 0;
    if (!(stream >> value.x >> separator) || separator != ',' || !(stream >> value.y >> separator) ||
        separator != ',' || !(stream >> value.z) || !(stream >> std::ws).eof()) {
        throw InputError(flag + ": expected three comma-separated numbers x,y,z, got \"" + text + "\"");
    }
    for (int i = 0; i < 3; ++i) {
        if (!sane_number(value[i])) {
            throw InputError(flag + ": expected finite numbers within +-1e9, got \"" + text + "\"");
        }
    }
    return value;
}

template <typename Enum>
Enum parse_choice(const std::string& text, const std::string& flag, const std::map<std::string, Enum>& choices) {
    const auto found = choices.find(text);
    if (found != choices.end()) return found->second;
    std::string names;
    for (const auto& [name, value] : choices) names += (names.empty() ? "" : ", ") + name;
    throw InputError(flag + ": unknown value \"" + text + "\" (expected " + names + ")");
}

void add_settings_options(CLI::App& render, SettingsOverrides& o, RawRenderOptions& raw) {
    render.add_option("--eye", raw.eye, "Camera position x,y,z (overrides the scene)");
    render.add_option("--target", raw.target, "Camera target x,y,z");
    render.add_option("--up", raw.up, "Camera up vector x,y,z");
    render.add_option("--fov", o.fov, "Vertical field of view in degrees (0 < fov < 180)");
    render.add_option("--near", o.near_plane, "Camera near plane (> 0)");
    render.add_option("--far", o.far_plane, "Camera far plane (> near)");
    render.add_option("--light-dir", raw.light_dir, "Direction the sunlight travels x,y,z");
    render
        .add_option("--angular-diameter", o.angular_diameter,
                    "The sun's angular diameter in degrees, for pcss (0..45; the scene's, default 0.53)")
        ->check(CLI::Range(0.0f, 45.0f));
    add_setting_options(render, raw.settings);
    // Every floating-point option, whatever its own range: finite and within +-1e9.
    for (CLI::Option* option : render.get_options()) {
        if (option->get_type_name().starts_with("FLOAT")) option->check(finite_number());
    }
}

void convert_raw_options(const RawRenderOptions& raw, RenderJob& job) {
    SettingsOverrides& o = job.overrides;
    convert_setting_options(raw.settings, o.settings);
    if (!raw.eye.empty()) o.eye = parse_vec3(raw.eye, "--eye");
    if (!raw.target.empty()) o.target = parse_vec3(raw.target, "--target");
    if (!raw.up.empty()) o.up = parse_vec3(raw.up, "--up");
    if (!raw.light_dir.empty()) o.light_direction = parse_vec3(raw.light_dir, "--light-dir");
    const SettingValue* scheme = o.settings.find("split_scheme");
    if (o.settings.find("splits") && scheme && *scheme != SettingValue(std::string("manual"))) {
        throw InputError("--splits: manual split distances need --split-scheme manual, not \"" +
                         std::get<std::string>(*scheme) + "\"");
    }
    if (raw.aov.starts_with("shadow:")) {
        job.aov = Aov::Shadow;
        job.aov_light = parse_light_index(raw.aov.substr(7), "--aov");
    } else if (!raw.aov.empty()) {
        job.aov = parse_choice<Aov>(raw.aov, "--aov",
                                    {{"shadow", Aov::Shadow}, {"cascade", Aov::Cascade}, {"contact", Aov::Contact}});
    }
    if (!raw.debug.empty() && !raw.aov.empty()) {
        throw InputError("--aov and --debug: choose one (an AOV replaces the image that --debug tints)");
    }
    if (!raw.debug.empty()) {
        job.debug = parse_choice<DebugView>(raw.debug, "--debug",
                                            {{"cascades", DebugView::Cascades},
                                             {"shadowmap", DebugView::ShadowMap},
                                             {"virtual-pages", DebugView::VirtualPages}});
    }
}

// Options shared by `render` and `bench`: the scene, its settings and the device.
// The scene argument and the load budget: every command that loads a scene.
void add_scene_options(CLI::App& command, std::string& scene, LoadBudget& budget) {
    command.add_option("scene", scene, "Scene file (.toml) or builtin:NAME (default builtin:default)")
        ->check(CLI::Validator(
            [](const std::string& path) { return path.empty() ? std::string("the scene path is empty") : ""; }, ""));
    command
        .add_option("--max-scene-triangles", budget.max_triangles,
                    "Refuse a scene whose glTF models would make more triangles, counting each placement (default " +
                        std::to_string(budget.max_triangles) + ")")
        ->check(CLI::PositiveNumber);
    command
        .add_option("--max-scene-bytes", budget.max_bytes,
                    "Refuse a scene whose meshes and decoded textures would take more bytes (default " +
                        std::to_string(budget.max_bytes) + ")")
        ->check(CLI::PositiveNumber);
}

void add_render_job_options(CLI::App& command, RenderJob& job, RawRenderOptions& raw) {
    add_scene_options(command, job.scene, job.load_budget);
    command.add_option("--config", raw.config, "Config file (.toml) with [output], [shadow], [camera], [sun] settings");
    command.add_flag("--validate", job.device.validation,
                     "Enable the Khronos validation layer (with synchronization validation); any message fails");
    command.add_option("--device", job.device.device_selector, "Vulkan device index or name (see `penumbra devices`)");
    add_settings_options(command, job.overrides, raw);
}

void finish_render_job(const RawRenderOptions& raw, RenderJob& job) {
    convert_raw_options(raw, job);
    if (!raw.config.empty()) job.config = raw.config;
}

void add_bench_options(CLI::App& bench, bench::BenchJob& job, RawBenchOptions& raw) {
    bench.add_option("--frames", job.frames, "Measured frames (default 100)")->check(CLI::Range(1u, 1000000u));
    bench.add_option("--warmup", job.warmup, "Frames rendered before measuring (default 10)")
        ->check(CLI::Range(0u, 1000000u));
    bench.add_option("--camera-path", raw.camera_path,
                     "Camera path: " + choice_list(bench::kCameraPathChoices, bench::CameraPath::Orbit) +
                         " (walk: 1.4 m/s at 60 frames/s; still: the scene's camera)");
    bench.add_option("--light-path", raw.light_path,
                     "Sun path: " + choice_list(bench::kLightPathChoices, bench::LightPath::Fixed));
    bench.add_option("--json", raw.json, "Also write the results (and device, settings, scene) as JSON");
    bench.add_option("--ceiling", raw.ceiling,
                     "Measure a ceiling instead: triangles (shadow pass at 512x512, no culling) | taps (full-screen "
                     "shadow-map taps in a fragment shader) | compute-taps (the same taps in a compute shader, one "
                     "thread per pixel) | layer-start (the cascades' layers cleared four ways, each timed)");
    bench.add_option("--taps", job.taps, "Texture taps per pixel for --ceiling taps and compute-taps (default 16)")
        ->check(CLI::Range(1u, bench::kMaxTaps));
    bench.add_flag("--readback", job.readback, "Read the images back every frame, as `render` does");
    bench.add_option("--toggle", raw.toggle,
                     "Alternate every measured frame between the settings and this change, TABLE.KEY=VALUE as in a "
                     "config file (e.g. shadow.filter=\"pcss\"): times update_settings() and what it rebuilds");
    bench.add_flag("--animate-dynamic", job.animate_dynamic,
                   "Move every dynamic instance each frame (a 2 m circle about its place, one turn per 120 frames)");
}

void finish_bench_job(const RawRenderOptions& raw, const RawBenchOptions& bench_raw, bench::BenchJob& job) {
    finish_render_job(raw, job.render);
    if (!bench_raw.camera_path.empty()) {
        job.camera_path = parse_choice(bench_raw.camera_path, "--camera-path", choice_map(bench::kCameraPathChoices));
    }
    if (!bench_raw.light_path.empty()) {
        job.light_path = parse_choice(bench_raw.light_path, "--light-path", choice_map(bench::kLightPathChoices));
    }
    if (!bench_raw.ceiling.empty()) {
        job.ceiling = parse_choice(bench_raw.ceiling, "--ceiling", choice_map(bench::kCeilingChoices));
    }
    if (!bench_raw.json.empty()) job.json = bench_raw.json;
    if (!bench_raw.toggle.empty()) {
        // "TABLE.KEY=VALUE" is the config-file line "KEY = VALUE" under [TABLE].
        const size_t dot = bench_raw.toggle.find('.');
        const size_t equals = bench_raw.toggle.find('=');
        if (dot == std::string::npos || equals == std::string::npos || dot > equals) {
            throw InputError("--toggle: expected TABLE.KEY=VALUE (e.g. shadow.filter=\"pcss\"), got \"" +
                             bench_raw.toggle + "\"");
        }
        job.toggle = parse_settings_text(
            "[" + bench_raw.toggle.substr(0, dot) + "]\n" + bench_raw.toggle.substr(dot + 1) + "\n", "--toggle");
        job.toggle_text = bench_raw.toggle;
    }
}

}  // namespace

int32_t parse_light_index(const std::string& text, const std::string& flag) {
    const bool digits = !text.empty() && text.size() <= 6 &&
                        std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (!digits)
        throw InputError(flag + ": expected shadow:N with N a light index (0, 1, ...), got \"shadow:" + text + "\"");
    return static_cast<int32_t>(std::stoi(text));
}

Command parse_command_line(int argc, char** argv) {
    CLI::App app{"penumbra: real-time shadows with Vulkan (cascaded shadow maps), rendered headlessly to PNG"};
    app.require_subcommand(0, 1);
    app.set_version_flag("--version", "penumbra 0.1.0");

    CLI::App* devices = app.add_subcommand("devices", "List Vulkan devices (index, name, type, driver, API version)");

    RenderJob job;
    RawRenderOptions raw;
    CLI::App* render = app.add_subcommand("render", "Render a scene with a sun shadow to a PNG");
    add_render_job_options(*render, job, raw);
    render->add_option("-o,--output", job.output, "Output PNG (default penumbra.png)");
    render->add_option(
        "--aov", raw.aov,
        "Write an AOV instead of colour: shadow (16-bit sun visibility) | shadow:N (light N of [[lights]]) | cascade | "
        "contact (16-bit, the sun's contact shadows alone)");
    render->add_option(
        "--debug", raw.debug,
        "Debug view: cascades (tint by cascade) | shadowmap (write the shadow-map layers side by side) | "
        "virtual-pages (tint by virtual level, page borders, unserved pages in magenta)");

    bench::BenchJob bench_job;
    RawRenderOptions bench_render_raw;
    RawBenchOptions bench_raw;
    CLI::App* bench = app.add_subcommand(
        "bench", "Time frames of a scene: GPU time per pass, CPU time per step, per-cascade load (docs/bench.md)");
    add_render_job_options(*bench, bench_job.render, bench_render_raw);
    add_bench_options(*bench, bench_job, bench_raw);

    compare::CompareJob compare_job;
    RawRenderOptions compare_render_raw;
    std::string compare_json;
    CLI::App* compare = app.add_subcommand(
        "compare",
        "Measure shadow quality against a ray-traced reference (Embree): error images and JSON (docs/QUALITY.md)");
    add_render_job_options(*compare, compare_job.render, compare_render_raw);
    add_compare_options(*compare, compare_job, compare_json);

    view::ViewJob view_job;
    RawRenderOptions view_render_raw;
    RawViewOptions view_raw;
    CLI::App* view =
        app.add_subcommand("view", "Open an interactive window with a live shadow debug panel (docs/viewer.md)");
    add_render_job_options(*view, view_job.render, view_render_raw);
    add_view_options(*view, view_job, view_raw);

    InspectJob inspect_job;
    CLI::App* inspect = app.add_subcommand(
        "inspect",
        "List a scene's objects and glTF nodes (with the names exclude_casters takes), triangles, bounds, shadow "
        "flags, alpha modes and lights (docs/cli.md)");
    add_scene_options(*inspect, inspect_job.scene, inspect_job.load_budget);
    inspect->add_flag("--json", inspect_job.json, "Print JSON instead of the text listing");

    try {
        app.parse(argc, argv);
        if (devices->parsed()) return DevicesCommand{};
        if (inspect->parsed()) return InspectCommand{inspect_job};
        if (bench->parsed()) {
            finish_bench_job(bench_render_raw, bench_raw, bench_job);
            return BenchCommand{bench_job};
        }
        if (compare->parsed()) {
            finish_render_job(compare_render_raw, compare_job.render);
            if (!compare_json.empty()) compare_job.json = compare_json;
            return CompareCommand{compare_job};
        }
        if (view->parsed()) {
            finish_render_job(view_render_raw, view_job.render);
            convert_view_options(view_raw, view_job);
            return ViewCommand{view_job};
        }
        if (!render->parsed()) {
            std::printf("%s", app.help().c_str());
            return ExitNow{0};
        }
        finish_render_job(raw, job);
        return RenderCommand{job};
    } catch (const CLI::ParseError& error) {
        // --help and --version arrive as "errors" with exit code 0; CLI11 prints them.
        if (error.get_exit_code() == 0) return ExitNow{app.exit(error)};
        std::fprintf(stderr, "penumbra: %s\n", escape_control_characters(error.what()).c_str());
        return ExitNow{2};
    } catch (const InputError& error) {
        std::fprintf(stderr, "penumbra: %s\n", error.what());
        return ExitNow{2};
    }
}

}  // namespace penumbra::cli

#include "view_options.hpp"

#include "cli.hpp"
#include "penumbra/errors.hpp"

namespace penumbra::cli {

void add_view_options(CLI::App& command, view::ViewJob& job, RawViewOptions& raw) {
    command.add_option("--frames", job.frames, "Render N frames, then exit (automation; no vsync)")
        ->check(CLI::Range(1u, 10000000u));
    command.add_option("--screenshot", raw.screenshot,
                       "PNG written from the last of --frames frames (and by F12), without the panel");
    command.add_option("--screenshot-aov", raw.screenshot_aov,
                       "What --screenshot holds: color (default) | shadow | shadow:N | cascade (as `render --aov`)");
    command.add_option("--script", raw.script, "Replay timed actions from FILE (docs/viewer.md)");
    command.add_option("--save-settings", raw.save_settings,
                       "Config file written by F5 / 'Save settings' (default penumbra-view.toml); with --frames, "
                       "also written at exit");
    command.add_flag("--no-ui", raw.no_ui, "Start with the panel hidden (F1 shows it)");
    command.add_option("--debug", raw.debug,
                       "Debug view: cascades | shadowmap (the layers shown in the panel) | virtual-pages");
}

void convert_view_options(const RawViewOptions& raw, view::ViewJob& job) {
    job.show_ui = !raw.no_ui;
    if (!raw.screenshot.empty()) job.screenshot = raw.screenshot;
    if (!raw.script.empty()) job.script = raw.script;
    if (!raw.save_settings.empty()) {
        job.settings_file = raw.save_settings;
        job.save_settings_on_exit = job.frames.has_value();
    }
    if (raw.screenshot_aov == "shadow") {
        job.screenshot_aov = Aov::Shadow;
    } else if (raw.screenshot_aov.starts_with("shadow:")) {
        // The visibility of light N, as `render --aov shadow:N` writes it.
        job.screenshot_aov = Aov::Shadow;
        job.render.aov_light = parse_light_index(raw.screenshot_aov.substr(7), "--screenshot-aov");
    } else if (raw.screenshot_aov == "cascade") {
        job.screenshot_aov = Aov::Cascade;
    } else if (!raw.screenshot_aov.empty() && raw.screenshot_aov != "color") {
        throw InputError("--screenshot-aov: unknown value \"" + raw.screenshot_aov +
                         "\" (expected color, shadow, shadow:N, cascade)");
    }
    if (raw.debug == "cascades") {
        job.render.debug = DebugView::Cascades;
    } else if (raw.debug == "shadowmap") {
        job.render.debug = DebugView::ShadowMap;
    } else if (raw.debug == "virtual-pages") {
        job.render.debug = DebugView::VirtualPages;
    } else if (!raw.debug.empty()) {
        throw InputError("--debug: unknown value \"" + raw.debug + "\" (expected cascades, shadowmap, virtual-pages)");
    }
    if (job.frames && !job.screenshot && job.screenshot_aov != Aov::None) {
        throw InputError("--screenshot-aov: needs --screenshot FILE");
    }
}

}  // namespace penumbra::cli

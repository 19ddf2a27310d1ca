// run_view(): the window, device, presenter and panel around a Viewer, and what is
// written once the run has passed validation.
#include <cstdio>

#include "image/output_files.hpp"
#include "penumbra/scene/settings_files.hpp"
#include "view_job.hpp"
#include "viewer.hpp"

namespace penumbra::view {
namespace {

std::string window_title(const ViewJob& job) {
    return "penumbra view: " + (job.render.scene.empty() ? std::string("builtin:default") : job.render.scene);
}

// What the run leaves for after validation: the automation screenshot and settings.
struct RunResult {
    uint32_t frames = 0;
    std::string device_name;
    std::optional<Capture> final_capture;
    RenderSettings settings;
    Camera camera;
    std::optional<Light> sun;
};

RunResult run_window(const ViewJob& job, PreparedJob prepared, std::vector<TimedAction> script, present::Window& window,
                     const VulkanContextOptions& options) {
    renderer::AppContext context(options);
    present::Surface surface(context, window);
    // Automation does not wait for vertical blank.
    present::Presenter presenter(context, window, surface, present::SwapchainOptions{!job.frames.has_value()});
    UiOverlay ui(context, window, presenter);
    Viewer viewer(job, std::move(prepared), std::move(script), ViewerParts{context, window, presenter, ui});
    RunResult result;
    result.frames = viewer.run();
    result.device_name = context.physical_device_info().name;
    result.final_capture = viewer.take_final_capture();
    result.settings = viewer.state().settings;
    result.camera = viewer.state().camera.camera();
    if (const Light* sun = viewer.state().scene.sun()) result.sun = *sun;
    return result;
}

}  // namespace

ViewSummary run_view(const ViewJob& job) {
    PreparedJob prepared = prepare_render_job(job.render);
    std::vector<TimedAction> script = job.script ? load_script(*job.script) : std::vector<TimedAction>{};
    present::Window window({window_title(job), prepared.settings.width, prepared.settings.height});
    VulkanContextOptions options = job.render.device;
    options.validation_log = std::make_shared<ValidationLog>();
    window.add_presentation(options);
    const RunResult result = run_window(job, std::move(prepared), std::move(script), window, options);
    // Checked after the device and instance are gone, so leak reports count too.
    check_validation(*options.validation_log);

    ViewSummary summary{result.frames, result.device_name, std::nullopt};
    if (result.final_capture) {
        write_capture(*result.final_capture);
        summary.screenshot = result.final_capture->file;
    }
    if (job.save_settings_on_exit) {
        write_output_file(job.settings_file,
                          format_settings_file(result.settings, result.camera, result.sun ? &*result.sun : nullptr));
    }
    return summary;
}

}  // namespace penumbra::view

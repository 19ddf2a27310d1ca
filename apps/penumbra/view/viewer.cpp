#include "viewer.hpp"

#include <cstdio>
#include <string>

#include "image/output_files.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/scene/settings_files.hpp"
#include "view_actions.hpp"

namespace penumbra::view {
namespace {

using Clock = std::chrono::steady_clock;

// Automation (--frames) advances animations by a fixed step so that runs are repeatable.
constexpr float kAutomationStepSeconds = 1.0f / 60.0f;

bool same_size(VkExtent2D extent, const RenderSettings& settings) {
    return extent.width == settings.width && extent.height == settings.height;
}

}  // namespace

Viewer::Viewer(const ViewJob& job, PreparedJob prepared, std::vector<TimedAction> script, const ViewerParts& parts)
    : job_(job),
      parts_(parts),
      state_{prepared.scene, prepared.settings, CameraController(prepared.scene.camera)},
      good_settings_(prepared.settings),
      output_(parts.context),
      script_(std::move(script)) {
    state_.show_ui = job.show_ui;
    state_.settings_file = job.settings_file;
    state_.screenshot_file = job.screenshot.value_or("penumbra-view.png");
    stats_.device_name = parts.context.info().name;
    window_size_ = parts.window.framebuffer_size();
    VkPhysicalDeviceVulkan11Properties properties11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &properties11};
    vkGetPhysicalDeviceProperties2(parts.context.physical_device(), &properties);
    max_views_ = properties11.maxMultiviewViewCount;
}

bool Viewer::keep_running() const {
    if (parts_.window.should_close() || state_.requests.quit) return false;
    return !job_.frames || frames_ < *job_.frames;
}

uint32_t Viewer::run() {
    Clock::time_point last = Clock::now();
    while (keep_running()) {
        const Clock::time_point now = Clock::now();
        const float elapsed = std::chrono::duration<float>(now - last).count();
        last = now;
        const double elapsed_ms = elapsed * 1000.0;
        stats_.frame_ms = stats_.frame_ms == 0.0 ? elapsed_ms : 0.9 * stats_.frame_ms + 0.1 * elapsed_ms;
        step(job_.frames ? kAutomationStepSeconds : elapsed);
    }
    return frames_;
}

void Viewer::step(float seconds) {
    parts_.window.poll_events();
    run_script();
    if (state_.requests.quit) return;  // `quit` at frame N: N frames are presented
    parts_.ui.begin_frame();
    handle_input(state_, seconds);
    stats_.frame = renderer_ ? &renderer_->last_frame() : nullptr;
    stats_.lights = &state_.scene.lights;
    stats_.shadow_map_bytes = renderer_ ? renderer_->shadow_map_bytes() : 0;
    draw_panel(state_, stats_);
    parts_.ui.end_frame();
    animate_sun(state_, seconds);
    if (state_.requests.save_settings) save_settings();
    follow_window_size();
    apply_settings();
    render_frame();
}

void Viewer::run_script() {
    std::string last_set;
    while (next_action_ < script_.size() && script_[next_action_].frame <= frames_) {
        const TimedAction& timed = script_[next_action_++];
        if (std::holds_alternative<action::Set>(timed.action)) last_set = timed.origin;
        apply_action(timed, state_, parts_.window);
    }
    if (!last_set.empty()) validate_script_frame(state_, last_set);
}

// The image size follows the window: a window resized by the user sets the settings'
// size; a size set by the panel or a script resizes the window.
void Viewer::follow_window_size() {
    const VkExtent2D size = parts_.window.framebuffer_size();
    if (size.width == 0 || size.height == 0) return;
    if (size.width != window_size_.width || size.height != window_size_.height) {
        window_size_ = size;
        state_.settings.width = size.width;
        state_.settings.height = size.height;
    } else if (!same_size(size, state_.settings)) {
        parts_.window.resize(state_.settings.width, state_.settings.height);
    }
}

void Viewer::apply_settings() {
    const ShadowSettings& shadow = state_.settings.shadow;
    if (shadow.strategy == ShadowStrategy::Multiview && static_cast<uint32_t>(shadow.cascades.count) > max_views_) {
        // One view per cascade: more cascades than the device's multiview limit cannot render.
        state_.status = "multiview: this device renders at most " + std::to_string(max_views_) + " views";
        state_.settings.shadow.strategy = ShadowStrategy::PerCascade;
    }
    if (renderer_ && !renderer_->needs_new_renderer(state_.settings)) {
        renderer_->update_settings(state_.settings);
        return;
    }
    // The last frame may still read the colour target; ~Renderer waits for the device.
    parts_.presenter.wait_for_last_frame();
    renderer_.reset();
    renderer_ = std::make_unique<renderer::Renderer>(parts_.context, state_.scene, state_.settings);
}

void Viewer::render_frame() {
    const VkExtent2D size = parts_.window.framebuffer_size();
    if (size.width == 0 || size.height == 0) {
        parts_.window.wait_events();  // minimised: nothing to draw into
        return;
    }
    const bool last_frame = job_.frames && frames_ + 1 == *job_.frames && job_.screenshot;
    std::optional<std::filesystem::path> capture_file = state_.requests.screenshot;
    if (last_frame) capture_file = *job_.screenshot;
    const bool capture_aov = capture_file && job_.screenshot_aov != Aov::None;
    const bool need_images = capture_aov || state_.settings.debug == DebugView::ShadowMap;

    // The previous frame's blit reads the colour target this render writes.
    parts_.presenter.wait_for_last_frame();
    renderer::FrameImages images;
    const Clock::time_point start = Clock::now();
    try {
        images = renderer_->render(state_.camera.camera(),
                                   need_images ? renderer::ReadbackMode::Images : renderer::ReadbackMode::None);
        good_settings_ = state_.settings;
    } catch (const InputError& error) {
        // E.g. a max distance inside the near plane: keep the last settings that worked.
        state_.status = error.what();
        state_.settings = good_settings_;
        return;
    }
    stats_.render_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    stats_.shadow_map_layers =
        state_.settings.debug == DebugView::ShadowMap ? renderer::shadow_map_strip(images) : renderer::GrayImage{};
    const bool presented = present_frame(capture_file && !capture_aov);
    if (presented && capture_file) finish_capture(*capture_file, images);
}

bool Viewer::present_frame(bool capture_window) {
    std::optional<present::Frame> frame = parts_.presenter.begin_frame();
    if (!frame) return false;  // the swapchain was recreated; try again next iteration
    output_.record_scene(frame->cmd, renderer_->color_target(), *frame, capture_window);
    if (state_.show_ui) parts_.ui.record(frame->cmd, *frame);
    output_.record_present_transition(frame->cmd, *frame);
    parts_.presenter.end_frame(*frame);
    ++frames_;
    return true;
}

void Viewer::finish_capture(const std::filesystem::path& file, const renderer::FrameImages& images) {
    parts_.presenter.wait_for_last_frame();
    Capture capture{file, job_.screenshot_aov};
    if (capture.aov == Aov::None) {
        capture.width = output_.captured_extent().width;
        capture.height = output_.captured_extent().height;
        capture.rgba = output_.captured_rgba();
    } else {
        capture.width = images.width;
        capture.height = images.height;
        capture.visibility = images.visibility;
        capture.cascade = images.cascade;
    }
    state_.requests.screenshot.reset();
    const bool automated_last = job_.frames && frames_ == *job_.frames;
    if (automated_last && job_.screenshot && file == *job_.screenshot) {
        final_capture_ = std::move(capture);  // written once validation has passed
        return;
    }
    write_capture(capture);
    state_.status = "wrote " + file.string();
    std::printf("penumbra: wrote %s\n", file.string().c_str());
}

void Viewer::save_settings() {
    const std::filesystem::path file = *state_.requests.save_settings;
    state_.requests.save_settings.reset();
    write_output_file(file, format_settings_file(state_.settings, state_.camera.camera(), state_.sun()));
    state_.status = "saved settings to " + file.string();
    std::printf("penumbra: saved settings to %s\n", file.string().c_str());
}

}  // namespace penumbra::view

#pragma once
// The viewer's frame loop: one iteration polls the window, replays the script's actions
// for this frame, runs the panel and input, makes the renderer follow the settings
// (recreated after the GPU is idle when a setting sizes its resources), renders, blits
// to the window, draws the panel and presents.
#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "capture.hpp"
#include "frame_output.hpp"
#include "panel.hpp"
#include "present/presenter.hpp"
#include "renderer/renderer.hpp"
#include "script.hpp"
#include "ui_overlay.hpp"
#include "view_job.hpp"
#include "view_state.hpp"

namespace penumbra::view {

struct ViewerParts {
    const renderer::AppContext& context;
    present::Window& window;
    present::Presenter& presenter;
    UiOverlay& ui;
};

class Viewer {
public:
    Viewer(const ViewJob& job, PreparedJob prepared, std::vector<TimedAction> script, const ViewerParts& parts);
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;

    // Runs until the window closes, `quit`, Escape or the job's frame count; returns the
    // number of frames presented.
    uint32_t run();
    // The automation screenshot of the last frame (--frames with --screenshot), if any.
    std::optional<Capture> take_final_capture() { return std::move(final_capture_); }
    const ViewState& state() const { return state_; }

private:
    bool keep_running() const;
    void step(float seconds);
    void run_script();
    void follow_window_size();
    void apply_settings();
    void render_frame();
    bool present_frame(bool capture_window);  // false: nothing presented this time
    void finish_capture(const std::filesystem::path& file, const renderer::FrameImages& images);
    void save_settings();

    const ViewJob& job_;
    ViewerParts parts_;
    ViewState state_;
    std::unique_ptr<renderer::Renderer> renderer_;
    RenderSettings good_settings_;  // the last settings that rendered
    FrameOutput output_;
    PanelStats stats_;
    std::vector<TimedAction> script_;
    size_t next_action_ = 0;
    uint32_t frames_ = 0;
    VkExtent2D window_size_{};
    uint32_t max_views_ = 0;  // maxMultiviewViewCount: the most cascades multiview can render
    std::optional<Capture> final_capture_;
};

}  // namespace penumbra::view

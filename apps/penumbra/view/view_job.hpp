#pragma once
// `penumbra view`: what the command line asks of the window viewer (docs/viewer.md).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "renderer/render_job.hpp"

namespace penumbra::view {

struct ViewJob {
    // Scene, config file, setting overrides, debug view and device, exactly as `render`
    // takes them (output and aov are unused).
    RenderJob render;
    std::optional<uint32_t> frames;                              // automation: render N frames, then exit
    std::optional<std::filesystem::path> screenshot;             // with frames: the last frame; F12 writes here too
    Aov screenshot_aov = Aov::None;                              // None: the window's image without the panel
    std::optional<std::filesystem::path> script;                 // timed actions (docs/viewer.md)
    std::filesystem::path settings_file = "penumbra-view.toml";  // F5 / "Save settings"
    bool save_settings_on_exit = false;                          // --save-settings with --frames
    bool show_ui = true;                                         // false: --no-ui (F1 toggles)
};

struct ViewSummary {
    uint32_t frames = 0;
    std::string device_name;
    std::optional<std::filesystem::path> screenshot;  // written at exit (automation)
};

// Opens the window and runs until it is closed (or `frames` frames). Throws InputError,
// DeviceError (no window system, no device), ValidationFailure, VulkanError.
ViewSummary run_view(const ViewJob& job);

}  // namespace penumbra::view

#pragma once
// Command-line flags of `penumbra view` beyond the render options it shares with
// `render` (docs/viewer.md).
#include <CLI/CLI.hpp>

#include <string>

#include "view/view_job.hpp"

namespace penumbra::cli {

struct RawViewOptions {
    std::string screenshot_aov, debug, screenshot, script, save_settings;
    bool no_ui = false;
};

void add_view_options(CLI::App& command, view::ViewJob& job, RawViewOptions& raw);

// Throws InputError naming the flag (unknown --screenshot-aov, --frames without a use...).
void convert_view_options(const RawViewOptions& raw, view::ViewJob& job);

}  // namespace penumbra::cli

#pragma once
// Command-line flags of the shadow filters (docs/filters.md), shared by `render` and
// `bench`. Ranges CLI11 can check are checked at parse time; the rest (16 or 32 taps,
// ...) by validate_shadow_settings, which names the setting.
#include <CLI/CLI.hpp>

#include <string>

#include "penumbra/scene/settings_overrides.hpp"

namespace penumbra::cli {

// Values that are converted after parsing so that errors can name the flag.
struct RawFilterOptions {
    std::string filter, pcss_quality;
    bool no_receiver_plane_bias = false;
    bool pcss_early_out = false;
    bool moments_poisson = false;
    bool msm_optimized_quantization = false;
};

void add_filter_options(CLI::App& command, SettingsOverrides& overrides, RawFilterOptions& raw);

// Throws InputError naming the flag for an unknown --filter or --pcss-quality.
void convert_filter_options(const RawFilterOptions& raw, SettingsOverrides& overrides);

}  // namespace penumbra::cli

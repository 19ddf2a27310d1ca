#include "filter_options.hpp"

#include "choice_help.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::cli {
namespace {

template <typename Enum>
Enum parse_name(const std::string& text, const std::string& flag, const std::map<std::string, Enum>& names) {
    const auto found = names.find(text);
    if (found != names.end()) return found->second;
    std::string expected;
    for (const auto& [name, value] : names) expected += (expected.empty() ? "" : ", ") + name;
    throw InputError(flag + ": unknown value \"" + text + "\" (expected " + expected + ")");
}

void add_comparison_options(CLI::App& command, FilterOverrides& f, RawFilterOptions& raw) {
    command.add_option("--filter", raw.filter,
                       "Shadow filter: " + choice_list(kShadowFilterChoices, FilterSettings{}.mode));
    command.add_flag("--no-receiver-plane-bias", raw.no_receiver_plane_bias,
                     "Disable the receiver-plane depth bias of pcf, poisson and pcss");
    command.add_option("--pcf-radius", f.pcf_radius, "pcf: grid radius R, (2R+1)^2 taps (0..5, default 1)")
        ->check(CLI::Range(0, 5));
    command.add_option("--poisson-taps", f.poisson_taps, "poisson: taps (16 or 32, default 16)")
        ->check(CLI::IsMember({16, 32}));
    command
        .add_option("--poisson-radius", f.poisson_radius,
                    "poisson (and --moments-poisson): disk radius in texels (0.5..32, default 2.5)")
        ->check(CLI::Range(0.5f, 32.0f));
    command.add_option("--pcss-blocker-taps", f.pcss_blocker_taps, "pcss: blocker-search taps (16 or 32)")
        ->check(CLI::IsMember({16, 32}));
    command.add_option("--pcss-quality", raw.pcss_quality, "pcss: filter taps low (16)|medium (25, default)|high (49)");
    command.add_flag("--pcss-early-out", raw.pcss_early_out, "pcss: fully shadowed when every blocker tap occludes");
    command.add_option("--pcss-max-penumbra", f.pcss_max_penumbra, "pcss: largest penumbra radius in texels (1..128)")
        ->check(CLI::Range(1.0f, 128.0f));
}

void add_moment_options(CLI::App& command, FilterOverrides& f, RawFilterOptions& raw) {
    command
        .add_option("--light-bleeding", f.light_bleeding_reduction,
                    "vsm/evsm/msm: light-bleeding reduction (0..0.95, default 0.2)")
        ->check(CLI::Range(0.0f, 0.95f));
    command.add_option("--blur-radius", f.blur_radius, "vsm/evsm/msm: Gaussian blur radius in texels (0..8, 0 = off)")
        ->check(CLI::Range(0, 8));
    command.add_flag("--moments-poisson", raw.moments_poisson, "vsm/evsm/msm: 16 Poisson taps of the moments");
    command
        .add_option("--evsm-positive-exponent", f.evsm_positive_exponent,
                    "evsm: positive warp exponent (0.1..100, default 40; clamped to 42 for 32-bit float)")
        ->check(CLI::Range(0.1f, 100.0f));
    command
        .add_option("--evsm-negative-exponent", f.evsm_negative_exponent,
                    "evsm: negative warp exponent (0.1..100, default 5; clamped to 42)")
        ->check(CLI::Range(0.1f, 100.0f));
    command.add_option("--evsm-components", f.evsm_components, "evsm: 2 (positive warp) or 4 (default)")
        ->check(CLI::IsMember({2, 4}));
    command.add_option("--msm-moment-bias", f.msm_moment_bias, "msm: moment bias (0..0.01, default 3e-5)")
        ->check(CLI::Range(0.0f, 0.01f));
    command.add_flag("--msm-quantization", raw.msm_optimized_quantization,
                     "msm: optimized moment quantization, 16-bit moments (Peters & Klein 2015)");
}

}  // namespace

void add_filter_options(CLI::App& command, SettingsOverrides& overrides, RawFilterOptions& raw) {
    add_comparison_options(command, overrides.filter, raw);
    add_moment_options(command, overrides.filter, raw);
    command
        .add_option("--angular-diameter", overrides.angular_diameter,
                    "The sun's angular diameter in degrees, for pcss (0..45; the scene's, default 0.53)")
        ->check(CLI::Range(0.0f, 45.0f));
}

void convert_filter_options(const RawFilterOptions& raw, SettingsOverrides& overrides) {
    FilterOverrides& f = overrides.filter;
    if (!raw.filter.empty()) f.mode = parse_name(raw.filter, "--filter", shadow_filter_names());
    if (!raw.pcss_quality.empty())
        f.pcss_quality = parse_name(raw.pcss_quality, "--pcss-quality", pcss_quality_names());
    if (raw.no_receiver_plane_bias) f.receiver_plane_bias = false;
    if (raw.pcss_early_out) f.pcss_early_out = true;
    if (raw.moments_poisson) f.moments_poisson = true;
    if (raw.msm_optimized_quantization) f.msm_optimized_quantization = true;
}

}  // namespace penumbra::cli

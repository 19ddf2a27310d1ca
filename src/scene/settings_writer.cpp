#include "penumbra/scene/settings_files.hpp"

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

#include "penumbra/errors.hpp"
#include "penumbra/settings.hpp"

namespace penumbra {
namespace {

// 9 significant digits: the shortest precision at which every float survives
// float -> decimal -> double -> float unchanged.
std::string real(float value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.9g", static_cast<double>(value));
    std::string result(text);
    // TOML needs a decimal point or exponent for a float; an integer-looking value is fine
    // (the reader accepts integers where numbers are expected) but "1.0" reads better.
    if (result.find_first_of(".eEn") == std::string::npos) result += ".0";
    return result;
}

std::string vec3(const glm::vec3& value) {
    return "[" + real(value.x) + ", " + real(value.y) + ", " + real(value.z) + "]";
}

std::string boolean(bool value) { return value ? "true" : "false"; }

// A choice as TOML writes it: its name, quoted.
template <typename Enum, std::size_t N>
std::string quoted(const ChoiceName<Enum> (&choices)[N], Enum value) {
    return std::string("\"") + choice_name(choices, value) + "\"";
}

void write_cascades(std::ostream& out, const ShadowSettings& shadow) {
    const CascadeSettings& c = shadow.cascades;
    out << "cascades = " << c.count << "\n";
    out << "resolution = " << c.resolution << "\n";
    out << "split_scheme = " << quoted(kSplitSchemeChoices, c.scheme) << "\n";
    out << "split_lambda = " << real(c.split_lambda) << "\n";
    if (!c.manual_splits.empty()) {
        out << "splits = [";
        for (size_t i = 0; i < c.manual_splits.size(); ++i) out << (i ? ", " : "") << real(c.manual_splits[i]);
        out << "]\n";
    }
    out << "max_distance = " << real(c.max_distance) << "\n";
    out << "fit = " << quoted(kFitModeChoices, c.fit) << "\n";
    out << "constant_bias = " << real(shadow.bias.constant) << "\n";
    out << "slope_bias = " << real(shadow.bias.slope) << "\n";
    out << "bias_clamp = " << real(shadow.bias.clamp) << "\n";
    out << "normal_offset = " << real(shadow.bias.normal_offset) << "\n";
    out << "blend_width = " << real(shadow.blend_width) << "\n";
    out << "strategy = " << quoted(kShadowStrategyChoices, shadow.strategy) << "\n";
    out << "cull_casters = " << boolean(shadow.cull_casters) << "\n";
    out << "caster_culling = " << quoted(kCasterCullingChoices, shadow.caster_culling) << "\n";
}

void write_filter(std::ostream& out, const FilterSettings& f) {
    namespace k = shadow_keys;
    out << k::kFilter << " = " << quoted(kShadowFilterChoices, f.mode) << "\n";
    out << k::kReceiverPlaneBias << " = " << boolean(f.receiver_plane_bias) << "\n";
    out << k::kPcfRadius << " = " << f.pcf_radius << "\n";
    out << k::kPoissonTaps << " = " << f.poisson_taps << "\n";
    out << k::kPoissonRadius << " = " << real(f.poisson_radius) << "\n";
    out << k::kPcssBlockerTaps << " = " << f.pcss_blocker_taps << "\n";
    out << k::kPcssQuality << " = " << quoted(kPcssQualityChoices, f.pcss_quality) << "\n";
    out << k::kPcssEarlyOut << " = " << boolean(f.pcss_early_out) << "\n";
    out << k::kPcssMaxPenumbra << " = " << real(f.pcss_max_penumbra) << "\n";
    out << k::kLightBleeding << " = " << real(f.light_bleeding_reduction) << "\n";
    out << k::kBlurRadius << " = " << f.blur_radius << "\n";
    out << k::kMomentsPoisson << " = " << boolean(f.moments_poisson) << "\n";
    out << k::kEvsmPositiveExponent << " = " << real(f.evsm_positive_exponent) << "\n";
    out << k::kEvsmNegativeExponent << " = " << real(f.evsm_negative_exponent) << "\n";
    out << k::kEvsmComponents << " = " << f.evsm_components << "\n";
    out << k::kMsmMomentBias << " = " << real(f.msm_moment_bias) << "\n";
    out << k::kMsmQuantization << " = " << boolean(f.msm_optimized_quantization) << "\n";
}

// The spot and point lights' shadow maps (docs/local-lights.md); the same keys as the flags.
void write_local_shadows(std::ostream& out, const LocalShadowSettings& local) {
    out << "local_shadow_budget = " << local.budget << "\n";
    out << "local_shadow_resolution = " << local.resolution << "\n";
    out << "local_shadow_sizing = " << quoted(kLocalShadowSizingChoices, local.sizing) << "\n";
}

}  // namespace

std::string format_settings_file(const RenderSettings& settings, const Camera& camera, const Light* sun) {
    std::ostringstream out;
    out << "# Written by penumbra view; `penumbra render SCENE --config THIS_FILE` reproduces the view.\n";
    out << "[output]\nwidth = " << settings.width << "\nheight = " << settings.height
        << "\nresolve = " << quoted(kShadowResolveChoices, settings.resolve) << "\n\n[shadow]\n";
    write_cascades(out, settings.shadow);
    write_filter(out, settings.shadow.filter);
    write_local_shadows(out, settings.local_shadows);
    out << "\n[camera]\neye = " << vec3(camera.eye) << "\ntarget = " << vec3(camera.target)
        << "\nup = " << vec3(camera.up) << "\nfov = " << real(camera.fov_y_degrees)
        << "\nnear = " << real(camera.near_plane) << "\nfar = " << real(camera.far_plane) << "\n";
    if (sun) {
        out << "\n[sun]\ndirection = " << vec3(sun->direction)
            << "\nangular_diameter = " << real(sun->angular_diameter_degrees) << "\n";
    }
    return out.str();
}

void write_settings_file(const std::filesystem::path& path, const RenderSettings& settings, const Camera& camera,
                         const Light* sun) {
    const std::string text = format_settings_file(settings, camera, sun);
    const std::filesystem::path temporary = path.string() + ".tmp";
    {
        std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
        file << text;
        if (!file.good()) throw InputError(path.string() + ": cannot write the settings file");
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw InputError(path.string() + ": cannot write the settings file");
    }
}

}  // namespace penumbra

#include "compare/compare_report.hpp"

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "image/output_files.hpp"
#include "image/png_io.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/settings.hpp"
#include "quality/error_images.hpp"

namespace penumbra::compare {
namespace {

using Json = nlohmann::ordered_json;

// The output files, in the order they are written and listed in the JSON.
constexpr const char* kRenderFile = "render_shadow.png";
constexpr const char* kHardFile = "reference_hard.png";
constexpr const char* kSoftFile = "reference_soft.png";
constexpr const char* kErrorFile = "error.png";
constexpr const char* kSoftErrorFile = "soft_error.png";
constexpr const char* kSideBySideFile = "side_by_side.png";

std::string filter_name(ShadowFilter filter) { return choice_name(kShadowFilterChoices, filter); }

Json settings_json(const RenderSettings& settings) {
    const ShadowSettings& shadow = settings.shadow;
    return {{"width", settings.width},
            {"height", settings.height},
            {"filter", filter_name(shadow.filter.mode)},
            {"fit", choice_name(kFitModeChoices, shadow.cascades.fit)},
            {"cascades", shadow.cascades.count},
            {"shadow_resolution", shadow.cascades.resolution},
            {"split_lambda", shadow.cascades.split_lambda},
            {"max_distance", shadow.cascades.max_distance},
            {"constant_bias", shadow.bias.constant},
            {"slope_bias", shadow.bias.slope},
            {"bias_clamp", shadow.bias.clamp},
            {"normal_offset", shadow.bias.normal_offset},
            {"blend_width", shadow.blend_width},
            {"contact_shadows", settings.contact.enabled},
            {"contact_length", settings.contact.length},
            {"contact_steps", settings.contact.steps},
            {"contact_thickness", settings.contact.thickness}};
}

Json class_json(const quality::ClassError& error) {
    return {{"percent", error.percent()}, {"pixels", error.wrong_pixels}, {"of", error.truth_pixels}};
}

Json hard_json(const quality::HardShadowMetrics& hard) {
    return {{"false_shadow", class_json(hard.false_shadow)},
            {"false_lit", class_json(hard.false_lit)},
            {"false_shadow_outside_edges", class_json(hard.false_shadow_outside_edges)},
            {"false_lit_outside_edges", class_json(hard.false_lit_outside_edges)},
            {"boundary_pixels", hard.boundary_pixels}};
}

Json contact_json(const quality::ContactMetrics& contact) {
    return {{"reach_m", kContactReachMetres},
            {"band_px", kContactBandPixels},
            {"contact_pixels", contact.contact_pixels},
            {"band_pixels", contact.band_pixels},
            {"false_lit", class_json(contact.false_lit)},
            {"false_shadow", class_json(contact.false_shadow)}};
}

Json soft_json(const quality::SoftShadowMetrics& soft) {
    return {{"mean_abs_error", soft.mean_abs_error},
            {"p95_abs_error", soft.p95_abs_error},
            {"edge_mean_abs_error", soft.edge_mean_abs_error},
            {"penumbra_pixels_render", soft.penumbra_pixels_render},
            {"penumbra_pixels_reference", soft.penumbra_pixels_reference},
            {"edge_length_px", soft.edge_length_px},
            {"penumbra_width_render_px", soft.penumbra_width_render_px},
            {"penumbra_width_reference_px", soft.penumbra_width_reference_px},
            {"penumbra_width_error_px", soft.penumbra_width_error_px}};
}

Json stability_json(const quality::StabilityMetrics& stability) {
    if (stability.frames < 2) return nullptr;
    return {{"frames", stability.frames},           {"compared_pixels", stability.compared_pixels},
            {"mean_change", stability.mean_change}, {"p99_change", stability.p99_change},
            {"max_change", stability.max_change},   {"flicker_percent", stability.flicker_percent}};
}

Json pixels_json(const PixelCounts& pixels) {
    return {{"total", pixels.total},
            {"geometry", pixels.geometry},
            {"facing_away", pixels.facing_away},
            {"beyond_shadow_distance", pixels.beyond_shadow_distance},
            {"outside_light", pixels.outside_light},
            {"not_receiving", pixels.not_receiving},
            {"evaluated", pixels.evaluated},
            {"shadowed_in_reference", pixels.shadowed},
            {"shadowed_percent", pixels.shadowed_percent()}};
}

Json vec3_json(const glm::vec3& v) { return {v.x, v.y, v.z}; }

const char* light_type_name(const CompareResult& result) {
    if (!result.local_light) return "sun";
    return result.local_light->type == LightType::Spot ? "spot" : "point";
}

// Which light was compared: its index in [[lights]], its kind and what shapes its reference.
Json light_json(const CompareResult& result) {
    Json light = {{"index", result.light_index}, {"type", light_type_name(result)}};
    if (!result.local_light) return light;
    const Light& local = *result.local_light;
    light["position"] = vec3_json(local.position);
    light["range"] = local.range;
    light["radius"] = local.radius;
    if (local.type == LightType::Spot) {
        light["direction"] = vec3_json(glm::normalize(local.direction));
        light["inner_angle_degrees"] = local.inner_angle_degrees;
        light["outer_angle_degrees"] = local.outer_angle_degrees;
        light["min_cone_factor"] = kMinConeFactor;
    }
    return light;
}

Json reference_json(const CompareResult& result) {
    Json reference = {{"tracer", "embree3"}, {"triangles", result.triangles}, {"rays_per_pixel", result.job.rays}};
    if (!result.local_light) {  // a local light's position and radius are in "light"
        reference["to_sun"] = vec3_json(result.to_sun);
        reference["sun_angular_diameter_degrees"] = result.sun_angular_diameter_degrees;
    }
    reference["edge_band_px"] = result.job.edge_band;
    reference["nearest_texel_world_size"] = result.nearest_texel_world_size;
    return reference;
}

std::filesystem::path json_path(const CompareJob& job) { return job.json ? *job.json : job.out_dir / "compare.json"; }

}  // namespace

std::string format_compare_summary(const CompareResult& result) {
    const quality::HardShadowMetrics& hard = result.hard;
    const quality::SoftShadowMetrics& soft = result.soft;
    char text[1024];
    std::snprintf(text, sizeof(text),
                  "penumbra compare: %s, %s light %d, %ux%u, filter %s, %llu evaluated pixels, %u rays (%s)\n"
                  "  hard: false shadow %.3f%% (%.3f%% outside edges), false lit %.3f%% (%.3f%% outside edges)\n"
                  "  soft: mean |error| %.4f, p95 %.4f, edge %.4f, penumbra width %.2f px (reference %.2f)\n",
                  result.scene.c_str(), light_type_name(result), result.light_index, result.settings.width,
                  result.settings.height, filter_name(result.settings.shadow.filter.mode).c_str(),
                  static_cast<unsigned long long>(result.pixels.evaluated), result.job.rays, result.device_name.c_str(),
                  hard.false_shadow.percent(), hard.false_shadow_outside_edges.percent(), hard.false_lit.percent(),
                  hard.false_lit_outside_edges.percent(), soft.mean_abs_error, soft.p95_abs_error,
                  soft.edge_mean_abs_error, soft.penumbra_width_render_px, soft.penumbra_width_reference_px);
    std::string summary = text;
    if (result.contact.band_pixels > 0) {
        std::snprintf(text, sizeof(text),
                      "  near contacts (%u px of %llu pixels shadowed within %.2f m): false lit %.3f%%, false shadow "
                      "%.3f%%\n",
                      kContactBandPixels, static_cast<unsigned long long>(result.contact.contact_pixels),
                      kContactReachMetres, result.contact.false_lit.percent(), result.contact.false_shadow.percent());
        summary += text;
    }
    std::snprintf(text, sizeof(text), "  shadowed: %.2f%% of the evaluated pixels in the reference\n",
                  result.pixels.shadowed_percent());
    summary += text;
    if (result.pixels.shadowed_percent() > kMostlyShadowedPercent) {
        std::snprintf(text, sizeof(text),
                      "  warning: more than %.0f%% of the evaluated pixels are in shadow: geometry such as a sky box "
                      "or dome may block the light everywhere (cast_shadows = false or exclude_casters in the scene "
                      "file)\n",
                      kMostlyShadowedPercent);
        summary += text;
    }
    if (result.stability.frames >= 2) {
        std::snprintf(text, sizeof(text),
                      "  stability over %u frames: mean change %.4f, p99 %.4f, max %.4f, flicker %.3f%%\n",
                      result.stability.frames, result.stability.mean_change, result.stability.p99_change,
                      result.stability.max_change, result.stability.flicker_percent);
        summary += text;
    }
    if (!result.stability_note.empty()) summary += "  stability: " + result.stability_note + "\n";
    if (result.sampling_noise.max_change > 0.0) {
        std::snprintf(text, sizeof(text),
                      "  sampling noise (frame 0 with its pattern rotated): mean change %.5f, p99 %.4f, max %.4f\n",
                      result.sampling_noise.mean_change, result.sampling_noise.p99_change,
                      result.sampling_noise.max_change);
        summary += text;
    }
    return summary;
}

std::string compare_json(const CompareResult& result) {
    const Json images = {{"render", kRenderFile}, {"reference_hard", kHardFile},  {"reference_soft", kSoftFile},
                         {"error", kErrorFile},   {"soft_error", kSoftErrorFile}, {"side_by_side", kSideBySideFile}};
    const Json report = {
        {"penumbra_version", result.version},
        {"device", result.device_name},
        {"scene", result.scene},
        {"settings", settings_json(result.settings)},
        {"light", light_json(result)},
        {"reference", reference_json(result)},
        {"pixels", pixels_json(result.pixels)},
        {"hard", hard_json(result.hard)},
        {"contact", contact_json(result.contact)},
        {"soft", soft_json(result.soft)},
        {"stability", stability_json(result.stability)},
        {"stability_note", result.stability_note.empty() ? Json(nullptr) : Json(result.stability_note)},
        {"sampling_noise",
         {{"compared_pixels", result.sampling_noise.compared_pixels},
          {"mean_change", result.sampling_noise.mean_change},
          {"p99_change", result.sampling_noise.p99_change},
          {"max_change", result.sampling_noise.max_change}}},
        {"timings_ms",
         {{"render", result.timings.render_ms}, {"bvh", result.timings.bvh_ms}, {"trace", result.timings.trace_ms}}},
        {"images", images}};
    return report.dump(2) + "\n";
}

std::vector<std::filesystem::path> compare_output_paths(const CompareJob& job) {
    std::vector<std::filesystem::path> paths;
    for (const char* name : {kRenderFile, kHardFile, kSoftFile, kErrorFile, kSoftErrorFile, kSideBySideFile}) {
        paths.push_back(job.out_dir / name);
    }
    paths.push_back(json_path(job));
    return paths;
}

// --out-dir may be created; the folder of a --json path, like -o's, must exist.
void check_compare_outputs(const CompareJob& job) {
    for (const std::filesystem::path& path : compare_output_paths(job)) {
        checked_output_path(path, OutputFolders::MayBeCreated);
    }
    if (job.json) checked_output_path(*job.json, OutputFolders::MustExist);
}

// All seven files or none: written to temporaries, renamed together at the end.
std::vector<std::filesystem::path> write_compare_outputs(const CompareResult& result) {
    const std::filesystem::path& dir = result.job.out_dir;
    const std::vector<std::filesystem::path> paths = compare_output_paths(result.job);
    OutputFiles output(paths, OutputFolders::MayBeCreated);

    const quality::VisibilityComparison& frame = result.images.frame;
    const uint32_t width = frame.width;
    const uint32_t height = frame.height;
    std::vector<float> hard(frame.hard.begin(), frame.hard.end());
    const quality::RgbaImage error_image = quality::hard_error_image(frame, result.images.color_rgba8);
    const quality::RgbaImage panels[] = {quality::gray_to_rgba(width, height, frame.rendered),
                                         quality::gray_to_rgba(width, height, frame.soft), error_image};
    const quality::RgbaImage side_by_side = quality::side_by_side(panels);

    output.write(dir / kRenderFile, encode_png_gray16(width, height, quality::to_gray16(frame.rendered)));
    output.write(dir / kHardFile, encode_png_gray8(width, height, quality::to_gray8(hard)));
    output.write(dir / kSoftFile, encode_png_gray16(width, height, quality::to_gray16(frame.soft)));
    output.write(dir / kErrorFile, encode_png_rgba8(width, height, error_image.pixels));
    output.write(dir / kSoftErrorFile, encode_png_gray8(width, height, quality::soft_error_image(frame)));
    output.write(dir / kSideBySideFile, encode_png_rgba8(side_by_side.width, side_by_side.height, side_by_side.pixels));
    output.write(json_path(result.job), compare_json(result));
    output.commit();
    return paths;
}

}  // namespace penumbra::compare

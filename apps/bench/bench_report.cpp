#include "bench/bench_report.hpp"

#include "image/output_files.hpp"

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <variant>

#include "penumbra/errors.hpp"

namespace penumbra::bench {
namespace {

using Json = nlohmann::ordered_json;

Json summary_json(const Summary& summary) {
    return Json{{"median", summary.median}, {"p95", summary.p95},   {"min", summary.min},
                {"max", summary.max},       {"mean", summary.mean}, {"samples", summary.samples}};
}

Json counts_json(const CountSummary& counts) {
    return Json{{"mean", counts.mean}, {"min", counts.min}, {"max", counts.max}};
}

Json setting_json(const SettingValue& value) {
    return std::visit([](const auto& stored) { return Json(stored); }, value);
}

// The tools' output settings, then every ShadowSystem setting by its declaration's name.
Json settings_json(const RenderSettings& settings) {
    Json json{{"width", settings.width},
              {"height", settings.height},
              {"resolve", choice_name(kShadowResolveChoices, settings.resolve)}};
    for (const SettingDeclaration& setting : kSettingDeclarations)
        json[setting.name] = setting_json(setting.get(settings));
    return json;
}

Json run_json(const BenchJob& job) {
    return Json{{"frames", job.frames},
                {"warmup", job.warmup},
                {"camera_path", camera_path_name(job.camera_path)},
                {"light_path", light_path_name(job.light_path)},
                {"readback", job.readback},
                {"animate_dynamic", job.animate_dynamic},
                {"toggle", job.toggle_text.empty() ? Json(nullptr) : Json(job.toggle_text)},
                {"ceiling", choice_name(kCeilingChoices, job.ceiling)},
                {"taps", is_tap_ceiling(job.ceiling) ? Json(job.taps) : Json(nullptr)},
                {"validation", job.render.device.validation}};
}

Json timings_json(const std::vector<std::string>& order, const std::map<std::string, Summary>& summaries) {
    Json timings = Json::object();
    for (const std::string& name : order) timings[name] = summary_json(summaries.at(name));
    return timings;
}

Json ceiling_json(const std::optional<CeilingReport>& ceiling) {
    if (!ceiling) return nullptr;
    return Json{{"mode", ceiling->mode},
                {"unit", ceiling->unit},
                {"work_per_frame", ceiling->work_per_frame},
                {"per_second", ceiling->per_second}};
}

Json local_shadow_json(const LocalShadowReport& light) {
    return Json{{"light", light.light},
                {"type", light.type},
                {"layers", light.layers},
                {"resolution", counts_json(light.resolution)},
                {"near_plane", light.near_plane},
                {"draws", counts_json(light.draws)},
                {"triangles", counts_json(light.triangles)},
                {"layers_kept", counts_json(light.layers_kept)}};
}

// The shadowed spot/point lights; their map's bytes are part of "shadow_map_bytes".
Json local_shadows_json(const std::vector<LocalShadowReport>& lights) {
    Json array = Json::array();
    uint32_t layers = 0;
    for (const LocalShadowReport& light : lights) {
        array.push_back(local_shadow_json(light));
        layers += light.layers;
    }
    return Json{{"shadowed_lights", lights.size()}, {"layers", layers}, {"lights", array}};
}

std::string format_row(const char* kind, const std::string& name, const Summary& summary) {
    char line[160];
    std::snprintf(line, sizeof(line), "%-4s %-22s %10.3f %10.3f %10.3f\n", kind, name.c_str(), summary.median,
                  summary.p95, summary.min);
    return line;
}

// The sun's technique as the header names it: the cascades' count, resolution and strategy,
// or the virtual shadow map's levels, resolution and pool.
std::string format_technique(const RenderSettings& s) {
    char text[160];
    if (s.shadow.technique == ShadowTechnique::Virtual) {
        const VirtualShadowSettings& v = s.shadow.virtual_maps;
        std::snprintf(text, sizeof(text), "virtual shadow map %d levels x %u, %u MiB pool", v.levels, v.resolution,
                      v.pool_mib);
    } else {
        std::snprintf(text, sizeof(text), "%d cascades x %u, %s", s.shadow.cascades.count, s.shadow.cascades.resolution,
                      choice_name(kShadowStrategyChoices, s.shadow.strategy));
    }
    return text;
}

std::string format_header(const BenchResult& result) {
    const RenderSettings& s = result.settings;
    char line[512];
    std::snprintf(line, sizeof(line),
                  "penumbra bench: %s (%llu triangles, %zu instances) on %s (%s)\n"
                  "%ux%u, %s, culling %s, face culling %s; %u frames after %u warm-up, camera %s, light %s\n",
                  result.scene.spec.c_str(), static_cast<unsigned long long>(result.scene.triangles),
                  result.scene.instances, result.device.name.c_str(), result.device.driver.c_str(), s.width, s.height,
                  format_technique(s).c_str(), s.shadow.cull_casters ? "on" : "off",
                  choice_name(kCasterCullingChoices, s.shadow.caster_culling), result.job.frames, result.job.warmup,
                  camera_path_name(result.job.camera_path), light_path_name(result.job.light_path));
    if (!result.job.toggle_text.empty()) {
        return line + ("every measured frame toggles " + result.job.toggle_text + " (update_settings)\n");
    }
    return line;
}

std::string format_cascades(const BenchResult& result) {
    if (result.cascades.empty()) return "";
    std::string text = "cascade  draws/frame  triangles/frame (mean)\n";
    char line[128];
    for (size_t c = 0; c < result.cascades.size(); ++c) {
        std::snprintf(line, sizeof(line), "%7zu %12.0f %16.0f\n", c, result.cascades[c].draws.mean,
                      result.cascades[c].triangles.mean);
        text += line;
    }
    return text;
}

// "1024", or "256-1024" when the resolution changed between frames.
std::string format_resolution(const CountSummary& resolution) {
    if (resolution.min == resolution.max) return std::to_string(resolution.min);
    return std::to_string(resolution.min) + "-" + std::to_string(resolution.max);
}

std::string format_local_shadows(const BenchResult& result) {
    if (result.local_shadows.empty()) return "";
    char line[160];
    std::snprintf(line, sizeof(line), "%zu shadowed spot/point light(s) (budget %u)\n", result.local_shadows.size(),
                  result.settings.local_shadows.budget);
    std::string text = line;
    text += "light  type   layers  resolution  near (m)  draws/frame  triangles/frame (mean)\n";
    for (const LocalShadowReport& light : result.local_shadows) {
        std::snprintf(line, sizeof(line), "%5u  %-5s  %6u  %10s  %8.2f  %11.0f  %21.0f\n", light.light,
                      light.type.c_str(), light.layers, format_resolution(light.resolution).c_str(),
                      static_cast<double>(light.near_plane), light.draws.mean, light.triangles.mean);
        text += line;
    }
    return text;
}

Json virtual_map_json(const std::optional<VirtualReport>& report) {
    if (!report) return nullptr;
    return Json{{"texel_world_size", report->texel_world_size},
                {"pool_pages", report->pool_pages},
                {"pool_bytes", report->pool_bytes},
                {"pages_requested", counts_json(report->pages_requested)},
                {"pages_rendered", counts_json(report->pages_rendered)},
                {"pages_cached", counts_json(report->pages_cached)},
                {"pages_unserved", counts_json(report->pages_unserved)},
                {"pages_resident", counts_json(report->pages_resident)},
                {"pages_evicted", counts_json(report->pages_evicted)},
                {"page_draws", counts_json(report->page_draws)},
                {"page_draw_triangles", counts_json(report->page_draw_triangles)},
                {"dropped_page_draws", counts_json(report->dropped_page_draws)},
                {"pages_deferred", counts_json(report->pages_deferred)},
                {"invalidated_all_frames", report->invalidated_all_frames}};
}

std::string format_virtual_map(const BenchResult& result) {
    if (!result.virtual_map) return "";
    const VirtualReport& v = *result.virtual_map;
    char line[256];
    std::snprintf(line, sizeof(line),
                  "virtual pages/frame (mean): requested %.0f, drawn %.0f, cached %.0f, unserved %.0f, resident %.0f "
                  "of %u (%.0f MiB pool)\n",
                  v.pages_requested.mean, v.pages_rendered.mean, v.pages_cached.mean, v.pages_unserved.mean,
                  v.pages_resident.mean, v.pool_pages, static_cast<double>(v.pool_bytes) / (1024.0 * 1024.0));
    return line;
}

std::string format_shadow_map_bytes(const BenchResult& result) {
    char line[160];
    std::snprintf(line, sizeof(line), "shadow maps: %llu bytes (%.1f MiB)%s\n",
                  static_cast<unsigned long long>(result.shadow_map_bytes),
                  static_cast<double>(result.shadow_map_bytes) / (1024.0 * 1024.0),
                  result.local_shadows.empty() ? "" : ", the spot/point lights' layers included");
    return line;
}

}  // namespace

std::string format_bench_table(const BenchResult& result) {
    std::string text = format_header(result);
    char line[160];
    std::snprintf(line, sizeof(line), "%-4s %-22s %10s %10s %10s\n", "", "pass", "median ms", "p95 ms", "min ms");
    text += line;
    for (const std::string& name : result.gpu_pass_order) text += format_row("gpu", name, result.gpu_ms.at(name));
    for (const std::string& name : result.cpu_step_order) text += format_row("cpu", name, result.cpu_ms.at(name));
    if (result.frames_without_gpu_times > 0) {
        text += "note: " + std::to_string(result.frames_without_gpu_times) +
                " frame(s) had no GPU timestamps (unsupported by the queue, or not ready)\n";
    }
    text += format_cascades(result);
    text += format_virtual_map(result);
    text += format_local_shadows(result);
    text += format_shadow_map_bytes(result);
    if (result.ceiling) {
        std::snprintf(line, sizeof(line), "ceiling %s: %llu %s per frame, %.4g per second\n",
                      result.ceiling->mode.c_str(), static_cast<unsigned long long>(result.ceiling->work_per_frame),
                      result.ceiling->unit.c_str(), result.ceiling->per_second);
        text += line;
    }
    return text;
}

std::string bench_json(const BenchResult& result) {
    Json cascades = Json::array();
    for (size_t c = 0; c < result.cascades.size(); ++c) {
        cascades.push_back(Json{{"index", c},
                                {"draws", counts_json(result.cascades[c].draws)},
                                {"triangles", counts_json(result.cascades[c].triangles)},
                                {"texels_rendered", counts_json(result.cascades[c].texels_rendered)},
                                {"texels_copied", counts_json(result.cascades[c].texels_copied)},
                                {"cache_reused_frames", result.cascades[c].cache_reused_frames}});
    }
    const Json document{
        {"schema", "penumbra-bench/1"},
        {"penumbra_version", result.version},
        {"device",
         {{"name", result.device.name},
          {"driver", result.device.driver},
          {"type", result.device.type},
          {"api_version", result.device.api_version},
          {"timestamp_valid_bits", result.device.timestamp_valid_bits},
          {"timestamp_period_ns", result.device.timestamp_period_ns}}},
        {"scene",
         {{"spec", result.scene.spec},
          {"meshes", result.scene.meshes},
          {"materials", result.scene.materials},
          {"instances", result.scene.instances},
          {"triangles", result.scene.triangles},
          {"vertices", result.scene.vertices}}},
        {"settings", settings_json(result.settings)},
        {"run", run_json(result.job)},
        {"gpu_ms", timings_json(result.gpu_pass_order, result.gpu_ms)},
        {"gpu_ms_per_frame", result.gpu_ms_per_frame},
        {"cpu_ms", timings_json(result.cpu_step_order, result.cpu_ms)},
        {"frames_without_gpu_times", result.frames_without_gpu_times},
        {"cascades", cascades},
        {"virtual_map", virtual_map_json(result.virtual_map)},
        {"local_shadows", local_shadows_json(result.local_shadows)},
        {"shadow_map_bytes", result.shadow_map_bytes},
        {"ceiling", ceiling_json(result.ceiling)},
    };
    return document.dump(2) + "\n";
}

void write_bench_json(const BenchResult& result, const std::filesystem::path& path) {
    write_output_file(path, bench_json(result));
}

}  // namespace penumbra::bench

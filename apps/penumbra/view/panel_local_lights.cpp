// The "Local lights" section of the viewer panel: the local shadow budget and resolution,
// and per shadowed spot/point light what its shadow pass did in the last frame.
#include <imgui.h>

#include <algorithm>
#include <bit>
#include <string>

#include "panel.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::view {
namespace {

constexpr int kMinLocalResolutionLog2 = 4;   // 16 texels, the smallest validate_render_settings accepts
constexpr int kMaxLocalResolutionLog2 = 13;  // 8192

struct LocalLightCounts {
    uint32_t lit = 0;              // spot and point lights (the first kMaxLocalLights are lit)
    uint32_t casting = 0;          // of those, the ones with cast_shadows
    uint32_t shadowed = 0;         // with a shadow map in the last frame
    double shadow_pass_ms = -1.0;  // GPU time of "shadow_local"; < 0 when not timed
};

LocalLightCounts count_local_lights(const PanelStats& stats) {
    LocalLightCounts counts;
    if (stats.lights) {
        for (const Light& light : *stats.lights) {
            if (light.type == LightType::Directional) continue;
            ++counts.lit;
            if (light.cast_shadows) ++counts.casting;
        }
    }
    if (!stats.frame) return counts;
    counts.shadowed = static_cast<uint32_t>(stats.frame->local_shadows.size());
    for (const gpu::ScopeTime& scope : stats.frame->gpu_times) {
        if (scope.name == "shadow_local") counts.shadow_pass_ms = scope.milliseconds;
    }
    return counts;
}

// These settings size the shared layered shadow map (and fix which maps follow the screen
// coverage), so changing them re-creates the renderer.
void local_shadow_controls(LocalShadowSettings& local) {
    int budget = static_cast<int>(local.budget);
    if (ImGui::SliderInt("shadow budget", &budget, 0, static_cast<int>(kMaxLocalShadowBudget))) {
        local.budget = static_cast<uint32_t>(budget);
    }
    // A slider over powers of two, labelled with the resolution itself (which need not be one:
    // --local-shadow-resolution takes any size from 16 to 8192).
    int exponent = std::clamp(static_cast<int>(std::bit_width(local.resolution)) - 1, kMinLocalResolutionLog2,
                              kMaxLocalResolutionLog2);
    const std::string label = std::to_string(local.resolution) + " texels";
    if (ImGui::SliderInt("shadow resolution", &exponent, kMinLocalResolutionLog2, kMaxLocalResolutionLog2,
                         label.c_str())) {
        local.resolution = 1u << exponent;
    }
    bool coverage = local.sizing == LocalShadowSizing::Coverage;
    if (ImGui::Checkbox("size by screen coverage (resolution = the largest)", &coverage)) {
        local.sizing = coverage ? LocalShadowSizing::Coverage : LocalShadowSizing::Fixed;
    }
}

const char* light_type_name(const PanelStats& stats, uint32_t light) {
    if (!stats.lights || light >= stats.lights->size()) return "?";
    return (*stats.lights)[light].type == LightType::Spot ? "spot" : "point";
}

void local_shadow_table(const PanelStats& stats) {
    constexpr int kColumns = 7;
    if (!ImGui::BeginTable("local shadows", kColumns, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) return;
    for (const char* heading : {"light", "type", "layers", "resolution", "near (m)", "draws", "triangles"}) {
        ImGui::TableSetupColumn(heading);
    }
    ImGui::TableHeadersRow();
    for (const LocalShadowInfo& light : stats.frame->local_shadows) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::Text("%u", light.light);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(light_type_name(stats, light.light));
        ImGui::TableNextColumn();
        ImGui::Text("%u", light.layers);
        ImGui::TableNextColumn();
        ImGui::Text("%u", light.resolution);
        ImGui::TableNextColumn();
        ImGui::Text("%.2f", static_cast<double>(light.near_plane));
        ImGui::TableNextColumn();
        ImGui::Text("%u", light.draws);
        ImGui::TableNextColumn();
        ImGui::Text("%llu", static_cast<unsigned long long>(light.triangles));
    }
    ImGui::EndTable();
}

}  // namespace

void draw_local_lights(LocalShadowSettings& local, const PanelStats& stats) {
    if (!ImGui::CollapsingHeader("Local lights", ImGuiTreeNodeFlags_DefaultOpen)) return;
    local_shadow_controls(local);
    const LocalLightCounts counts = count_local_lights(stats);
    ImGui::Text("%u spot/point light(s), %u cast shadows, %u shadowed", counts.lit, counts.casting, counts.shadowed);
    if (counts.casting > counts.shadowed && stats.frame) {
        ImGui::TextDisabled("%u beyond the budget (or the light limit) render unshadowed",
                            counts.casting - counts.shadowed);
    }
    if (counts.shadow_pass_ms >= 0.0) ImGui::Text("GPU shadow_local %.3f ms", counts.shadow_pass_ms);
    if (stats.frame && !stats.frame->local_shadows.empty()) local_shadow_table(stats);
}

}  // namespace penumbra::view

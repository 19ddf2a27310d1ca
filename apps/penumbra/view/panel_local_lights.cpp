// The "Local lights" section of the viewer panel: the local shadow budget and resolution,
// and per shadowed spot/point light what its shadow pass did in the last frame.
#include <imgui.h>

#include <string>

#include "panel.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::view {
namespace {

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

void draw_local_lights(Settings& settings, const PanelStats& stats) {
    if (!ImGui::CollapsingHeader("Local lights", ImGuiTreeNodeFlags_DefaultOpen)) return;
    // These settings size the shared layered shadow map: changing them re-creates the renderer.
    draw_setting_group(settings, "local_shadows", stats.frame);
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

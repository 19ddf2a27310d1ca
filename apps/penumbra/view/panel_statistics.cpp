// The statistics sections of the viewer panel: frame and GPU pass times, per-cascade
// depth range, texel density and load, and the shadow-map layers.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "panel.hpp"

namespace penumbra::view {
namespace {

void timing_section(const PanelStats& stats) {
    if (!ImGui::CollapsingHeader("Timings", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Text("device: %s", stats.device_name.c_str());
    ImGui::Text("frame %.2f ms (%.1f fps), Renderer::render %.2f ms", stats.frame_ms,
                stats.frame_ms > 0.0 ? 1000.0 / stats.frame_ms : 0.0, stats.render_ms);
    ImGui::Text("shadow maps: %.1f MiB", static_cast<double>(stats.shadow_map_bytes) / (1024.0 * 1024.0));
    if (!stats.frame) return;
    if (stats.frame->gpu_times.empty()) {
        ImGui::TextDisabled("GPU pass times: the queue has no timestamps");
        return;
    }
    for (const gpu::ScopeTime& scope : stats.frame->gpu_times) {
        ImGui::Text("GPU %-20s %8.3f ms", scope.name.c_str(), scope.milliseconds);
    }
    const renderer::CpuTimes& cpu = stats.frame->cpu_times;
    ImGui::Text("CPU setup %.2f, culling %.2f, recording %.2f ms", cpu.cascade_setup_ms, cpu.culling_ms,
                cpu.recording_ms);
}

void cascade_table(const renderer::FrameInfo& frame) {
    if (!ImGui::BeginTable("cascades", 8, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) return;
    for (const char* heading : {"#", "range (m)", "texels/m", "draws", "triangles", "cache", "texels drawn", "copied"})
        ImGui::TableSetupColumn(heading);
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < frame.cascades.size(); ++i) {
        const CascadeInfo& cascade = frame.cascades[i];
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::Text("%zu", i);
        ImGui::TableNextColumn();
        ImGui::Text("%.2f - %.2f", cascade.split_near, cascade.split_far);
        ImGui::TableNextColumn();
        ImGui::Text("%.1f", cascade.texel_world_size > 0.0f ? 1.0f / cascade.texel_world_size : 0.0f);
        ImGui::TableNextColumn();
        ImGui::Text("%u", cascade.draws);
        ImGui::TableNextColumn();
        ImGui::Text("%llu", static_cast<unsigned long long>(cascade.triangles));
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(cascade.cache_reused ? "kept" : "drawn");
        ImGui::TableNextColumn();
        ImGui::Text("%llu", static_cast<unsigned long long>(cascade.texels_rendered));
        ImGui::TableNextColumn();
        ImGui::Text("%llu", static_cast<unsigned long long>(cascade.texels_copied));
    }
    ImGui::EndTable();
}

// What the frame drew into a cached cascade, outlined over its cells: the static casters'
// rectangles in red, the dynamic instances' reach in yellow (a cascade drawn whole gets no
// outline).
void refreshed_regions(ImDrawList* draw, ImVec2 layer_origin, float layer_side, const CascadeInfo& cascade,
                       uint32_t resolution) {
    const float scale = layer_side / static_cast<float>(std::max(resolution, 1u));
    const auto outline = [&](const TexelRegion& region, ImU32 colour) {
        const ImVec2 p0(layer_origin.x + region.x * scale, layer_origin.y + region.y * scale);
        const ImVec2 p1(p0.x + std::max(region.width * scale, 1.0f), p0.y + std::max(region.height * scale, 1.0f));
        draw->AddRect(p0, p1, colour);
    };
    if (cascade.cache_reused) {
        for (const TexelRegion& region : cascade.redrawn) outline(region, IM_COL32(255, 64, 64, 255));
    }
    for (const TexelRegion& region : cascade.dynamic_regions) outline(region, IM_COL32(255, 220, 0, 255));
}

// The layers as a grid of filled cells (the stock ImGui 1.86 Vulkan backend cannot bind
// user textures): each cell averages a block of texels of the 8-bit strip.
void shadow_map_layers(const renderer::GrayImage& strip, const renderer::FrameInfo* frame) {
    if (strip.width == 0 || strip.height == 0) {
        ImGui::TextDisabled("choose debug view \"shadow-map layers\" to show them");
        return;
    }
    const uint32_t layers = strip.width / strip.height;
    constexpr uint32_t kCells = 48;  // per layer side
    const float cell = std::max(1.0f, (ImGui::GetContentRegionAvail().x / static_cast<float>(layers)) / kCells);
    const uint32_t block = std::max(1u, strip.height / kCells);
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    for (uint32_t layer = 0; layer < layers; ++layer) {
        for (uint32_t y = 0; y < kCells; ++y) {
            for (uint32_t x = 0; x < kCells; ++x) {
                const uint32_t px = std::min(layer * strip.height + x * block, strip.width - 1);
                const uint32_t py = std::min(y * block, strip.height - 1);
                const uint8_t value = strip.pixels[size_t{py} * strip.width + px];
                const ImVec2 p0(origin.x + (layer * kCells + x) * cell, origin.y + y * cell);
                draw->AddRectFilled(p0, ImVec2(p0.x + cell, p0.y + cell), IM_COL32(value, value, value, 255));
            }
        }
    }
    for (uint32_t layer = 0; frame && layer < layers && layer < frame->cascades.size(); ++layer) {
        refreshed_regions(draw, ImVec2(origin.x + layer * kCells * cell, origin.y), kCells * cell,
                          frame->cascades[layer], strip.height);
    }
    ImGui::Dummy(ImVec2(layers * kCells * cell, kCells * cell));
    if (frame) ImGui::TextDisabled("with the shadow cache: red, static casters drawn again; yellow, dynamic instances");
}

// The virtual shadow map's frame: its pages (the GPU's counts arrive frames in flight
// later), its pool, and the texel size of the levels.
void virtual_map_section(const VirtualShadowInfo& map) {
    const double pool_mib = static_cast<double>(map.pool_bytes) / (1024.0 * 1024.0);
    ImGui::Text("pool %u pages (%.0f MiB): %u resident (%.0f %%)", map.pool_pages, pool_mib, map.pages_resident,
                map.pool_pages ? 100.0 * map.pages_resident / map.pool_pages : 0.0);
    ImGui::Text("pages: %u requested, %u drawn, %u cached, %u unserved, %u evicted", map.pages_requested,
                map.pages_rendered, map.pages_cached, map.pages_unserved, map.pages_evicted);
    ImGui::Text("caster instances drawn into pages: %u (%llu triangles)%s", map.page_draws,
                static_cast<unsigned long long>(map.page_draw_triangles),
                map.invalidated_all ? " (every page stale this frame)" : "");
    if (map.dropped_page_draws > 0) {
        ImGui::Text("%u page draws dropped (over virtual_page_draws): drawn in the next frames",
                    map.dropped_page_draws);
    }
    if (map.pages_deferred > 0) {
        ImGui::Text("%u pages deferred to later frames (the page draws of the frames before overflowed)",
                    map.pages_deferred);
    }
    if (map.counted_frame == 0) ImGui::TextDisabled("the GPU's counts arrive after the frames in flight");
    std::string sizes;
    for (size_t l = 0; l < map.texel_world_size.size(); ++l) {
        char size[32];
        std::snprintf(size, sizeof(size), "%s%.3g", l ? ", " : "", map.texel_world_size[l]);
        sizes += size;
    }
    ImGui::TextWrapped("texel per level (m): %s", sizes.c_str());
}

}  // namespace

void draw_statistics(const PanelStats& stats) {
    timing_section(stats);
    if (stats.frame && stats.frame->virtual_map &&
        ImGui::CollapsingHeader("Virtual shadow map", ImGuiTreeNodeFlags_DefaultOpen)) {
        virtual_map_section(*stats.frame->virtual_map);
    }
    if (stats.frame && ImGui::CollapsingHeader("Cascade statistics", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Text("shadow distance %.1f m", stats.frame->shadow_distance);
        cascade_table(*stats.frame);
    }
    if (ImGui::CollapsingHeader("Shadow-map layers")) shadow_map_layers(stats.shadow_map_layers, stats.frame);
}

}  // namespace penumbra::view

#pragma once
// The viewer's Dear ImGui panel: every shadow setting live, the camera and sun, debug
// views, per-cascade and per-local-light statistics, GPU time per pass and the shadow-map
// layers.
#include <string>
#include <string_view>
#include <vector>

#include "renderer/debug_images.hpp"
#include "renderer/renderer.hpp"
#include "view_state.hpp"

namespace penumbra::view {

// What the panel reports about the last rendered frame.
struct PanelStats {
    const renderer::FrameInfo* frame = nullptr;  // null before the first frame
    const std::vector<Light>* lights = nullptr;  // the scene's lights (local_shadow_stats index them)
    double frame_ms = 0.0;                       // wall-clock time between frames, smoothed
    double render_ms = 0.0;                      // CPU time in Renderer::render (includes its GPU wait)
    uint64_t shadow_map_bytes = 0;
    std::string device_name;
    renderer::GrayImage shadow_map_layers;  // with DebugView::ShadowMap: the layers side by side
};

// Draws the panel (when state.show_ui). Edits go to a copy of state.settings that
// replaces it only when validate_render_settings() accepts it (else state.status says
// why); camera, sun and requests are changed in place.
void draw_panel(ViewState& state, const PanelStats& stats);

// A control for every setting of `group` (SettingDeclaration::group) that applies to
// `settings`, editing them in place.
void draw_setting_group(Settings& settings, std::string_view group, const renderer::FrameInfo* frame);

// Controls of the settings sections, on `settings` in place (used by draw_panel).
void draw_shadow_settings(RenderSettings& settings, const renderer::FrameInfo* frame);

// The "Local lights" section: the local shadow settings on `settings` in place, and the
// last frame's shadowed spot/point lights (used by draw_panel).
void draw_local_lights(Settings& settings, const PanelStats& stats);

// Statistics sections (used by draw_panel).
void draw_statistics(const PanelStats& stats);

}  // namespace penumbra::view

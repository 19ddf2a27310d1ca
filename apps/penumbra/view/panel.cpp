// The viewer panel's frame: camera, sun, saving, and the settings and statistics sections.
#include "panel.hpp"

#include <imgui.h>

#include "penumbra/errors.hpp"

namespace penumbra::view {
namespace {

void camera_section(ViewState& state) {
    if (!ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) return;
    int mode = state.camera.mode() == CameraMode::Fly ? 0 : 1;
    if (ImGui::RadioButton("fly", &mode, 0)) state.camera.set_mode(CameraMode::Fly);
    ImGui::SameLine();
    if (ImGui::RadioButton("orbit", &mode, 1)) state.camera.set_mode(CameraMode::Orbit);
    ImGui::SameLine();
    if (ImGui::Button("reset (R)")) state.camera.reset();
    ImGui::SliderFloat("speed (m/s)", &state.camera.speed, 0.1f, 200.0f, "%.1f", ImGuiSliderFlags_Logarithmic);
    Camera camera = state.camera.camera();
    bool changed = ImGui::DragFloat3("eye", &camera.eye.x, 0.05f);
    changed |= ImGui::DragFloat3("target", &camera.target.x, 0.05f);
    changed |= ImGui::SliderFloat("fov (deg)", &camera.fov_y_degrees, 5.0f, 150.0f);
    if (changed && glm::length(camera.target - camera.eye) > 1e-4f) state.camera.set_camera(camera);
}

void sun_section(ViewState& state) {
    if (!ImGui::CollapsingHeader("Sun", ImGuiTreeNodeFlags_DefaultOpen)) return;
    Light* sun = state.sun();
    if (!sun) {
        ImGui::TextUnformatted("the scene has no sun");
        return;
    }
    SunAngles angles = sun_angles(sun->direction);
    bool changed = ImGui::SliderFloat("azimuth (deg)", &angles.azimuth_degrees, -180.0f, 180.0f);
    changed |= ImGui::SliderFloat("elevation (deg)", &angles.elevation_degrees, 1.0f, 90.0f);
    if (changed) sun->direction = sun_travel_direction(angles);
    ImGui::Checkbox("animate (L)", &state.animate_sun);
    ImGui::SameLine();
    ImGui::SliderFloat("deg/s", &state.sun_degrees_per_second, -90.0f, 90.0f);
    float diameter = sun->angular_diameter_degrees;
    if (ImGui::SliderFloat("angular diameter (deg)", &diameter, 0.0f, 45.0f)) {
        // As [sun] angular_diameter does: every directional light.
        for (Light& light : state.scene.lights) {
            if (light.type == LightType::Directional) light.angular_diameter_degrees = diameter;
        }
    }
}

void save_section(ViewState& state) {
    if (ImGui::Button("Save settings (F5)")) state.requests.save_settings = state.settings_file;
    ImGui::SameLine();
    if (ImGui::Button("Screenshot (F12)")) state.requests.screenshot = state.screenshot_file;
    ImGui::TextDisabled("to %s", state.settings_file.string().c_str());
    if (!state.status.empty()) ImGui::TextWrapped("%s", state.status.c_str());
}

}  // namespace

void draw_panel(ViewState& state, const PanelStats& stats) {
    if (!state.show_ui) return;
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(380, 640), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("penumbra (F1 hides)")) {
        ImGui::End();
        return;
    }
    save_section(state);
    camera_section(state);
    sun_section(state);
    RenderSettings edited = state.settings;
    draw_shadow_settings(edited, stats.frame);
    draw_local_lights(edited, stats);
    if (edited.shadow.cascades.count != state.settings.shadow.cascades.count &&
        edited.shadow.cascades.scheme == SplitScheme::Manual) {
        edited.shadow.cascades.manual_splits.clear();  // refilled for the new count next frame
        edited.shadow.cascades.scheme = SplitScheme::Practical;
    }
    try {
        validate_render_settings(edited, "panel");
        state.settings = edited;
    } catch (const InputError& error) {
        state.status = error.what();
    }
    draw_statistics(stats);
    ImGui::End();
}

}  // namespace penumbra::view

#include "view_actions.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "penumbra/errors.hpp"
#include "penumbra/scene/settings_overrides.hpp"

namespace penumbra::view {
namespace {

constexpr float kLookDegreesPerPixel = 0.2f;
constexpr float kSunDegreesPerSecond = 45.0f;

bool key_down(int key) { return ImGui::GetIO().KeysDown[key]; }
bool key_pressed(int key) { return ImGui::IsKeyPressed(key, false); }

void turn_sun(ViewState& state, float azimuth_degrees, float elevation_degrees) {
    Light* sun = state.sun();
    if (!sun || (azimuth_degrees == 0.0f && elevation_degrees == 0.0f)) return;
    SunAngles angles = sun_angles(sun->direction);
    angles.azimuth_degrees += azimuth_degrees;
    angles.elevation_degrees = std::clamp(angles.elevation_degrees + elevation_degrees, 1.0f, 90.0f);
    sun->direction = sun_travel_direction(angles);
}

void keyboard_movement(ViewState& state, float seconds) {
    const ImGuiIO& io = ImGui::GetIO();
    glm::vec3 direction(0.0f);
    direction.x = static_cast<float>(key_down(GLFW_KEY_D) - key_down(GLFW_KEY_A));
    direction.y = static_cast<float>(key_down(GLFW_KEY_E) - key_down(GLFW_KEY_Q));
    direction.z = static_cast<float>(key_down(GLFW_KEY_W) - key_down(GLFW_KEY_S));
    const float modifier = io.KeyShift ? 4.0f : (io.KeyCtrl ? 0.25f : 1.0f);
    if (direction != glm::vec3(0.0f)) state.camera.move(direction * state.camera.speed * modifier * seconds);
    const float sun_step = kSunDegreesPerSecond * seconds;
    turn_sun(state, sun_step * static_cast<float>(key_down(GLFW_KEY_RIGHT) - key_down(GLFW_KEY_LEFT)),
             sun_step * static_cast<float>(key_down(GLFW_KEY_UP) - key_down(GLFW_KEY_DOWN)));
}

void keyboard_commands(ViewState& state) {
    if (key_pressed(GLFW_KEY_F1)) state.show_ui = !state.show_ui;
    if (key_pressed(GLFW_KEY_F12) || key_pressed(GLFW_KEY_P)) state.requests.screenshot = state.screenshot_file;
    if (key_pressed(GLFW_KEY_F5)) state.requests.save_settings = state.settings_file;
    if (key_pressed(GLFW_KEY_ESCAPE)) state.requests.quit = true;
    if (key_pressed(GLFW_KEY_R)) state.camera.reset();
    if (key_pressed(GLFW_KEY_L)) state.animate_sun = !state.animate_sun;
    if (key_pressed(GLFW_KEY_TAB)) {
        state.camera.set_mode(state.camera.mode() == CameraMode::Fly ? CameraMode::Orbit : CameraMode::Fly);
    }
}

void mouse(ViewState& state) {
    const ImGuiIO& io = ImGui::GetIO();
    // Right (or left, outside the panel) drag looks around in fly mode and orbits in orbit mode.
    if (io.MouseDown[1] || io.MouseDown[0]) {
        state.camera.turn(-io.MouseDelta.x * kLookDegreesPerPixel, -io.MouseDelta.y * kLookDegreesPerPixel);
    }
    if (io.MouseWheel != 0.0f) {
        if (state.camera.mode() == CameraMode::Orbit) {
            state.camera.zoom(std::pow(0.9f, io.MouseWheel));
        } else {
            state.camera.speed = std::clamp(state.camera.speed * std::pow(1.2f, io.MouseWheel), 0.1f, 500.0f);
        }
    }
}

// `set TABLE.KEY = VALUE`: the same merge as a config file. Validation waits for the
// frame's last action (validate_script_frame) so that keys that must change together
// (split_scheme and splits) can be set on consecutive lines.
void apply_set(const action::Set& set, ViewState& state) {
    apply_overrides(set.overrides, state.settings);
    Scene& scene = state.scene;
    scene.camera = state.camera.camera();
    apply_overrides(set.overrides, scene);
    state.camera.set_camera(scene.camera);
}

}  // namespace

void handle_input(ViewState& state, float seconds) {
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureKeyboard) {
        keyboard_movement(state, seconds);
        keyboard_commands(state);
    }
    if (!io.WantCaptureMouse) mouse(state);
}

void validate_script_frame(ViewState& state, const std::string& origin) {
    validate_render_settings(state.settings, origin);
    state.scene.camera = state.camera.camera();
    validate_camera_and_sun(state.scene, origin);
}

void animate_sun(ViewState& state, float seconds) {
    if (state.animate_sun) turn_sun(state, state.sun_degrees_per_second * seconds, 0.0f);
}

void apply_action(const TimedAction& timed, ViewState& state, present::Window& window) {
    struct Visitor {
        ViewState& state;
        present::Window& window;
        void operator()(const action::Set& a) const { apply_set(a, state); }
        void operator()(const action::Move& a) const { state.camera.move(a.right_up_forward); }
        void operator()(const action::Turn& a) const { state.camera.turn(a.yaw_degrees, a.pitch_degrees); }
        void operator()(const action::Mode& a) const { state.camera.set_mode(a.mode); }
        void operator()(const action::Zoom& a) const { state.camera.zoom(a.factor); }
        void operator()(const action::Sun& a) const {
            if (Light* sun = state.sun()) sun->direction = sun_travel_direction(a.angles);
        }
        void operator()(const action::AnimateSun& a) const {
            state.animate_sun = a.degrees_per_second != 0.0f;
            state.sun_degrees_per_second = a.degrees_per_second;
        }
        void operator()(const action::Resize& a) const { window.resize(a.width, a.height); }
        void operator()(const action::ResetCamera&) const { state.camera.reset(); }
        void operator()(const action::Ui& a) const { state.show_ui = a.show; }
        void operator()(const action::Screenshot& a) const { state.requests.screenshot = a.file; }
        void operator()(const action::SaveSettings& a) const { state.requests.save_settings = a.file; }
        void operator()(const action::Quit&) const { state.requests.quit = true; }
    };
    std::visit(Visitor{state, window}, timed.action);
}

}  // namespace penumbra::view

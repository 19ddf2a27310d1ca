#pragma once
// Viewer scripts: timed actions replayed by `penumbra view --script FILE`. One action a
// line, "FRAME VERB ARGUMENTS", FRAME counting rendered frames from 0 in non-decreasing
// order; '#' starts a comment. The action runs before frame FRAME is rendered.
//
//   0   set shadow.cascades = 2        # any config-file key (docs/cli.md), TOML value
//   0   set shadow.resolution = 1024
//   5   move 0 0 2.5                   # metres right, up, forward (camera axes)
//   5   turn 10 -5                     # degrees yaw (left), pitch (up)
//   6   mode orbit                     # fly | orbit
//   7   zoom 0.8                       # orbit distance factor
//   8   sun 120 35                     # azimuth, elevation in degrees
//   8   animate-sun 30                 # degrees per second of azimuth (0 stops)
//   9   resize 800 600                 # window size in pixels
//   9   reset-camera
//   10  ui hide                        # show | hide
//   12  screenshot shot.png
//   12  save-settings view.toml
//   20  quit
//
// Everything is checked when the file is read: an unknown verb, a wrong argument count,
// a bad number or an invalid `set` (unknown key, wrong type) is an InputError naming
// "FILE:LINE".
#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include <glm/glm.hpp>
#include "penumbra/scene/settings_overrides.hpp"
#include "view_controls.hpp"

namespace penumbra::view {

namespace action {
struct Set {
    SettingsOverrides overrides;
    std::string origin;  // "FILE:LINE", for validation messages
};
struct Move {
    glm::vec3 right_up_forward{0.0f};
};
struct Turn {
    float yaw_degrees = 0.0f;
    float pitch_degrees = 0.0f;
};
struct Mode {
    CameraMode mode = CameraMode::Fly;
};
struct Zoom {
    float factor = 1.0f;
};
struct Sun {
    SunAngles angles;
};
struct AnimateSun {
    float degrees_per_second = 0.0f;
};
struct Resize {
    uint32_t width = 0;
    uint32_t height = 0;
};
struct ResetCamera {};
struct Ui {
    bool show = true;
};
struct Screenshot {
    std::filesystem::path file;
};
struct SaveSettings {
    std::filesystem::path file;
};
struct Quit {};
}  // namespace action

using Action = std::variant<action::Set, action::Move, action::Turn, action::Mode, action::Zoom, action::Sun,
                            action::AnimateSun, action::Resize, action::ResetCamera, action::Ui, action::Screenshot,
                            action::SaveSettings, action::Quit>;

struct TimedAction {
    uint32_t frame = 0;
    Action action;
    std::string origin;  // "FILE:LINE"
};

std::vector<TimedAction> parse_script(const std::string& text, const std::string& origin);
std::vector<TimedAction> load_script(const std::filesystem::path& path);

}  // namespace penumbra::view

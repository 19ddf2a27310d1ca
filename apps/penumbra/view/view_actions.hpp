#pragma once
// Changes to the viewer's state from the keyboard and mouse, and from script actions.
#include <string>

#include "present/window.hpp"
#include "script.hpp"
#include "view_state.hpp"

namespace penumbra::view {

// Keyboard and mouse (docs/viewer.md), read from Dear ImGui's IO, which the GLFW backend
// fills; ignored while the panel has the mouse or keyboard. `seconds`: the frame's time step.
void handle_input(ViewState& state, float seconds);

// Carries out one script action; `set` is not validated here (see below).
void apply_action(const TimedAction& timed, ViewState& state, present::Window& window);

// Validates the settings, camera and sun after a frame's actions; throws InputError
// naming `origin` (the frame's last `set` line) for an out-of-range value.
void validate_script_frame(ViewState& state, const std::string& origin);

// Advances the sun's azimuth when it is animated.
void animate_sun(ViewState& state, float seconds);

}  // namespace penumbra::view

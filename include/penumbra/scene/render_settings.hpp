#pragma once
// Everything that configures a frame of the penumbra tools besides the scene (Penumbra::
// scene): output size, the ShadowSystem's settings and debug views. Filled from (in increasing priority) the scene
// file's [output]/[shadow] tables, a --config file, and command-line flags.
#include <cstdint>
#include <string>

#include "penumbra/settings.hpp"

namespace penumbra {

enum class DebugView {
    None,
    Cascades,   // tint the colour image by cascade index
    ShadowMap,  // also read back the shadow map so its layers can be written side by side
};

constexpr uint32_t kMaxImageSize = 16384;
// Spot and point lights the tools' renderer lights (the first ones of a scene's list).
inline constexpr uint32_t kMaxLocalLights = 64;

struct RenderSettings {
    uint32_t width = 1280;
    uint32_t height = 720;
    ShadowSettings shadow;
    DebugView debug = DebugView::None;
    // Also render and read back each pixel's world position and normal (FrameImages::
    // world_position / world_normal), for `penumbra compare`. Off: frames pay nothing.
    bool geometry_aovs = false;
    // Shadow maps of spot and point lights (docs/local-lights.md).
    LocalShadowSettings local_shadows;
    // The light whose visibility goes into FrameImages::visibility: an index into the
    // scene's [[lights]] list (`--aov shadow:N`), or -1 for the sun (`--aov shadow`).
    int32_t visibility_light = -1;
};

// Throws InputError naming `origin` and the setting for out-of-range values.
void validate_render_settings(const RenderSettings& settings, const std::string& origin);

}  // namespace penumbra

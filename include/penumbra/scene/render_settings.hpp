#pragma once
// Everything that configures a frame of the penumbra tools besides the scene (Penumbra::
// scene): output size, the ShadowSystem's settings and debug views. Filled from (in increasing priority) the scene
// file's [output]/[shadow] tables, a --config file, and command-line flags.
#include <cstdint>
#include <map>
#include <string>

#include "penumbra/settings.hpp"

namespace penumbra {

enum class DebugView {
    None,
    Cascades,   // tint the colour image by cascade index
    ShadowMap,  // also read back the shadow map so its layers can be written side by side
};

// Where the tools' renderer evaluates the shadows it shades with (docs/library.md has both
// paths): in its lighting pass, once per shaded fragment (penumbra/shadow.glsl), or once
// per pixel in Penumbra's compute resolve (ShadowSystem::record_visibility) after a depth
// and normal pre-pass, the lighting pass then reading the visibility image. Auto picks the
// faster one as measured (docs/PERFORMANCE.md): see effective_resolve().
enum class ShadowResolve {
    Auto,
    Forward,
    Deferred,
};
inline constexpr ChoiceName<ShadowResolve> kShadowResolveChoices[] = {
    {"auto", ShadowResolve::Auto}, {"forward", ShadowResolve::Forward}, {"deferred", ShadowResolve::Deferred}};
const std::map<std::string, ShadowResolve>& shadow_resolve_names();

// The path `resolve` stands for: Auto is Deferred where the shadows cost many taps per
// shaded fragment (pcf, poisson and pcss filters) or spot/point lights cast shadows (each
// adds its own lookups), Forward otherwise (hard and the moment filters take one lookup per
// light, and the pre-pass would cost more than the overdraw it saves): on an H100 with the
// 1 M-triangle forest at 1080p, deferred is 1.3 ms faster with pcf R=2 and 0.3 ms with 16
// shadowed local lights, 1.1 ms slower with hard.
ShadowResolve effective_resolve(ShadowResolve resolve, ShadowFilter filter, bool local_shadow_casters);

constexpr uint32_t kMaxImageSize = 16384;
// Spot and point lights the tools' renderer lights (the first ones of a scene's list).
inline constexpr uint32_t kMaxLocalLights = 64;

struct RenderSettings {
    uint32_t width = 1280;
    uint32_t height = 720;
    ShadowResolve resolve = ShadowResolve::Auto;  // [output] resolve, --resolve
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

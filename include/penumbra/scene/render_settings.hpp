#pragma once
// Everything that configures a frame of the penumbra tools besides the scene (Penumbra::
// scene): output size, the ShadowSystem's settings and debug views. Filled from (in increasing priority) the scene
// file's [output]/[shadow] tables, a --config file, and command-line flags.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include "penumbra/settings.hpp"

namespace penumbra {

enum class DebugView {
    None,
    Cascades,   // tint the colour image by cascade index
    ShadowMap,  // also read back the shadow map so its layers can be written side by side
    // Tint the colour image by the virtual shadow map's level, with its page borders and
    // the pixels whose pages are not resident (the technique must be virtual)
    VirtualPages,
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

// The path `resolve` stands for. Auto is Deferred where a filter takes many taps per shaded
// fragment (pcf, poisson, pcss) and either the image has at least kDeferredMinPixels or
// spot/point lights cast shadows (each adds its lookups to every fragment); Forward
// otherwise: hard and the moment filters take one lookup per light, and the pre-pass then
// costs more than the overdraw it saves. Measured on an H100 with the 1 M-triangle forest
// (docs/PERFORMANCE.md, commits e897cbc and 56088cc): at 3840 x 2160 deferred saves
// 0.7-2.7 ms with those filters and costs 2.2 ms with hard; at 1920 x 1080 it costs
// 0.4 ms with pcf R=2 and 0.5 ms with poisson and, with 16 shadowed local lights, saves
// 1.1-1.3 ms with pcf and pcss and costs 0.5 ms with hard.
inline constexpr uint64_t kDeferredMinPixels = 4'000'000;
ShadowResolve effective_resolve(ShadowResolve resolve, ShadowFilter filter, bool local_shadow_casters, uint64_t pixels,
                                bool contact_shadows = false);

constexpr uint32_t kMaxImageSize = 16384;
// Spot and point lights the tools' renderer lights (the first ones of a scene's list).
inline constexpr uint32_t kMaxLocalLights = 64;

// RenderSettings::visibility_light: the sun's contact-shadow term alone, without its map.
inline constexpr int32_t kVisibilityContact = -2;

// The ShadowSystem's settings (shadow, local_shadows) and the tools' own.
struct RenderSettings : Settings {
    uint32_t width = 1280;
    uint32_t height = 720;
    ShadowResolve resolve = ShadowResolve::Auto;  // [output] resolve, --resolve
    DebugView debug = DebugView::None;
    // Also render and read back each pixel's world position and normal (FrameImages::
    // world_position / world_normal), for `penumbra compare`. Off: frames pay nothing.
    bool geometry_aovs = false;
    // The light whose visibility goes into FrameImages::visibility: an index into the
    // scene's [[lights]] list (`--aov shadow:N`), -1 for the sun (`--aov shadow`), or
    // kVisibilityContact for the sun's contact-shadow term alone (`--aov contact`).
    int32_t visibility_light = -1;
};

// The tools' own settings, declared as the ShadowSystem's are (penumbra/settings.hpp):
// [output] in config and scene files, flags, --help, validation, the viewer and bench
// reports read these declarations. Their accessors take the Settings a RenderSettings
// derives from and read the RenderSettings around it: use them on a RenderSettings only.
namespace setting_detail {
template <auto Member>
struct OutputField {
    static auto& in(Settings& settings) { return static_cast<RenderSettings&>(settings).*Member; }
    static const auto& in(const Settings& settings) { return static_cast<const RenderSettings&>(settings).*Member; }
};
}  // namespace setting_detail

template <auto Member>
constexpr SettingDeclaration declare_output(SettingDeclaration setting) {
    return declare_field<setting_detail::OutputField<Member>>(setting);
}

template <const auto& Choices, auto Member>
constexpr SettingDeclaration declare_output_choice(SettingDeclaration setting) {
    return declare_choice_field<Choices, setting_detail::OutputField<Member>>(setting);
}

inline constexpr SettingDeclaration kOutputSettingDeclarations[] = {
    declare_output<&RenderSettings::width>({.name = "width", .minimum = 1, .maximum = kMaxImageSize}),
    declare_output<&RenderSettings::height>({.name = "height", .minimum = 1, .maximum = kMaxImageSize}),
    declare_output_choice<kShadowResolveChoices, &RenderSettings::resolve>({.name = "resolve"}),
};

// The declaration of the tools' setting called `name`, or nullptr.
const SettingDeclaration* find_output_setting(std::string_view name);

// Throws InputError naming `origin` and the setting for out-of-range values.
void validate_render_settings(const RenderSettings& settings, const std::string& origin);

}  // namespace penumbra

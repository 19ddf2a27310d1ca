#include "penumbra/scene/render_settings.hpp"

#include "penumbra/errors.hpp"

namespace penumbra {

const SettingDeclaration* find_output_setting(std::string_view name) {
    for (const SettingDeclaration& setting : kOutputSettingDeclarations) {
        if (name == setting.name) return &setting;
    }
    return nullptr;
}

const std::map<std::string, ShadowResolve>& shadow_resolve_names() { return choice_map(kShadowResolveChoices); }

ShadowResolve effective_resolve(ShadowResolve resolve, ShadowFilter filter, bool local_shadow_casters, uint64_t pixels,
                                bool contact_shadows) {
    if (resolve != ShadowResolve::Auto) return resolve;
    // Both paths then need the depth pre-pass; compute traces it faster than fragments do.
    if (contact_shadows) return ShadowResolve::Deferred;
    const bool many_taps =
        filter == ShadowFilter::Pcf || filter == ShadowFilter::Poisson || filter == ShadowFilter::Pcss;
    return many_taps && (pixels >= kDeferredMinPixels || local_shadow_casters) ? ShadowResolve::Deferred
                                                                               : ShadowResolve::Forward;
}

void validate_render_settings(const RenderSettings& settings, const std::string& origin) {
    for (const SettingDeclaration& setting : kOutputSettingDeclarations) {
        const std::string problem = setting_value_problem(setting, setting.get(settings));
        if (!problem.empty()) throw InputError(origin + ": " + setting.name + ": " + problem);
    }
    validate_settings(settings, origin);
}

}  // namespace penumbra

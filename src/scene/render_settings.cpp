#include "penumbra/scene/render_settings.hpp"

#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

void check_image_size(uint32_t value, const char* name, const std::string& origin) {
    if (value == 0 || value > kMaxImageSize) {
        throw InputError(origin + ": " + name + ": " + std::to_string(value) + " is out of range (1.." +
                         std::to_string(kMaxImageSize) + ")");
    }
}

}  // namespace

const std::map<std::string, ShadowResolve>& shadow_resolve_names() { return choice_map(kShadowResolveChoices); }

ShadowResolve effective_resolve(ShadowResolve resolve, ShadowFilter filter, bool local_shadow_casters,
                                uint64_t pixels) {
    if (resolve != ShadowResolve::Auto) return resolve;
    const bool many_taps =
        filter == ShadowFilter::Pcf || filter == ShadowFilter::Poisson || filter == ShadowFilter::Pcss;
    return many_taps && (pixels >= kDeferredMinPixels || local_shadow_casters) ? ShadowResolve::Deferred
                                                                               : ShadowResolve::Forward;
}

void validate_render_settings(const RenderSettings& settings, const std::string& origin) {
    check_image_size(settings.width, "width", origin);
    check_image_size(settings.height, "height", origin);
    validate_settings(settings, origin);
}

}  // namespace penumbra

#include "core/render_settings.hpp"

#include "core/errors.hpp"

namespace penumbra {
namespace {

void check_image_size(uint32_t value, const char* name, const std::string& origin) {
    if (value == 0 || value > kMaxImageSize) {
        throw InputError(origin + ": " + name + ": " + std::to_string(value) + " is out of range (1.." +
                         std::to_string(kMaxImageSize) + ")");
    }
}

}  // namespace

void validate_render_settings(const RenderSettings& settings, const std::string& origin) {
    check_image_size(settings.width, "width", origin);
    check_image_size(settings.height, "height", origin);
    validate_shadow_settings(settings.shadow, origin);
    if (settings.local_shadows.budget > kMaxLocalShadowBudget) {
        throw InputError(origin + ": local_shadow_budget: " + std::to_string(settings.local_shadows.budget) +
                         " is out of range (0.." + std::to_string(kMaxLocalShadowBudget) + ")");
    }
    if (settings.local_shadows.resolution < 16 || settings.local_shadows.resolution > 8192) {
        throw InputError(origin + ": local_shadow_resolution: " + std::to_string(settings.local_shadows.resolution) +
                         " is out of range (16..8192)");
    }
}

}  // namespace penumbra

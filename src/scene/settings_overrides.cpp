#include "penumbra/scene/settings_overrides.hpp"

#include <cmath>
#include <cstdio>

#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

template <typename T>
void assign_if(const std::optional<T>& value, T& target) {
    if (value) target = *value;
}

std::string format_number(float value) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", value);
    return buffer;
}

}  // namespace

void SettingAssignments::assign(const SettingDeclaration& setting, SettingValue value) {
    for (auto& [declaration, stored] : values_) {
        if (declaration == &setting) {
            stored = std::move(value);
            return;
        }
    }
    values_.emplace_back(&setting, std::move(value));
}

const SettingValue* SettingAssignments::find(std::string_view name) const {
    for (const auto& [declaration, value] : values_) {
        if (name == declaration->name) return &value;
    }
    return nullptr;
}

void SettingAssignments::apply_to(Settings& settings) const {
    for (const auto& [declaration, value] : values_) declaration->set(settings, value);
    // Giving split distances implies manual splits, unless the same source names a scheme.
    if (find("splits") && !find("split_scheme")) settings.shadow.cascades.scheme = SplitScheme::Manual;
}

void apply_overrides(const SettingsOverrides& overrides, RenderSettings& settings) {
    overrides.settings.apply_to(settings);
}

void apply_overrides(const SettingsOverrides& overrides, Scene& scene) {
    assign_if(overrides.eye, scene.camera.eye);
    assign_if(overrides.target, scene.camera.target);
    assign_if(overrides.up, scene.camera.up);
    assign_if(overrides.fov, scene.camera.fov_y_degrees);
    assign_if(overrides.near_plane, scene.camera.near_plane);
    assign_if(overrides.far_plane, scene.camera.far_plane);
    if (overrides.angular_diameter) {
        for (Light& light : scene.lights) {
            if (light.type == LightType::Directional) light.angular_diameter_degrees = *overrides.angular_diameter;
        }
    }
    if (overrides.light_direction) {
        for (Light& light : scene.lights) {
            if (light.type == LightType::Directional) {
                light.direction = *overrides.light_direction;
                return;
            }
        }
        Light sun;
        sun.direction = *overrides.light_direction;
        sun.angular_diameter_degrees = overrides.angular_diameter.value_or(sun.angular_diameter_degrees);
        scene.lights.push_back(sun);
    }
}

void validate_camera_and_sun(const Scene& scene, const std::string& origin) {
    const Camera& camera = scene.camera;
    if (glm::length(camera.target - camera.eye) < 1e-6f) {
        throw InputError(origin + ": camera: eye and target are the same point");
    }
    if (!(camera.fov_y_degrees > 0.0f && camera.fov_y_degrees < 180.0f)) {
        throw InputError(origin + ": camera.fov: " + format_number(camera.fov_y_degrees) +
                         " is out of range (0 < fov < 180 degrees)");
    }
    if (!(camera.near_plane > 0.0f)) {
        throw InputError(origin + ": camera.near: " + format_number(camera.near_plane) + " must be > 0");
    }
    if (!(camera.far_plane > camera.near_plane)) {
        throw InputError(origin + ": camera.far: " + format_number(camera.far_plane) + " must be > near (" +
                         format_number(camera.near_plane) + ")");
    }
    if (!(glm::length(camera.up) > 1e-6f)) throw InputError(origin + ": camera.up: zero-length vector");
    for (const Light& light : scene.lights) {
        if (light.type == LightType::Directional && !(glm::length(light.direction) > 1e-6f)) {
            throw InputError(origin + ": light direction: zero-length vector");
        }
        const float angular = light.angular_diameter_degrees;
        if (light.type == LightType::Directional && !(angular >= 0.0f && angular <= 45.0f)) {
            throw InputError(origin + ": angular_diameter: " + format_number(angular) +
                             " is outside the allowed range [0, 45] degrees");
        }
    }
}

}  // namespace penumbra

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

void apply_overrides(const SettingsOverrides& overrides, RenderSettings& settings) {
    assign_if(overrides.width, settings.width);
    assign_if(overrides.resolve, settings.resolve);
    assign_if(overrides.height, settings.height);
    CascadeSettings& cascades = settings.shadow.cascades;
    assign_if(overrides.cascades, cascades.count);
    assign_if(overrides.shadow_resolution, cascades.resolution);
    assign_if(overrides.local_shadow_budget, settings.local_shadows.budget);
    assign_if(overrides.local_shadow_resolution, settings.local_shadows.resolution);
    assign_if(overrides.local_shadow_sizing, settings.local_shadows.sizing);
    assign_if(overrides.split_scheme, cascades.scheme);
    assign_if(overrides.split_lambda, cascades.split_lambda);
    if (overrides.splits) {
        cascades.manual_splits = *overrides.splits;
        if (!overrides.split_scheme) cascades.scheme = SplitScheme::Manual;  // giving splits implies manual
    }
    assign_if(overrides.max_distance, cascades.max_distance);
    assign_if(overrides.fit, cascades.fit);
    assign_if(overrides.constant_bias, settings.shadow.bias.constant);
    assign_if(overrides.slope_bias, settings.shadow.bias.slope);
    assign_if(overrides.bias_clamp, settings.shadow.bias.clamp);
    assign_if(overrides.normal_offset, settings.shadow.bias.normal_offset);
    assign_if(overrides.blend_width, settings.shadow.blend_width);
    assign_if(overrides.strategy, settings.shadow.strategy);
    assign_if(overrides.cull_casters, settings.shadow.cull_casters);
    assign_if(overrides.caster_culling, settings.shadow.caster_culling);
    apply_filter_overrides(overrides.filter, settings.shadow.filter);
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

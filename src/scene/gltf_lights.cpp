// KHR_lights_punctual (glTF 2.0 extension): directional, spot and point lights placed by
// nodes, imported as scene lights when a scene file asks for them (import_lights = true).
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>

#include "penumbra/settings.hpp"
#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

// The irradiance a spot or point light without a range fades to, relative to 1 m.
constexpr double kRangeFalloff = 0.01;

LightType light_type(const GltfSource& source, const tinygltf::Light& light, const std::string& where) {
    if (light.type == "directional") return LightType::Directional;
    if (light.type == "spot") return LightType::Spot;
    if (light.type == "point") return LightType::Point;
    source.fail(where + ".type", "unknown light type \"" + light.type + "\" (expected directional, spot or point)");
}

// The light's own values, checked once, in its model-space frame.
Light convert_light(const GltfSource& source, const tinygltf::Light& gltf, const std::string& where) {
    Light light;
    light.type = light_type(source, gltf, where);
    if (!gltf.color.empty()) {
        if (gltf.color.size() != 3 || !std::all_of(gltf.color.begin(), gltf.color.end(), within_float_math) ||
            *std::min_element(gltf.color.begin(), gltf.color.end()) < 0.0) {
            source.fail(where + ".color", "expected 3 finite numbers >= 0");
        }
        light.color = {gltf.color[0], gltf.color[1], gltf.color[2]};
    }
    if (!within_float_math(gltf.intensity) || gltf.intensity < 0.0) {
        source.fail(where + ".intensity", "expected a finite number >= 0, got " + std::to_string(gltf.intensity));
    }
    light.intensity = static_cast<float>(gltf.intensity);
    light.radius = 0.0f;  // punctual: the spot and point shadows are hard with pcss as well
    if (light.type == LightType::Directional) return light;
    if (!within_float_math(gltf.range) || gltf.range < 0.0) {
        source.fail(where + ".range", "expected a finite number > 0, got " + std::to_string(gltf.range));
    }
    const double fade_range = std::sqrt(std::max(gltf.intensity, kRangeFalloff) / kRangeFalloff);
    light.range = static_cast<float>(gltf.range > 0.0 ? gltf.range : std::clamp(fade_range, 0.1, 1e4));
    if (light.type == LightType::Spot) {
        const double inner = gltf.spot.innerConeAngle;
        const double outer = gltf.spot.outerConeAngle;
        if (!std::isfinite(inner) || !std::isfinite(outer) || inner < 0.0 || outer <= inner ||
            outer > std::numbers::pi / 2.0 + 1e-6) {
            source.fail(where + ".spot", "expected 0 <= innerConeAngle < outerConeAngle <= pi/2, got " +
                                             std::to_string(inner) + " and " + std::to_string(outer));
        }
        light.inner_angle_degrees = static_cast<float>(glm::degrees(inner));
        light.outer_angle_degrees = static_cast<float>(glm::degrees(outer));
    }
    return light;
}

}  // namespace

std::optional<int> punctual_light_of(const GltfSource& source, const tinygltf::Node& node, int node_index) {
    const auto extension = node.extensions.find("KHR_lights_punctual");
    if (extension == node.extensions.end()) return std::nullopt;
    const std::string where = "nodes[" + std::to_string(node_index) + "].extensions.KHR_lights_punctual.light";
    const tinygltf::Value& value = extension->second;
    if (!value.IsObject() || !value.Has("light") || !value.Get("light").IsInt()) {
        source.fail(where, "expected the index of a light");
    }
    const int light = value.Get("light").GetNumberAsInt();
    if (light < 0 || static_cast<size_t>(light) >= source.model.lights.size()) {
        source.fail(where, "light " + std::to_string(light) + " does not exist (the file has " +
                               std::to_string(source.model.lights.size()) + " lights)");
    }
    return light;
}

void append_gltf_lights(const GltfSource& source, const std::vector<GltfPlacedLight>& placed,
                        const std::vector<glm::mat4>& placements, std::vector<Light>& lights) {
    if (!placed.empty() && placements.size() > kMaxLights / placed.size()) {
        source.fail("KHR_lights_punctual", std::to_string(placements.size()) + " placement(s) of " +
                                               std::to_string(placed.size()) + " light(s) exceed " +
                                               std::to_string(kMaxLights) + " lights");
    }
    for (const glm::mat4& placement : placements) {
        for (const GltfPlacedLight& entry : placed) {
            const std::string where = "lights[" + std::to_string(entry.light) + "]";
            Light light = convert_light(source, source.model.lights[static_cast<size_t>(entry.light)], where);
            const glm::mat4 world = placement * entry.transform;
            // glTF lights shine along the node's local -Z from its origin.
            const glm::vec3 direction = glm::vec3{world * glm::vec4{0.0f, 0.0f, -1.0f, 0.0f}};
            if (!(glm::length(direction) > 0.0f) || !std::isfinite(glm::length(direction))) {
                source.fail("nodes[" + std::to_string(entry.node) + "]",
                            "the transform of a light node collapses its direction");
            }
            light.direction = glm::normalize(direction);
            light.position = glm::vec3{world[3]};
            lights.push_back(light);
        }
    }
}

}  // namespace penumbra

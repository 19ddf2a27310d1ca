#pragma once
// Partial settings from one source (scene file, config file or command line). Sources
// are applied in increasing priority: scene file, then --config file, then flags.
#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/scene.hpp"

namespace penumbra {

// Values a source gives for the ShadowSystem's settings (kSettingDeclarations), each
// checked against its declaration when read, in the order given.
class SettingAssignments {
public:
    // Replaces an earlier value of the same setting. `value` must be one that
    // setting_value_problem() accepts.
    void assign(const SettingDeclaration& setting, SettingValue value);
    // The value given for the setting called `name`, or nullptr.
    const SettingValue* find(std::string_view name) const;
    bool empty() const { return values_.empty(); }
    // A RenderSettings when an output setting is among them (their accessors need one).
    void apply_to(Settings& settings) const;

private:
    std::vector<std::pair<const SettingDeclaration*, SettingValue>> values_;
};

struct SettingsOverrides {
    // [output] and [shadow]: the tools' and the ShadowSystem's settings, by declaration
    // (kOutputSettingDeclarations, kSettingDeclarations).
    SettingAssignments settings;
    // [camera] and [sun]
    std::optional<glm::vec3> eye;
    std::optional<glm::vec3> target;
    std::optional<glm::vec3> up;
    std::optional<float> fov;
    std::optional<float> near_plane;
    std::optional<float> far_plane;
    std::optional<glm::vec3> light_direction;
    std::optional<float> angular_diameter;  // degrees, the sun's disk (soft-shadow filters)
};

void apply_overrides(const SettingsOverrides& overrides, RenderSettings& settings);
// Camera and sun overrides; a sun override on a scene without a sun adds one.
void apply_overrides(const SettingsOverrides& overrides, Scene& scene);

// Throws InputError naming `origin` when the scene's camera or sun is invalid:
// eye equal to target, fov outside (0, 180), near <= 0, far <= near, zero light direction,
// angular diameter outside [0, 45] degrees.
void validate_camera_and_sun(const Scene& scene, const std::string& origin);

}  // namespace penumbra

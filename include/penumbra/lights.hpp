#pragma once
// The lights a ShadowSystem shadows (ShadowSystem::set_lights). A light's index in the
// list given to set_lights() is its index everywhere else: in FrameInfo, in the shaders
// (penumbra_light_visibility(index, ...)) and in the resolved visibility image's slots.
#include <cstdint>

#include "penumbra/math.hpp"

namespace penumbra {

enum class LightType {
    Directional,  // the sun: the first directional light in the list gets the cascades
    Spot,         // a perspective map up to 60 degrees (outer half-angle), a cube beyond
    Point,        // a cube of six maps
};

struct LightDesc {
    LightType type = LightType::Directional;
    // Directional and spot: the direction light travels (sun -> ground); any length but 0.
    Vec3 direction{-0.4f, -1.0f, -0.3f};
    Vec3 position;                           // spot and point lights, world space
    float angular_diameter_degrees = 0.53f;  // directional: the sun's disk (pcss softness), 0..45
    float inner_angle_degrees = 20.0f;       // spot: full intensity inside (half-angle from the axis)
    float outer_angle_degrees = 30.0f;       // spot: nothing outside, (0, 180); >= inner
    float range = 25.0f;                     // spot and point: the light and its shadow end here (metres, > 0)
    float radius = 0.1f;                     // spot and point: the light's size for pcss (metres, >= 0)
    // Spot and point: texels per side of its shadow map; 0 = Settings::local_shadows.
    uint32_t shadow_resolution = 0;
    bool cast_shadows = true;
};

}  // namespace penumbra

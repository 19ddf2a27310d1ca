#include "library/light_checks.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "penumbra/errors.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::library {
namespace {

class LightChecker {
public:
    explicit LightChecker(size_t index) : prefix_("ShadowSystem::set_lights: lights[" + std::to_string(index) + "].") {}

    void require(bool ok, const char* field, float value, const char* range) const {
        if (ok) return;
        std::ostringstream message;
        message << prefix_ << field << ": " << value << " " << range;
        throw InputError(message.str());
    }

    void require_direction(const Vec3& v, const char* field) const {
        const bool finite = std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
        const double length = std::sqrt(double{v.x} * v.x + double{v.y} * v.y + double{v.z} * v.z);
        if (!finite || !(length > 0.0) || !std::isfinite(length)) {  // normalised in double: any length works
            throw InputError(prefix_ + field + ": must be a finite, non-zero vector");
        }
    }

    void require_finite(const Vec3& v, const char* field) const {
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
            throw InputError(prefix_ + field + ": must be finite");
        }
        if (std::abs(v.x) > kMaxWorldMagnitude || std::abs(v.y) > kMaxWorldMagnitude ||
            std::abs(v.z) > kMaxWorldMagnitude) {
            std::ostringstream message;
            message << prefix_ << field << ": (" << v.x << ", " << v.y << ", " << v.z << ") is beyond "
                    << kMaxWorldMagnitude << " in magnitude (kMaxWorldMagnitude)";
            throw InputError(message.str());
        }
    }

    // An enum value the caller cast from a number LightType does not define.
    void require_type(LightType type) const {
        if (type == LightType::Directional || type == LightType::Spot || type == LightType::Point) return;
        throw InputError(prefix_ + "type: " + std::to_string(static_cast<int>(type)) +
                         " is not a LightType (Directional, Spot or Point)");
    }

private:
    std::string prefix_;
};

void check_light(const LightDesc& light, size_t index) {
    const LightChecker check(index);
    check.require_type(light.type);
    if (light.type == LightType::Directional) {
        check.require_direction(light.direction, "direction");
        check.require(light.angular_diameter_degrees >= 0.0f && light.angular_diameter_degrees <= 45.0f,
                      "angular_diameter_degrees", light.angular_diameter_degrees, "is outside [0, 45]");
        return;
    }
    check.require_finite(light.position, "position");
    if (light.type == LightType::Spot) {
        check.require_direction(light.direction, "direction");
        check.require(light.outer_angle_degrees > 0.0f && light.outer_angle_degrees < 180.0f, "outer_angle_degrees",
                      light.outer_angle_degrees, "is outside (0, 180)");
        check.require(light.inner_angle_degrees >= 0.0f && light.inner_angle_degrees <= light.outer_angle_degrees,
                      "inner_angle_degrees", light.inner_angle_degrees, "is outside [0, outer_angle_degrees]");
    }
    check.require(light.range > 0.0f && light.range <= kMaxWorldMagnitude, "range", light.range,
                  "must be > 0 and at most kMaxWorldMagnitude");
    check.require(light.radius >= 0.0f && light.radius <= kMaxWorldMagnitude, "radius", light.radius,
                  "must be >= 0 and at most kMaxWorldMagnitude");
    check.require(light.shadow_resolution == 0 || (light.shadow_resolution >= 16 && light.shadow_resolution <= 8192),
                  "shadow_resolution", static_cast<float>(light.shadow_resolution), "is not 0 or within 16..8192");
}

}  // namespace

void check_lights(std::span<const LightDesc> lights) {
    if (lights.size() > kMaxLights) {
        throw InputError("ShadowSystem::set_lights: " + std::to_string(lights.size()) + " lights, at most " +
                         std::to_string(kMaxLights));
    }
    for (size_t i = 0; i < lights.size(); ++i) check_light(lights[i], i);
}

}  // namespace penumbra::library

// Per-cascade filter numbers. A cascade's orthographic projection maps light-space
// metres to UV by 1 / (width, height) and to reverse-Z depth by -1 / depth range, so a
// length along the light in metres is depth * depth_range, and a lateral length in UV
// is metres / width (Fernando 2005's penumbra estimate, directional-light form).
#include "core/shadow_filters.hpp"

#include <cmath>

namespace penumbra {

glm::vec2 clamped_evsm_exponents(const FilterSettings& filter) {
    return glm::min(glm::vec2(filter.evsm_positive_exponent, filter.evsm_negative_exponent),
                    glm::vec2(kEvsmMaxExponentFloat32));
}

int pcss_filter_taps(PcssQuality quality) {
    switch (quality) {
        case PcssQuality::Low:
            return 16;
        case PcssQuality::Medium:
            return 25;
        case PcssQuality::High:
            return 49;
    }
    return 25;
}

CascadeFilterParams cascade_filter_params(const Cascade& cascade, float angular_diameter_degrees) {
    const glm::vec2 lateral_extent = glm::max(glm::vec2(cascade.light_extent), glm::vec2(1e-6f));
    const float depth_range = std::max(cascade.light_extent.z, 1e-6f);
    const float half_angle = glm::radians(angular_diameter_degrees) * 0.5f;
    CascadeFilterParams params;
    params.light_radius_uv_per_depth = depth_range * std::tan(half_angle) / lateral_extent;
    // dz/du = (metres of depth / depth range) / (metres across / width) = slope * width / range.
    params.max_depth_gradient = kMaxReceiverSlope * lateral_extent / depth_range;
    return params;
}

}  // namespace penumbra

#pragma once
// Pure helpers of the shadow filters (docs/filters.md): which filters need the moments
// pass, tap counts, and the per-cascade numbers the shadow library needs to turn the
// light's angular size and the receiver's slope into shadow-map UV. No Vulkan.
#include <map>
#include <string>

#include "core/cascades.hpp"
#include "penumbra/settings.hpp"

namespace penumbra {

// PCSS variable-width filter taps per quality: 16, 25, 49.
int pcss_filter_taps(PcssQuality quality);

// The largest EVSM exponent whose warped second moment exp(2 c) stays finite in 32-bit
// float storage (Lauritzen's EVSM: 42 for fp32; 5.54 would be the limit for fp16).
constexpr float kEvsmMaxExponentFloat32 = 42.0f;

// The EVSM exponents (positive, negative) the shaders use: every moment format is 32-bit
// float or 16-bit UNORM (MSM only), so they are clamped to the fp32 limit.
glm::vec2 clamped_evsm_exponents(const FilterSettings& filter);

// The receiver slope (metres of light-space depth per metre across) beyond which the
// receiver-plane depth gradient is clamped: tan(84 degrees). Steeper gradients come from
// grazing receivers or from screen-space derivatives taken across a silhouette.
constexpr float kMaxReceiverSlope = 10.0f;

struct CascadeFilterParams {
    // The light's angular radius mapped to shadow-map UV per unit of reverse-Z depth:
    // depth range * tan(angular diameter / 2) / (light-space width, height). Multiplied
    // by a depth difference it gives the radius (per axis) of the light's footprint.
    glm::vec2 light_radius_uv_per_depth{0.0f};
    // The clamp of the receiver-plane depth gradient dz/du, dz/dv (kMaxReceiverSlope in
    // UV and reverse-Z depth units).
    glm::vec2 max_depth_gradient{0.0f};
};

CascadeFilterParams cascade_filter_params(const Cascade& cascade, float angular_diameter_degrees);

}  // namespace penumbra

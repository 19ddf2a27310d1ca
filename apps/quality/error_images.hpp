#pragma once
// Images that show where a render's shadows are wrong (written by `penumbra compare`):
// the error image paints false shadow (lit in truth, shadowed in the render) red and false
// lit (shadowed in truth, lit in the render) cyan over a dimmed grey copy of the render.
#include <cstdint>
#include <span>
#include <vector>

#include "quality/shadow_metrics.hpp"

namespace penumbra::quality {

struct RgbaImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> pixels;  // RGBA8, row 0 at the top
};

inline constexpr uint8_t kFalseShadowColor[3] = {235, 45, 45};
inline constexpr uint8_t kFalseLitColor[3] = {0, 200, 255};

std::vector<uint8_t> to_gray8(std::span<const float> values);    // [0, 1] -> 0..255
std::vector<uint16_t> to_gray16(std::span<const float> values);  // [0, 1] -> 0..65535
RgbaImage gray_to_rgba(uint32_t width, uint32_t height, std::span<const float> values);

// `color_rgba8`: the render's colour image, shown in grey underneath the errors.
RgbaImage hard_error_image(const VisibilityComparison& frame, std::span<const uint8_t> color_rgba8);

// |rendered - soft reference| on evaluated pixels, scaled by 4 (so 0.25 is white).
std::vector<uint8_t> soft_error_image(const VisibilityComparison& frame);

// Panels of equal height side by side, separated by `gap` white columns.
RgbaImage side_by_side(std::span<const RgbaImage> panels, uint32_t gap = 4);

}  // namespace penumbra::quality

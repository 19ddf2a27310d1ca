#include "quality/error_images.hpp"

#include <algorithm>
#include <cmath>

namespace penumbra::quality {
namespace {

uint8_t unorm8(float value) { return static_cast<uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)); }

void put(std::vector<uint8_t>& rgba, size_t pixel, const uint8_t (&color)[3]) {
    for (int c = 0; c < 3; ++c) rgba[pixel * 4 + c] = color[c];
    rgba[pixel * 4 + 3] = 255;
}

}  // namespace

std::vector<uint8_t> to_gray8(std::span<const float> values) {
    std::vector<uint8_t> gray(values.size());
    std::transform(values.begin(), values.end(), gray.begin(), unorm8);
    return gray;
}

std::vector<uint16_t> to_gray16(std::span<const float> values) {
    std::vector<uint16_t> gray(values.size());
    std::transform(values.begin(), values.end(), gray.begin(), [](float value) {
        return static_cast<uint16_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 65535.0f));
    });
    return gray;
}

RgbaImage gray_to_rgba(uint32_t width, uint32_t height, std::span<const float> values) {
    RgbaImage image{width, height, std::vector<uint8_t>(values.size() * 4)};
    for (size_t i = 0; i < values.size(); ++i) {
        const uint8_t gray = unorm8(values[i]);
        put(image.pixels, i, {gray, gray, gray});
    }
    return image;
}

RgbaImage hard_error_image(const VisibilityComparison& frame, std::span<const uint8_t> color_rgba8) {
    const size_t pixels = size_t{frame.width} * frame.height;
    RgbaImage image{frame.width, frame.height, std::vector<uint8_t>(pixels * 4)};
    for (size_t i = 0; i < pixels; ++i) {
        // Rec. 709 luma of the (sRGB-encoded) colour, dimmed so that the error colours stand out.
        const float luma =
            0.2126f * color_rgba8[i * 4] + 0.7152f * color_rgba8[i * 4 + 1] + 0.0722f * color_rgba8[i * 4 + 2];
        const auto gray = static_cast<uint8_t>(40.0f + luma * 0.5f);
        put(image.pixels, i, {gray, gray, gray});
        if (!frame.evaluated[i]) continue;
        const bool rendered_lit = frame.rendered[i] >= kShadowedBelow;
        if (frame.hard[i] && !rendered_lit) put(image.pixels, i, kFalseShadowColor);
        if (!frame.hard[i] && rendered_lit) put(image.pixels, i, kFalseLitColor);
    }
    return image;
}

std::vector<uint8_t> soft_error_image(const VisibilityComparison& frame) {
    std::vector<uint8_t> image(frame.evaluated.size(), 0);
    for (size_t i = 0; i < image.size(); ++i) {
        if (frame.evaluated[i]) image[i] = unorm8(4.0f * std::abs(frame.rendered[i] - frame.soft[i]));
    }
    return image;
}

RgbaImage side_by_side(std::span<const RgbaImage> panels, uint32_t gap) {
    RgbaImage image;
    for (const RgbaImage& panel : panels) {
        image.width += panel.width + (image.width ? gap : 0);
        image.height = std::max(image.height, panel.height);
    }
    image.pixels.assign(size_t{image.width} * image.height * 4, 255);
    uint32_t left = 0;
    for (const RgbaImage& panel : panels) {
        for (uint32_t y = 0; y < panel.height; ++y) {
            const auto source = panel.pixels.begin() + static_cast<std::ptrdiff_t>(size_t{y} * panel.width * 4);
            std::copy(source, source + static_cast<std::ptrdiff_t>(panel.width * 4),
                      image.pixels.begin() + static_cast<std::ptrdiff_t>((size_t{y} * image.width + left) * 4));
        }
        left += panel.width + gap;
    }
    return image;
}

}  // namespace penumbra::quality

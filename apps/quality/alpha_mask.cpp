#include "quality/alpha_mask.hpp"

#include <algorithm>
#include <cmath>

namespace penumbra::quality {
namespace {

int positive_modulo(int value, int modulus) {
    const int remainder = value % modulus;
    return remainder < 0 ? remainder + modulus : remainder;
}

// A texel index outside 0..size-1 mapped back in, as the Vulkan specification's texel
// coordinate wrapping operations define it ("Wrapping Operation").
int wrap(int index, int size, TextureWrap mode) {
    switch (mode) {
        case TextureWrap::Repeat:
            return positive_modulo(index, size);
        case TextureWrap::ClampToEdge:
            return std::clamp(index, 0, size - 1);
        case TextureWrap::MirroredRepeat: {
            const int shifted = positive_modulo(index, 2 * size) - size;
            return (size - 1) - (shifted >= 0 ? shifted : -(1 + shifted));
        }
    }
    return 0;
}

float texel_alpha(const Texture& texture, int x, int y) {
    const size_t texel = static_cast<size_t>(y) * texture.width + static_cast<size_t>(x);
    return static_cast<float>(texture.rgba8[texel * 4 + 3]) / 255.0f;
}

}  // namespace

float sample_alpha(const Texture& texture, glm::vec2 uv) {
    if (texture.width == 0 || texture.height == 0) return 1.0f;
    const auto width = static_cast<int>(texture.width);
    const auto height = static_cast<int>(texture.height);
    if (texture.nearest) {
        const int x = wrap(static_cast<int>(std::floor(uv.x * static_cast<float>(width))), width, texture.wrap_u);
        const int y = wrap(static_cast<int>(std::floor(uv.y * static_cast<float>(height))), height, texture.wrap_v);
        return texel_alpha(texture, x, y);
    }
    const float x = uv.x * static_cast<float>(width) - 0.5f;
    const float y = uv.y * static_cast<float>(height) - 0.5f;
    const float x_floor = std::floor(x);
    const float y_floor = std::floor(y);
    const float fx = x - x_floor;
    const float fy = y - y_floor;
    const int x0 = wrap(static_cast<int>(x_floor), width, texture.wrap_u);
    const int y0 = wrap(static_cast<int>(y_floor), height, texture.wrap_v);
    const int x1 = wrap(static_cast<int>(x_floor) + 1, width, texture.wrap_u);
    const int y1 = wrap(static_cast<int>(y_floor) + 1, height, texture.wrap_v);
    const float top = texel_alpha(texture, x0, y0) * (1.0f - fx) + texel_alpha(texture, x1, y0) * fx;
    const float bottom = texel_alpha(texture, x0, y1) * (1.0f - fx) + texel_alpha(texture, x1, y1) * fx;
    return top * (1.0f - fy) + bottom * fy;
}

std::optional<float> alpha_cutoff(const Material& material) {
    switch (material.alpha_mode) {
        case AlphaMode::Opaque:
            return std::nullopt;
        case AlphaMode::Mask:
            return material.alpha_cutoff;
        case AlphaMode::Blend:
            return 0.5f;
    }
    return std::nullopt;
}

float material_alpha(const Material& material, const Texture* texture, glm::vec2 uv) {
    float alpha = material.base_color.a;
    if (texture) alpha *= sample_alpha(*texture, uv);
    return alpha;
}

}  // namespace penumbra::quality

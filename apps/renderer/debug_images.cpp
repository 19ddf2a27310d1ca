#include "renderer/debug_images.hpp"

#include <algorithm>

namespace penumbra::renderer {

GrayImage shadow_map_strip(const FrameImages& images) {
    const uint32_t resolution = images.shadow_map_resolution;
    GrayImage strip;
    strip.width = resolution * images.shadow_map_layers;
    strip.height = resolution;
    strip.pixels.assign(size_t{strip.width} * strip.height, 0);
    const size_t layer_texels = size_t{resolution} * resolution;
    for (uint32_t layer = 0; layer < images.shadow_map_layers; ++layer) {
        const float* depth = images.shadow_map.data() + layer * layer_texels;
        float lowest = 1.0f, highest = 0.0f;
        for (size_t i = 0; i < layer_texels; ++i) {
            if (depth[i] <= 0.0f) continue;  // reverse-Z 0: nothing was rendered here
            lowest = std::min(lowest, depth[i]);
            highest = std::max(highest, depth[i]);
        }
        const float range = std::max(highest - lowest, 1e-12f);
        // Unwrapped: the cascade's texel (x, y) lies at its layer origin plus (x, y), modulo
        // the layer's side (toroidal cascades), so the strip shows each cascade as it covers
        // the ground.
        const glm::uvec2 origin =
            layer < images.shadow_map_layer_origins.size() ? images.shadow_map_layer_origins[layer] : glm::uvec2(0);
        for (uint32_t y = 0; y < resolution; ++y) {
            for (uint32_t x = 0; x < resolution; ++x) {
                const uint32_t layer_x = (x + origin.x) % resolution;
                const uint32_t layer_y = (y + origin.y) % resolution;
                const float d = depth[size_t{layer_y} * resolution + layer_x];
                const float t = d <= 0.0f ? -1.0f : (d - lowest) / range;
                strip.pixels[size_t{y} * strip.width + layer * resolution + x] =
                    t < 0.0f ? 0 : static_cast<uint8_t>(48.0f + 207.0f * t);
            }
        }
    }
    return strip;
}

}  // namespace penumbra::renderer

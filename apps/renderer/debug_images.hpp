#pragma once
// Debug images built from a frame's read-back data.
#include <cstdint>
#include <vector>

#include "renderer/renderer.hpp"

namespace penumbra::renderer {

struct GrayImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> pixels;
};

// The shadow map's layers side by side (cascade 0 on the left), 8-bit gray. Each layer is
// stretched over its own depth range so that detail is visible: the caster nearest the
// light is white, the farthest dark gray, and texels with no caster black.
GrayImage shadow_map_strip(const FrameImages& images);

}  // namespace penumbra::renderer

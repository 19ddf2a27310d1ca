#pragma once
// A screenshot taken by the viewer: the window's image (without the panel) or an AOV of
// the same frame, written as `penumbra render` writes its images.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "renderer/render_job.hpp"

namespace penumbra::view {

struct Capture {
    std::filesystem::path file;
    Aov aov = Aov::None;
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;         // Aov::None: 8-bit sRGB RGBA
    std::vector<uint16_t> visibility;  // Aov::Shadow
    std::vector<uint8_t> cascade;      // Aov::Cascade
};

// Writes the PNG atomically; throws InputError when the file cannot be written.
void write_capture(const Capture& capture);

}  // namespace penumbra::view

#include "scene/procedural_textures.hpp"

#include <array>
#include <cmath>
#include <utility>

namespace penumbra {
namespace {

constexpr std::array<std::pair<std::string_view, ProceduralPattern>, 3> kPatternNames{{
    {"checker", ProceduralPattern::Checker},
    {"checker_holes", ProceduralPattern::CheckerHoles},
    {"round_holes", ProceduralPattern::RoundHoles},
}};

struct Rgba {
    uint8_t r, g, b, a;
};

// Colour of one texel; (u, v) are the texel's centre in cell units (cell i spans [i, i+1)).
Rgba pattern_texel(ProceduralPattern pattern, float u, float v) {
    const bool odd_cell = (static_cast<int>(u) + static_cast<int>(v)) % 2 == 1;
    switch (pattern) {
        case ProceduralPattern::Checker:
            return odd_cell ? Rgba{90, 90, 90, 255} : Rgba{200, 200, 200, 255};
        case ProceduralPattern::CheckerHoles:
            return odd_cell ? Rgba{255, 255, 255, 0} : Rgba{255, 255, 255, 255};
        case ProceduralPattern::RoundHoles: {
            // Hole radius 0.35 cell: the holes cover ~38% of the area and leave solid bars.
            const float du = u - std::floor(u) - 0.5f;
            const float dv = v - std::floor(v) - 0.5f;
            const bool in_hole = du * du + dv * dv < 0.35f * 0.35f;
            return Rgba{255, 255, 255, static_cast<uint8_t>(in_hole ? 0 : 255)};
        }
    }
    return Rgba{255, 255, 255, 255};
}

}  // namespace

std::optional<ProceduralPattern> procedural_pattern_from_name(std::string_view name) {
    for (const auto& [pattern_name, pattern] : kPatternNames) {
        if (pattern_name == name) return pattern;
    }
    return std::nullopt;
}

std::string procedural_pattern_names() { return "checker, checker_holes or round_holes"; }

bool pattern_has_holes(ProceduralPattern pattern) { return pattern != ProceduralPattern::Checker; }

Texture make_procedural_texture(ProceduralPattern pattern, uint32_t size, uint32_t cells) {
    Texture texture;
    texture.width = size;
    texture.height = size;
    texture.rgba8.reserve(static_cast<size_t>(size) * size * 4);
    const float cells_per_texel = static_cast<float>(cells) / static_cast<float>(size);
    for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size; ++x) {
            const Rgba texel = pattern_texel(pattern, (static_cast<float>(x) + 0.5f) * cells_per_texel,
                                             (static_cast<float>(y) + 0.5f) * cells_per_texel);
            texture.rgba8.insert(texture.rgba8.end(), {texel.r, texel.g, texel.b, texel.a});
        }
    }
    return texture;
}

}  // namespace penumbra

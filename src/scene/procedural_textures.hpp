#pragma once
// Procedural RGBA8 textures for primitives in scene files (`texture = "round_holes"`),
// chiefly alpha-masked casters whose holes must show up in the shadow.
#include <optional>
#include <string>
#include <string_view>

#include "penumbra/scene/scene.hpp"

namespace penumbra {

enum class ProceduralPattern {
    Checker,       // light and dark grey squares, opaque
    CheckerHoles,  // white squares alternating with fully transparent ones
    RoundHoles,    // white with a grid of round, fully transparent holes
};

std::optional<ProceduralPattern> procedural_pattern_from_name(std::string_view name);
// "checker, checker_holes or round_holes", for error messages.
std::string procedural_pattern_names();
// True when the pattern has transparent texels, so a material using it wants alpha masking.
bool pattern_has_holes(ProceduralPattern pattern);

// A `size` x `size` texture with `cells` x `cells` squares or holes.
Texture make_procedural_texture(ProceduralPattern pattern, uint32_t size = 256, uint32_t cells = 8);

}  // namespace penumbra

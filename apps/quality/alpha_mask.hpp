#pragma once
// The alpha test of shadow casters, on the CPU, as the shadow pass does it on the GPU
// (shaders/shadow_masked.frag): alpha = base colour alpha * texture alpha, the texture
// sampled bilinearly with repeat addressing; MASK materials cut at their cutoff, BLEND
// materials cast as MASK at 0.5 (docs/techniques.md).
#include <optional>

#include "penumbra/scene/scene.hpp"

namespace penumbra::quality {

// The texture's alpha at `uv`, bilinear with repeat wrapping (texel centres at (i + 0.5) / size).
float sample_alpha_bilinear_repeat(const Texture& texture, glm::vec2 uv);

// The cutoff below which a material's surface lets light through, or nullopt when opaque.
std::optional<float> alpha_cutoff(const Material& material);

// The material's alpha at `uv` (the texture is `texture`, or none).
float material_alpha(const Material& material, const Texture* texture, glm::vec2 uv);

}  // namespace penumbra::quality

#pragma once
// The alpha test of shadow casters, on the CPU, as the shadow pass does it on the GPU
// (shaders/shadow_masked.frag): alpha = base colour alpha * texture alpha, the texture
// sampled with its own wrap modes and filter (the glTF sampler); MASK materials cut at their cutoff, BLEND
// materials cast as MASK at 0.5 (docs/techniques.md).
#include <optional>

#include "penumbra/scene/scene.hpp"

namespace penumbra::quality {

// The texture's alpha at `uv` as a Vulkan sampler of the texture's wrap modes and filter
// reads it: bilinear (texel centres at (i + 0.5) / size) or nearest.
float sample_alpha(const Texture& texture, glm::vec2 uv);

// The cutoff below which a material's surface lets light through, or nullopt when opaque.
std::optional<float> alpha_cutoff(const Material& material);

// The material's alpha at `uv` (the texture is `texture`, or none).
float material_alpha(const Material& material, const Texture* texture, glm::vec2 uv);

}  // namespace penumbra::quality

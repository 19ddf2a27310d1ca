#pragma once
// Small deterministic camera motions for the temporal-stability measurement: frame k of a
// sequence moves the camera by a fraction of a shadow texel to a few texels and turns it
// by an angle that shifts the view at the target by as much. Frame 0 is the camera itself.
#include <cstdint>

#include "penumbra/scene/scene.hpp"

namespace penumbra::quality {

// `texel_world_size`: the world size of a texel of the nearest cascade (what "sub-texel"
// and "a few texels" are measured in).
Camera jittered_camera(const Camera& camera, uint32_t frame, float texel_world_size);

}  // namespace penumbra::quality

#pragma once
// Range checks of ShadowSystem::set_lights() (docs/library.md): every message names the
// light's index and field and the offending value.
#include <span>

#include "penumbra/lights.hpp"

namespace penumbra::library {

// Throws InputError for more than kMaxLights lights or any value outside its range.
void check_lights(std::span<const LightDesc> lights);

}  // namespace penumbra::library

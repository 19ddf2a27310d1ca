#pragma once
// The specialization constants of shaders/include/shadow_filter_constants.glsl for a
// filter configuration; shared by the lighting and moments passes so that both compile
// the same variant.
#include <vector>

#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::passes {

std::vector<gpu::SpecializationValue> shadow_filter_specialization(const FilterSettings& filter);

}  // namespace penumbra::passes

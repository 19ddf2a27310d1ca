#pragma once
// Measurements on the `--aov shadow` image for the shadow-filter tests: which pixels see
// the ground plane (and where), and visibility profiles across a shadow edge.
#include <functional>
#include <optional>
#include <vector>

#include "analytic_shadow.hpp"
#include "render_fixture.hpp"

namespace penumbra::testing {

struct GroundSample {
    glm::vec2 xz;      // the ground point the pixel sees
    float visibility;  // the sun's visibility there
};

// Every pixel whose primary ray reaches the ground (|x|, |z| <= half_size) before any of
// `boxes`.
std::vector<GroundSample> ground_samples(const Scene& scene, const renderer::FrameImages& images, float half_size,
                                         const std::vector<Aabb>& boxes);

// Mean visibility in bins of `bin_width` over a signed distance (e.g. to a shadow edge,
// positive on the lit side) from `lowest` to `highest`; bins without samples are empty.
struct Profile {
    float lowest = 0.0f;
    float bin_width = 0.0f;
    std::vector<std::optional<float>> mean_visibility;
};

Profile visibility_profile(const std::vector<GroundSample>& samples,
                           const std::function<std::optional<float>(glm::vec2)>& signed_distance, float lowest,
                           float highest, float bin_width);

// The width of the lit-to-shadow transition: from the last bin (walking inward from the
// lit side) whose mean is >= `lit` to the first whose mean is <= `shadow`. nullopt when
// either level is never reached.
std::optional<float> transition_width(const Profile& profile, float lit = 0.98f, float shadow = 0.02f);

// Total length of the bins whose mean lies strictly between `low` and `high` (partially
// lit): the penumbra width, even where no umbra is left.
float partial_width(const Profile& profile, float low = 0.05f, float high = 0.95f);

}  // namespace penumbra::testing

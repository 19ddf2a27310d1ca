#pragma once
// Finding the sky box or dome that shadows a whole image (a closed mesh around the camera
// and the scene that casts): the image is black, nothing errs, and the user cannot tell
// why. Judged by what the camera sees, not by bounding boxes alone, so that a room lit
// through its window, legitimately mostly in shadow, is not reported.
#include <vector>

#include "penumbra/scene/inventory.hpp"

namespace penumbra::quality {

struct EnclosingCaster {
    SceneEntry entry;
    // The share of the shadow-receiving surface points the camera sees whose path to the
    // sun this entry alone blocks.
    double shadowed_share = 0.0;
};

// The rule: a casting entry (scene_inventory) whose world bounds hold the camera and the
// centres of at least kHeldShare of the other entries' bounds is a candidate; it is
// reported when it alone blocks the sun from at least kShadowedShare of the receiving
// surface points seen through a grid of rays over the view (width / height = aspect).
// Empty without a shadow-casting sun.
inline constexpr double kHeldShare = 0.9;
inline constexpr double kShadowedShare = 0.98;
std::vector<EnclosingCaster> find_enclosing_casters(const Scene& scene, const Camera& camera, float aspect);

// One warning line naming each caster as exclude_casters accepts it; empty for none.
std::string enclosing_casters_warning(const std::vector<EnclosingCaster>& casters);

}  // namespace penumbra::quality

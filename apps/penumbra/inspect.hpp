#pragma once
// `penumbra inspect SCENE`: what a scene is made of, in the names its settings take (the
// `nodes[i]` / `meshes[j]` forms and the exclude_casters entry of every glTF node), so
// that nobody has to read a model's JSON to switch a sky's shadow off.
#include <string>

#include "penumbra/scene/loader.hpp"

namespace penumbra::cli {

struct InspectJob {
    std::string scene = std::string(kDefaultSceneName);
    LoadBudget load_budget;
    bool json = false;  // print JSON instead of the text listing
};

// Loads the scene (InputError on bad input) and returns the listing, text or JSON.
std::string inspect_scene(const InspectJob& job);

// The same for a scene already loaded; `scene_name` heads the listing.
std::string format_inspection(const Scene& scene, const std::string& scene_name, bool json);

}  // namespace penumbra::cli

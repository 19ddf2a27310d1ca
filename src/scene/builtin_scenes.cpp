// Built-in scenes, written in the scene-file format itself so that they double as
// examples and go through the same validation as user files (docs/scene-format.md).
#include <array>
#include <string_view>

#include "penumbra/errors.hpp"
#include "penumbra/scene/loader.hpp"
#include "scene/forest_scene.hpp"
#include "scene/terrain_scene.hpp"

namespace penumbra {
namespace {

// Shows the usual shadow artefacts at a glance: contact and peter-panning (the slab floating
// 5 cm above the ground), thin casters that alias (3 cm fence rails and posts), alpha-tested
// holes that must appear in the shadow, and poles out to ~50 m so every cascade has work.
constexpr std::string_view kDefaultScene = R"toml(
[camera]
eye = [0.0, 6.0, 12.0]
target = [0.0, 0.0, 0.0]
fov = 60.0
near = 0.1
far = 200.0

[[lights]]
type = "directional"
direction = [-0.4, -1.0, -0.3]
color = [1.0, 0.96, 0.9]
intensity = 3.0
angular_diameter = 0.53

[ambient]
color = [0.25, 0.3, 0.35]

# Ground: 60 x 60 m, reaching 57 m in front of the camera.
[[objects]]
type = "plane"
size = [60.0, 60.0]
translation = [0.0, 0.0, -15.0]
color = [0.7, 0.7, 0.68]

# Poles of growing height at growing distance (about 6, 12, 18, 26, 36 and 48 m).
[[objects]]
type = "cylinder"
radius = 0.08
height = 2.0
translation = [-4.5, 1.0, 7.5]
color = [0.8, 0.3, 0.2]

[[objects]]
type = "cylinder"
radius = 0.08
height = 3.0
translation = [-3.5, 1.5, 0.0]
color = [0.8, 0.3, 0.2]

[[objects]]
type = "cylinder"
radius = 0.1
height = 4.0
translation = [4.0, 2.0, -6.0]
color = [0.8, 0.3, 0.2]

[[objects]]
type = "cylinder"
radius = 0.12
height = 5.0
translation = [-5.0, 2.5, -14.0]
color = [0.8, 0.3, 0.2]

[[objects]]
type = "cylinder"
radius = 0.15
height = 6.0
translation = [6.0, 3.0, -24.0]
color = [0.8, 0.3, 0.2]

[[objects]]
type = "cylinder"
radius = 0.2
height = 7.0
translation = [-7.0, 3.5, -36.0]
color = [0.8, 0.3, 0.2]

# Boxes: a turned cube, a tall block and a low wall further away.
[[objects]]
type = "box"
size = [1.5, 1.5, 1.5]
translation = [2.5, 0.75, 1.5]
rotation = [0.0, 20.0, 0.0]
color = [0.3, 0.5, 0.8]

[[objects]]
type = "box"
size = [1.0, 3.0, 1.0]
translation = [-6.0, 1.5, -4.0]
color = [0.35, 0.7, 0.4]

[[objects]]
type = "box"
size = [4.0, 1.0, 0.5]
translation = [5.0, 0.5, -12.0]
rotation = [0.0, -30.0, 0.0]
color = [0.75, 0.7, 0.45]

# Slab floating 5 cm above the ground: its shadow must touch its footprint (peter-panning check).
[[objects]]
type = "box"
size = [2.5, 0.1, 2.5]
translation = [-2.5, 0.1, 3.5]
color = [0.85, 0.85, 0.85]

# A fence of 3 cm posts and rails: thin casters that under-sampled shadow maps break up.
[[objects]]
type = "cylinder"
radius = 0.015
height = 1.2
translation = [0.0, 0.6, 5.0]
color = [0.4, 0.3, 0.2]

[[objects]]
type = "cylinder"
radius = 0.015
height = 1.2
translation = [4.0, 0.6, 5.0]
color = [0.4, 0.3, 0.2]

[[objects]]
type = "box"
size = [4.0, 0.03, 0.03]
translation = [2.0, 1.0, 5.0]
color = [0.4, 0.3, 0.2]

[[objects]]
type = "box"
size = [4.0, 0.03, 0.03]
translation = [2.0, 0.5, 5.0]
color = [0.4, 0.3, 0.2]

[[objects]]
type = "sphere"
radius = 1.0
translation = [-0.5, 1.0, -1.5]
color = [0.9, 0.9, 0.9]
roughness = 0.3

# Alpha-masked casters: a vertical panel with round holes, turned 25 degrees, and a slanted
# checkerboard cut-out. Their shadows must show the holes.
[[objects]]
type = "plane"
size = [2.5, 2.5]
rotation = [90.0, 25.0, 0.0]
translation = [-4.0, 1.5, -1.0]
color = [0.9, 0.5, 0.2]
texture = "round_holes"
alpha_mode = "mask"
alpha_cutoff = 0.5
double_sided = true

[[objects]]
type = "plane"
size = [2.0, 2.0]
rotation = [60.0, -35.0, 0.0]
translation = [6.5, 1.6, -2.5]
color = [0.6, 0.8, 0.9]
texture = "checker_holes"
alpha_mode = "mask"
alpha_cutoff = 0.5
double_sided = true
)toml";

// The smallest scene with a shadow: a 2 m cube on a 20 m ground under the default sun.
constexpr std::string_view kBoxOnPlaneScene = R"toml(
[[lights]]
type = "directional"
direction = [-0.4, -1.0, -0.3]

[[objects]]
type = "plane"
size = [20.0, 20.0]

[[objects]]
type = "box"
size = [2.0, 2.0, 2.0]
translation = [0.0, 1.0, 0.0]
)toml";

struct BuiltinScene {
    std::string_view name;
    std::string_view toml;
};

constexpr std::array<BuiltinScene, 2> kBuiltinScenes{{
    {"default", kDefaultScene},
    {"box-on-plane", kBoxOnPlaneScene},
}};

}  // namespace

std::vector<std::string> builtin_scene_names() {
    std::vector<std::string> names;
    for (const BuiltinScene& scene : kBuiltinScenes) names.emplace_back(scene.name);
    names.emplace_back("forest");   // procedural; takes ?count=N&spots=N&points=N (scene/forest_scene.hpp)
    names.emplace_back("terrain");  // procedural; takes ?size=N&trees=N (scene/terrain_scene.hpp)
    return names;
}

Scene builtin_scene(const std::string& name) {
    const std::string origin = std::string(kBuiltinPrefix) + name;
    // "NAME?QUERY": only the procedural scenes take parameters.
    const size_t query_start = name.find('?');
    const std::string base = name.substr(0, query_start);
    const std::string query = query_start == std::string::npos ? "" : name.substr(query_start + 1);
    if (base == "forest") return make_forest_scene(parse_forest_parameters(query, origin));
    if (base == "terrain") return make_terrain_scene(parse_terrain_parameters(query, origin));
    for (const BuiltinScene& scene : kBuiltinScenes) {
        if (scene.name != base) continue;
        if (query_start != std::string::npos)
            throw InputError(origin + ": built-in scene \"" + base + "\" takes no parameters");
        return parse_scene_toml(scene.toml, origin, {});
    }
    std::string valid;
    for (const std::string& known : builtin_scene_names()) valid += (valid.empty() ? "" : ", ") + known;
    throw InputError(origin + ": unknown built-in scene \"" + name + "\" (expected one of: " + valid + ")");
}

}  // namespace penumbra

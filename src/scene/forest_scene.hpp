#pragma once
// The procedural stress scene behind "builtin:forest?count=N": N trees (a trunk
// cylinder, an ellipsoid crown and a rock beside it) jittered over a 400 m square of
// ground. Each kind of object is one Mesh shared by all its Instances, so the scene
// costs little memory at any size while the renderer still submits one draw per
// instance. Triangles: exactly kForestTrianglesPerTree * N + kForestGroundTriangles:
// count=100 is 0.1 M, count=1000 is 1 M and count=10000 is 10 M triangles (plus the
// ground's 8,192). The trees cover the whole square at every count, so triangle density
// (and every cascade's work) grows linearly with N. Deterministic: the same N always gives the same scene.
//
// "builtin:forest?count=N&spots=S&points=P" adds S shadow-casting spot lights, each above a
// tree and aimed down at it, and P shadow-casting point lights at lantern height beside
// trees, both spread over the forest by tree index (docs/bench.md); "&spot_angle=A" sets the
// spots' outer angle (degrees, default 35; inner = outer - 10), so that spots wider than 60
// degrees, shadowed by cubes, can be measured. Lights follow the sun in Scene::lights: spots
// first, then points, so light 1 is the first spot. "&movers=M" adds M dynamic instances
// (a tree crown each, 900 triangles, flagged `dynamic`) on a ring in front of the camera,
// for `bench --animate-dynamic` to move (cached cascades with moving casters).
#include <cstdint>
#include <string>

#include "penumbra/scene/scene.hpp"

namespace penumbra {

constexpr uint32_t kForestTrianglesPerTree = 1000;  // crown 900 + trunk 88 + rock 12
// make_plane() tessellates large planes into 64 x 64 cells (a lavapipe multiview workaround).
constexpr uint32_t kForestGroundTriangles = 64 * 64 * 2;
constexpr uint32_t kForestDefaultCount = 1000;
constexpr uint32_t kForestMaxCount = 100000;
constexpr float kForestSize = 400.0f;             // side of the square the trees cover, metres
constexpr uint32_t kForestDefaultSpotAngle = 35;  // degrees: the cone holds its tree and rock
struct ForestParameters {
    uint32_t count = kForestDefaultCount;  // trees
    // Spots plus points at most kMaxLocalLights: the lighting shader lights no more.
    uint32_t spots = 0;                             // shadow-casting spot lights aimed down at trees
    uint32_t points = 0;                            // shadow-casting point lights between the trees
    uint32_t spot_angle = kForestDefaultSpotAngle;  // the spots' outer angle, degrees (1..179)
    uint32_t movers = 0;                            // dynamic crowns on a ring in view
};

Scene make_forest_scene(uint32_t count);
Scene make_forest_scene(const ForestParameters& parameters);

// Parses the query after "forest?": "" or "KEY=N" pairs joined by '&', KEY one of count,
// spots, points, spot_angle, movers, each at most once. Throws InputError naming `origin`, the key and the value.
ForestParameters parse_forest_parameters(const std::string& query, const std::string& origin);

}  // namespace penumbra

#pragma once
// The open-world scene behind "builtin:terrain?size=S&trees=N": S x S metres of rolling
// hills (a 256 x 256-cell height field, flat within 400 m of the centre), a fence of
// centimetre-thin posts and rails a few metres in front of the camera, N trees whose
// distances from the camera are spread evenly over every octave from 12 m to 45 % of the
// side (as many between 12 and 24 m as between 2 and 4 km), leaving a lane down the middle
// of the view clear to the horizon, and buildings from 200 m out to the horizon. The camera stands at the centre at eye
// height, looking along -Z over the fence and the forest toward the horizon; the sun is low behind it (long shadows). A
// scene for the virtual shadow map: casters at every distance, each sharp only with texels as fine as its pixels.
// Triangles: kTerrainGroundTriangles + kTerrainFenceTriangles + kTerrainTrianglesPerTree * N + 12 * kTerrainBuildings
// (trees=1000: 1,121,652). Deterministic.
#include <cstdint>
#include <string>

#include "penumbra/scene/scene.hpp"

namespace penumbra {

constexpr uint32_t kTerrainCells = 256;     // height field cells per side
constexpr uint32_t kTerrainTileCells = 16;  // cells per side of one ground tile (an instance)
constexpr uint32_t kTerrainTiles = kTerrainCells / kTerrainTileCells;  // tiles per side
constexpr uint32_t kTerrainGroundTriangles = kTerrainCells * kTerrainCells * 2;
constexpr uint32_t kTerrainTrianglesPerTree = 988;  // crown 900 + trunk 88
constexpr uint32_t kTerrainFencePosts = 13;
constexpr uint32_t kTerrainFenceTriangles = 12 * (kTerrainFencePosts + 2);  // posts and two rails
constexpr uint32_t kTerrainBuildings = 200;
constexpr uint32_t kTerrainDefaultSize = 20000;  // metres
constexpr uint32_t kTerrainDefaultTrees = 1000;
constexpr float kTerrainFlatRadius = 400.0f;  // metres of flat ground around the centre
constexpr float kTerrainNearestTree = 12.0f;  // metres from the camera

struct TerrainParameters {
    uint32_t size = kTerrainDefaultSize;  // side of the square, metres (1000..40000)
    uint32_t trees = kTerrainDefaultTrees;
};

Scene make_terrain_scene(const TerrainParameters& parameters);

// The ground's height at (x, z): hills whose heights and wavelengths scale with the side,
// blending to 0 within kTerrainFlatRadius of the centre.
float terrain_height(float x, float z, float size);

// Parses the query after "terrain?": "" or size=N and trees=N joined by '&', each at most
// once. Throws InputError naming `origin`, the key and the value.
TerrainParameters parse_terrain_parameters(const std::string& query, const std::string& origin);

}  // namespace penumbra

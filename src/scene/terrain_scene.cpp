#include "scene/terrain_scene.hpp"

#include <array>
#include <cmath>

#include <glm/common.hpp>

#include "penumbra/scene/primitives.hpp"
#include "scene/mesh_tools.hpp"
#include "scene/procedural_parameters.hpp"
#include "scene/procedural_random.hpp"

namespace penumbra {
namespace {

enum TerrainMaterial : uint32_t { kGroundMaterial, kBark, kFoliage, kWood, kStone };
// Mesh indices of the terrain's object kinds; the ground's tiles follow.
enum TerrainMesh : uint32_t { kTrunk, kCrown, kBox, kBuilding, kFirstTile };

constexpr float kTwoPi = 6.2831853f;
// Hash streams: trees 0..8, buildings 100..106.
constexpr uint64_t kBuildingStream = 100;
// Half the angle of view the scene's camera sees across (60 degrees vertically at 16:9 is
// about 46 each way): three trees and buildings in four stand inside it.
constexpr float kViewHalfAngle = 0.87f;  // 50 degrees
constexpr float kEyeHeight = 1.7f;
constexpr float kFenceDistance = 8.0f;  // metres in front of the camera
constexpr float kTreeLane = 0.21f;      // 12 degrees each side of the view's axis without trees

// Flat ground around the camera, so that the near field is a plain receiver.
float flat_blend(float x, float z) {
    return glm::smoothstep(kTerrainFlatRadius, 3.0f * kTerrainFlatRadius, std::sqrt(x * x + z * z));
}

glm::vec3 ground_normal(float x, float z, float size) {
    const float step = size / static_cast<float>(kTerrainCells) * 0.25f;
    const float dx = terrain_height(x + step, z, size) - terrain_height(x - step, z, size);
    const float dz = terrain_height(x, z + step, size) - terrain_height(x, z - step, size);
    return glm::normalize(glm::vec3{-dx, 2.0f * step, -dz});
}

// Tile (tile_x, tile_z) of the height field: kTerrainTileCells^2 of its kTerrainCells^2
// quads, in world coordinates, counter-clockwise seen from above. The ground is tiles, as
// open worlds lay out their terrain, so that culling finds the part of it a page or a
// cascade needs (a page of the virtual map draws whole instances).
Mesh make_ground_tile(float size, uint32_t tile_x, uint32_t tile_z) {
    Mesh mesh;
    const uint32_t side = kTerrainTileCells + 1;
    mesh.vertices.reserve(size_t{side} * side);
    for (uint32_t j = 0; j < side; ++j) {
        for (uint32_t i = 0; i < side; ++i) {
            const float u = static_cast<float>(tile_x * kTerrainTileCells + i) / kTerrainCells;
            const float v = static_cast<float>(tile_z * kTerrainTileCells + j) / kTerrainCells;
            const float x = (u - 0.5f) * size;
            const float z = (0.5f - v) * size;  // row 0 at +Z, as make_plane's UVs
            mesh.vertices.push_back({{x, terrain_height(x, z, size), z}, ground_normal(x, z, size), {u, v}});
        }
    }
    mesh.indices.reserve(size_t{kTerrainTileCells} * kTerrainTileCells * 6);
    for (uint32_t j = 0; j < kTerrainTileCells; ++j) {
        for (uint32_t i = 0; i < kTerrainTileCells; ++i) {
            const uint32_t near_left = j * side + i;  // (x0, z1)
            const uint32_t near_right = near_left + 1;
            const uint32_t far_right = near_right + side;  // (x1, z0): the next row lies toward -Z
            const uint32_t far_left = near_left + side;
            mesh.indices.insert(mesh.indices.end(), {near_left, near_right, far_right, near_left, far_right, far_left});
        }
    }
    mesh.bounds = compute_mesh_bounds(mesh.vertices);
    mesh.material = kGroundMaterial;
    return mesh;
}

void add_materials(Scene& scene) {
    const glm::vec4 colors[] = {{0.38f, 0.43f, 0.27f, 1.0f},  // ground
                                {0.33f, 0.24f, 0.15f, 1.0f},  // bark
                                {0.18f, 0.42f, 0.16f, 1.0f},  // foliage
                                {0.55f, 0.45f, 0.32f, 1.0f},  // fence wood
                                {0.62f, 0.6f, 0.57f, 1.0f}};  // buildings
    for (const glm::vec4& color : colors) scene.materials.push_back(Material{color});
}

void add_meshes(Scene& scene, float size) {
    const auto with_material = [](Mesh mesh, TerrainMaterial material) {
        mesh.material = material;
        return mesh;
    };
    scene.meshes.push_back(with_material(make_cylinder(1.0f, 1.0f, 22), kBark));  // 88 triangles
    scene.meshes.push_back(with_material(make_sphere(1.0f, 30, 16), kFoliage));   // 900 triangles
    scene.meshes.push_back(with_material(make_box(glm::vec3{1.0f}), kWood));
    scene.meshes.push_back(with_material(make_box(glm::vec3{1.0f}), kStone));
    for (uint32_t tile_z = 0; tile_z < kTerrainTiles; ++tile_z) {
        for (uint32_t tile_x = 0; tile_x < kTerrainTiles; ++tile_x) {
            scene.meshes.push_back(make_ground_tile(size, tile_x, tile_z));
        }
    }
}

void add_box(Scene& scene, uint32_t mesh, const glm::vec3& centre, const glm::vec3& size, float yaw_degrees = 0.0f) {
    scene.instances.push_back({mesh, compose_transform(centre, {0.0f, yaw_degrees, 0.0f}, size)});
}

// Posts 4 cm square and 1.2 m tall, one metre apart, with two 3 cm rails: the centimetre
// casters a shadow map loses first when its texels grow.
void add_fence(Scene& scene) {
    const float half_width = 0.5f * static_cast<float>(kTerrainFencePosts - 1);
    for (uint32_t post = 0; post < kTerrainFencePosts; ++post) {
        add_box(scene, kBox, {static_cast<float>(post) - half_width, 0.6f, -kFenceDistance}, {0.04f, 1.2f, 0.04f});
    }
    for (const float height : {0.5f, 1.0f}) {
        add_box(scene, kBox, {0.0f, height, -kFenceDistance + 0.035f}, {2.0f * half_width + 0.04f, 0.03f, 0.03f});
    }
}

// The direction from the camera of object `index` (stream `stream`): three in four inside
// the camera's view, more than `lane` radians off its axis (a clear view down the middle
// to the horizon), the rest anywhere around it.
glm::vec2 direction_from_camera(uint32_t index, uint64_t stream, float lane) {
    const float t = procedural_random01(index, stream);
    const float side = procedural_random01(index, stream + 1) < 0.5f ? -1.0f : 1.0f;
    const float angle = index % 4 != 3 ? side * procedural_lerp(lane, kViewHalfAngle, t) : kTwoPi * t;
    return {std::sin(angle), -std::cos(angle)};  // angle 0: straight ahead, -Z
}

// A distance in [nearest, farthest] whose logarithm is spread evenly over the objects:
// object `index` of `count` takes its own slice, jittered inside it.
float distance_by_octave(uint32_t index, uint32_t count, float nearest, float farthest, uint64_t stream) {
    const float t = (static_cast<float>(index) + procedural_random01(index, stream)) / static_cast<float>(count);
    return nearest * std::pow(farthest / nearest, t);
}

void add_tree(Scene& scene, uint32_t index, uint32_t count, float size) {
    const float distance = distance_by_octave(index, count, kTerrainNearestTree, 0.45f * size, 0);
    const glm::vec2 base = distance * direction_from_camera(index, 1, kTreeLane);
    const float ground = terrain_height(base.x, base.y, size);
    const float trunk_height = procedural_lerp(3.0f, 6.0f, procedural_random01(index, 3));
    const float trunk_radius = procedural_lerp(0.18f, 0.35f, procedural_random01(index, 4));
    const float crown_radius = procedural_lerp(1.5f, 3.0f, procedural_random01(index, 5));
    const float crown_height = crown_radius * procedural_lerp(1.2f, 1.8f, procedural_random01(index, 6));
    const glm::vec3 zero{0.0f};
    scene.instances.push_back({kTrunk, compose_transform({base.x, ground + 0.5f * trunk_height, base.y}, zero,
                                                         {trunk_radius, trunk_height, trunk_radius})});
    scene.instances.push_back({kCrown, compose_transform({base.x, ground + trunk_height + 0.6f * crown_height, base.y},
                                                         zero, {crown_radius, crown_height, crown_radius})});
}

// Buildings from 200 m to the horizon, 10 to 30 m across and 10 to 40 m tall, sunk a metre
// into the slope they stand on.
void add_building(Scene& scene, uint32_t index, float size) {
    const float distance = distance_by_octave(index, kTerrainBuildings, 200.0f, 0.45f * size, kBuildingStream);
    const glm::vec2 base = distance * direction_from_camera(index, kBuildingStream + 1, 0.0f);
    const glm::vec3 extent{procedural_lerp(10.0f, 30.0f, procedural_random01(index, kBuildingStream + 3)),
                           procedural_lerp(10.0f, 40.0f, procedural_random01(index, kBuildingStream + 4)),
                           procedural_lerp(10.0f, 30.0f, procedural_random01(index, kBuildingStream + 5))};
    const float ground = terrain_height(base.x, base.y, size) - 1.0f;
    add_box(scene, kBuilding, {base.x, ground + 0.5f * extent.y, base.y}, extent,
            360.0f * procedural_random01(index, kBuildingStream + 6));
}

}  // namespace

float terrain_height(float x, float z, float size) {
    // Three octaves of crossed sines: hills a fifth of the side apart, 1.2 % of it high.
    const float relief = 0.012f * size;
    const float k = kTwoPi / size;
    const float hills = 0.5f * std::sin(5.0f * k * x + 0.7f) * std::cos(4.0f * k * z + 1.3f) +
                        0.3f * std::sin(11.0f * k * (0.8f * x + 0.6f * z) + 2.1f) +
                        0.2f * std::cos(23.0f * k * (0.6f * x - 0.8f * z) + 0.4f);
    return relief * hills * flat_blend(x, z);
}

Scene make_terrain_scene(const TerrainParameters& parameters) {
    const auto size = static_cast<float>(parameters.size);
    Scene scene;
    scene.camera.eye = {0.0f, kEyeHeight, 0.0f};
    scene.camera.target = {0.0f, kEyeHeight - 0.6f, -50.0f};  // toward the horizon, a little down
    scene.camera.far_plane = size;
    Light sun;
    sun.direction = glm::normalize(glm::vec3{0.35f, -0.45f, -0.82f});  // low, behind the camera
    sun.color = {1.0f, 0.94f, 0.85f};
    scene.lights.push_back(sun);
    add_materials(scene);
    add_meshes(scene, size);
    scene.instances.reserve(kTerrainTiles * kTerrainTiles + kTerrainFencePosts + 2 + size_t{2} * parameters.trees +
                            kTerrainBuildings);
    for (uint32_t tile = 0; tile < kTerrainTiles * kTerrainTiles; ++tile) {
        scene.instances.push_back({kFirstTile + tile, glm::mat4{1.0f}});
    }
    add_fence(scene);
    for (uint32_t index = 0; index < parameters.trees; ++index) add_tree(scene, index, parameters.trees, size);
    for (uint32_t index = 0; index < kTerrainBuildings; ++index) add_building(scene, index, size);
    return scene;
}

namespace {

constexpr std::array<ProceduralParameter<TerrainParameters>, 2> kTerrainParameterSpecs{{
    {"size", 1000, 40000, &TerrainParameters::size},
    {"trees", 0, 100000, &TerrainParameters::trees},
}};

}  // namespace

TerrainParameters parse_terrain_parameters(const std::string& query, const std::string& origin) {
    return parse_procedural_parameters<TerrainParameters>(query, origin, kTerrainParameterSpecs, TerrainParameters{});
}

}  // namespace penumbra

#include "scene/forest_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "penumbra/errors.hpp"
#include "penumbra/scene/primitives.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "scene/procedural_parameters.hpp"
#include "scene/procedural_random.hpp"

namespace penumbra {
namespace {

// Mesh (and material) indices of the forest's object kinds.
enum ForestMesh : uint32_t { kGround, kTrunk, kCrown, kRock };

// Segment counts chosen for kForestTrianglesPerTree: a UV sphere has segments * (2 * rings
// - 2) triangles (30 x 16 -> 900), a capped cylinder 4 * segments (22 -> 88), a box 12.
constexpr uint32_t kCrownSegments = 30;
constexpr uint32_t kCrownRings = 16;
constexpr uint32_t kTrunkSegments = 22;

float random01(uint64_t tree, uint64_t stream) { return procedural_random01(tree, stream); }

float lerp(float a, float b, float t) { return procedural_lerp(a, b, t); }

void add_materials(Scene& scene) {
    const glm::vec4 colors[] = {{0.36f, 0.42f, 0.25f, 1.0f},  // ground
                                {0.33f, 0.24f, 0.15f, 1.0f},  // bark
                                {0.18f, 0.42f, 0.16f, 1.0f},  // foliage
                                {0.52f, 0.5f, 0.47f, 1.0f}};  // rock
    for (const glm::vec4& color : colors) scene.materials.push_back(Material{color});
}

void add_meshes(Scene& scene) {
    scene.meshes.push_back(make_plane(kForestSize + 40.0f, kForestSize + 40.0f));
    scene.meshes.push_back(make_cylinder(1.0f, 1.0f, kTrunkSegments));
    scene.meshes.push_back(make_sphere(1.0f, kCrownSegments, kCrownRings));
    scene.meshes.push_back(make_box(glm::vec3{1.0f}));
    for (uint32_t kind = 0; kind < scene.meshes.size(); ++kind) scene.meshes[kind].material = kind;
}

// Tree `index` sits in its own cell of an n x n grid over the square (cells spread evenly
// when count is not a square number), jittered inside the cell.
glm::vec2 tree_position(uint32_t index, uint32_t count) {
    const auto cells_per_side = static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(count))));
    const uint64_t cell = uint64_t{index} * cells_per_side * cells_per_side / count;
    const float cell_size = kForestSize / static_cast<float>(cells_per_side);
    const float x = (static_cast<float>(cell % cells_per_side) + lerp(0.2f, 0.8f, random01(index, 0))) * cell_size;
    const float z = (static_cast<float>(cell / cells_per_side) + lerp(0.2f, 0.8f, random01(index, 1))) * cell_size;
    return glm::vec2{x, z} - 0.5f * kForestSize;
}

// The random shape of tree `index`, shared by its instances and the lights placed by it.
struct TreeShape {
    glm::vec2 base{0.0f};  // x, z of the trunk's foot
    float trunk_height = 0.0f;
    float trunk_radius = 0.0f;
    float crown_radius = 0.0f;
    float crown_height = 0.0f;  // half-height of the ellipsoid

    // The crown overlaps the trunk's top third, so the two read as one tree from afar.
    float crown_center() const { return trunk_height + 0.6f * crown_height; }
    float top() const { return crown_center() + crown_height; }
};

TreeShape tree_shape(uint32_t index, uint32_t count) {
    TreeShape tree;
    tree.base = tree_position(index, count);
    tree.trunk_height = lerp(3.0f, 6.0f, random01(index, 2));
    tree.trunk_radius = lerp(0.18f, 0.35f, random01(index, 3));
    tree.crown_radius = lerp(1.5f, 3.0f, random01(index, 4));
    tree.crown_height = tree.crown_radius * lerp(1.2f, 1.8f, random01(index, 5));
    return tree;
}

void add_tree(Scene& scene, uint32_t index, uint32_t count) {
    const TreeShape tree = tree_shape(index, count);
    const glm::vec2 base = tree.base;
    const glm::vec3 zero{0.0f};
    scene.instances.push_back({kTrunk, compose_transform({base.x, 0.5f * tree.trunk_height, base.y}, zero,
                                                         {tree.trunk_radius, tree.trunk_height, tree.trunk_radius})});
    scene.instances.push_back({kCrown, compose_transform({base.x, tree.crown_center(), base.y}, zero,
                                                         {tree.crown_radius, tree.crown_height, tree.crown_radius})});
    const float rock_angle = 6.2831853f * random01(index, 6);
    const float rock_distance = lerp(2.0f, 4.0f, random01(index, 7));
    const glm::vec3 rock_size{lerp(0.6f, 1.6f, random01(index, 8)), lerp(0.4f, 1.0f, random01(index, 9)),
                              lerp(0.6f, 1.4f, random01(index, 10))};
    const glm::vec3 rock_position{base.x + rock_distance * std::cos(rock_angle), 0.4f * rock_size.y,
                                  base.y + rock_distance * std::sin(rock_angle)};
    scene.instances.push_back(
        {kRock, compose_transform(rock_position, {0.0f, glm::degrees(rock_angle), 0.0f}, rock_size)});
}

// Dynamic crowns on a ring of 25 m around the point the camera looks at, 4 m up: inside
// the near cascades of the scene's camera, casting on the ground and the trees around.
void add_movers(Scene& scene, uint32_t movers) {
    for (uint32_t i = 0; i < movers; ++i) {
        const float angle = 6.2831853f * static_cast<float>(i) / static_cast<float>(std::max(movers, 1u));
        const glm::vec3 position{25.0f * std::cos(angle), 4.0f, 25.0f * std::sin(angle)};
        Instance mover{kCrown, compose_transform(position, glm::vec3(0.0f), {1.5f, 2.5f, 1.5f})};
        mover.dynamic = true;
        mover.name = "mover";
        scene.instances.push_back(mover);
    }
}

// Light `index` of `lights` goes by the middle tree of its equal share of the tree indices;
// tree indices run row by row over the grid, so the lights spread over the whole square.
uint32_t tree_for_light(uint32_t index, uint32_t lights, uint32_t count) {
    return static_cast<uint32_t>((uint64_t{2} * index + 1) * count / (uint64_t{2} * lights));
}

// A unit vector in the ground plane at a random angle (light `index`, hash stream `stream`).
glm::vec2 ground_direction(uint32_t index, uint64_t stream) {
    const float angle = 6.2831853f * random01(index, stream);
    return {std::cos(angle), std::sin(angle)};
}

// Hash streams of the lights, apart from the trees' streams 0..10.
constexpr uint64_t kSpotStream = 100;
constexpr uint64_t kPointStream = 200;

// 10 m above the tree's top and 5 m to a side, aimed at the middle of its trunk, so the cone
// (70 degrees wide by default) holds the tree, its rock and the ground around it.
Light forest_spot(uint32_t index, uint32_t spots, uint32_t count, uint32_t outer_angle_degrees) {
    const TreeShape tree = tree_shape(tree_for_light(index, spots, count), count);
    const glm::vec2 side = tree.base + 5.0f * ground_direction(index, kSpotStream);
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {side.x, tree.top() + 10.0f, side.y};
    spot.direction = glm::normalize(glm::vec3{tree.base.x, 0.5f * tree.trunk_height, tree.base.y} - spot.position);
    spot.outer_angle_degrees = static_cast<float>(outer_angle_degrees);
    spot.inner_angle_degrees = std::max(0.0f, spot.outer_angle_degrees - 10.0f);
    spot.range = 2.5f * spot.position.y;  // reaches the ground well outside the cone's axis
    // Radiance about 1.5 at the ground below (inverse square): half the sun's.
    spot.intensity = 1.5f * spot.position.y * spot.position.y;
    spot.color = {1.0f, 0.85f, 0.6f};
    spot.radius = 0.2f;
    return spot;
}

// A lantern 2.5 m up, just outside the crown of its tree: every cube face sees casters.
Light forest_point(uint32_t index, uint32_t points, uint32_t count) {
    const TreeShape tree = tree_shape(tree_for_light(index, points, count), count);
    const glm::vec2 side = tree.base + (tree.crown_radius + 1.5f) * ground_direction(index, kPointStream);
    Light point;
    point.type = LightType::Point;
    point.position = {side.x, 2.5f, side.y};
    point.range = 20.0f;
    point.intensity = 40.0f;
    point.color = {1.0f, 0.7f, 0.4f};
    point.radius = 0.1f;
    return point;
}

}  // namespace

Scene make_forest_scene(uint32_t count) { return make_forest_scene(ForestParameters{count, 0, 0}); }

Scene make_forest_scene(const ForestParameters& parameters) {
    const uint32_t count = parameters.count;
    Scene scene;
    // From inside the forest, looking across it: the shadow distance (150 m) is full of trees.
    scene.camera.eye = {0.0f, 20.0f, 90.0f};
    scene.camera.target = {0.0f, 3.0f, 0.0f};
    scene.camera.far_plane = 800.0f;
    Light sun;
    sun.color = {1.0f, 0.96f, 0.9f};
    scene.lights.push_back(sun);
    for (uint32_t i = 0; i < parameters.spots; ++i) {
        scene.lights.push_back(forest_spot(i, parameters.spots, count, parameters.spot_angle));
    }
    for (uint32_t i = 0; i < parameters.points; ++i) scene.lights.push_back(forest_point(i, parameters.points, count));
    add_materials(scene);
    add_meshes(scene);
    scene.instances.reserve(1 + size_t{3} * count + parameters.movers);
    scene.instances.push_back({kGround, glm::mat4{1.0f}});
    for (uint32_t index = 0; index < count; ++index) add_tree(scene, index, count);
    add_movers(scene, parameters.movers);
    return scene;
}

namespace {

constexpr std::array<ProceduralParameter<ForestParameters>, 5> kForestParameterSpecs{{
    {"count", 1, kForestMaxCount, &ForestParameters::count},
    {"spots", 0, kMaxLocalLights, &ForestParameters::spots},
    {"points", 0, kMaxLocalLights, &ForestParameters::points},
    {"spot_angle", 1, 179, &ForestParameters::spot_angle},
    {"movers", 0, 1000, &ForestParameters::movers},
}};

}  // namespace

ForestParameters parse_forest_parameters(const std::string& query, const std::string& origin) {
    const ForestParameters parameters =
        parse_procedural_parameters<ForestParameters>(query, origin, kForestParameterSpecs, ForestParameters{});
    if (parameters.spots + parameters.points > kMaxLocalLights) {
        throw InputError(origin + ": spots + points: at most " + std::to_string(kMaxLocalLights) +
                         " spot and point lights are lit, got " + std::to_string(parameters.spots) + " + " +
                         std::to_string(parameters.points));
    }
    return parameters;
}

}  // namespace penumbra

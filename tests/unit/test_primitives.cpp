// Procedural meshes: counts, bounds, outward normals and counter-clockwise front faces.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "penumbra/scene/primitives.hpp"
#include "scene/mesh_tools.hpp"

namespace penumbra {
namespace {

struct PrimitiveCase {
    std::string name;
    std::function<Mesh()> make;
    size_t triangles;
    Aabb bounds;
    friend void PrintTo(const PrimitiveCase& c, std::ostream* os) { *os << c.name; }  // not its bytes
};

std::vector<PrimitiveCase> primitive_cases() {
    return {
        // A 4 x 2 m plane is a grid of 2 m cells: 2 x 1 cells, 2 triangles each.
        {"plane", [] { return make_plane(4.0f, 2.0f); }, 4, {{-2.0f, 0.0f, -1.0f}, {2.0f, 0.0f, 1.0f}}},
        {"box",
         [] {
             return make_box({1.0f, 2.0f, 3.0f});
         },
         12,
         {{-0.5f, -1.0f, -1.5f}, {0.5f, 1.0f, 1.5f}}},
        {"sphere", [] { return make_sphere(2.0f); }, 32 * (2 * 16 - 2), {glm::vec3{-2.0f}, glm::vec3{2.0f}}},
        {"coarse_sphere", [] { return make_sphere(1.0f, 8, 4); }, 8 * (2 * 4 - 2), {glm::vec3{-1.0f}, glm::vec3{1.0f}}},
        {"cylinder", [] { return make_cylinder(0.5f, 3.0f); }, 4 * 32, {{-0.5f, -1.5f, -0.5f}, {0.5f, 1.5f, 0.5f}}},
    };
}

class PrimitiveTest : public ::testing::TestWithParam<PrimitiveCase> {};

TEST_P(PrimitiveTest, HasTheExpectedTriangleCount) {
    const Mesh mesh = GetParam().make();
    EXPECT_EQ(mesh.indices.size() % 3, 0u);
    EXPECT_EQ(mesh.indices.size() / 3, GetParam().triangles);
}

TEST_P(PrimitiveTest, IndicesStayInRange) {
    const Mesh mesh = GetParam().make();
    for (uint32_t index : mesh.indices) ASSERT_LT(index, mesh.vertices.size());
}

TEST_P(PrimitiveTest, BoundsMatchTheRequestedSize) {
    const Mesh mesh = GetParam().make();
    const float tolerance = 1e-5f;
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(mesh.bounds.min[axis], GetParam().bounds.min[axis], tolerance) << "axis " << axis;
        EXPECT_NEAR(mesh.bounds.max[axis], GetParam().bounds.max[axis], tolerance) << "axis " << axis;
    }
}

TEST_P(PrimitiveTest, NormalsAreUnitLengthAndUvsInsideTheUnitSquare) {
    for (const Vertex& vertex : GetParam().make().vertices) {
        EXPECT_NEAR(glm::length(vertex.normal), 1.0f, 1e-5f);
        EXPECT_GE(vertex.uv.x, 0.0f);
        EXPECT_LE(vertex.uv.x, 1.0f);
        EXPECT_GE(vertex.uv.y, 0.0f);
        EXPECT_LE(vertex.uv.y, 1.0f);
    }
}

// Right-handed, counter-clockwise front faces: the cross product of a triangle's edges points
// to the side its vertex normals point to.
TEST_P(PrimitiveTest, FrontFacesAreCounterClockwiseAroundTheNormals) {
    const Mesh mesh = GetParam().make();
    for (size_t first = 0; first < mesh.indices.size(); first += 3) {
        const Vertex& a = mesh.vertices[mesh.indices[first]];
        const Vertex& b = mesh.vertices[mesh.indices[first + 1]];
        const Vertex& c = mesh.vertices[mesh.indices[first + 2]];
        const glm::vec3 face_normal = glm::cross(b.position - a.position, c.position - a.position);
        ASSERT_GT(glm::length(face_normal), 0.0f) << "degenerate triangle " << first / 3;
        for (const Vertex* vertex : {&a, &b, &c}) {
            ASSERT_GT(glm::dot(face_normal, vertex->normal), 0.0f) << "triangle " << first / 3;
        }
    }
}

// Every primitive is convex and centred on the origin, so an outward normal never points
// back towards the centre (the plane's normal is +Y by contract).
TEST_P(PrimitiveTest, NormalsPointOutward) {
    const Mesh mesh = GetParam().make();
    for (const Vertex& vertex : mesh.vertices) {
        if (GetParam().name == "plane") {
            EXPECT_EQ(vertex.normal, glm::vec3(0.0f, 1.0f, 0.0f));
        } else {
            EXPECT_GT(glm::dot(vertex.normal, vertex.position), 0.0f);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Primitives, PrimitiveTest, ::testing::ValuesIn(primitive_cases()),
                         [](const auto& test_info) { return test_info.param.name; });

TEST(Primitives, CylinderSideNormalsAreHorizontal) {
    const Mesh mesh = make_cylinder(1.0f, 2.0f, 16);
    for (const Vertex& vertex : mesh.vertices) {
        const bool on_cap = std::abs(vertex.normal.y) > 0.5f;
        if (on_cap) {
            EXPECT_NEAR(vertex.position.y, vertex.normal.y, 1e-6f);  // caps at +-height/2
        } else {
            EXPECT_NEAR(vertex.normal.y, 0.0f, 1e-6f);
        }
    }
}

TEST(ComposeTransform, IdentityForNeutralArguments) {
    EXPECT_EQ(compose_transform(glm::vec3{0.0f}, glm::vec3{0.0f}, glm::vec3{1.0f}), glm::mat4{1.0f});
}

TEST(ComposeTransform, RotatesAboutXThenYThenZ) {
    // X 90 takes +Y to +Z; Y 90 then takes +Z to +X. The other order would give +Z.
    const glm::mat4 transform = compose_transform(glm::vec3{0.0f}, {90.0f, 90.0f, 0.0f}, glm::vec3{1.0f});
    const glm::vec3 rotated{transform * glm::vec4{0.0f, 1.0f, 0.0f, 0.0f}};
    EXPECT_NEAR(rotated.x, 1.0f, 1e-6f);
    EXPECT_NEAR(rotated.y, 0.0f, 1e-6f);
    EXPECT_NEAR(rotated.z, 0.0f, 1e-6f);
}

TEST(ComposeTransform, ScalesThenRotatesThenTranslates) {
    const glm::mat4 transform = compose_transform({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 90.0f}, {2.0f, 1.0f, 1.0f});
    const glm::vec3 moved{transform * glm::vec4{1.0f, 0.0f, 0.0f, 1.0f}};
    EXPECT_NEAR(moved.x, 0.0f, 1e-6f);
    EXPECT_NEAR(moved.y, 2.0f, 1e-6f);
    EXPECT_NEAR(moved.z, 5.0f, 1e-6f);
}

TEST(MeshTools, SmoothNormalsAreAreaWeighted) {
    // Two triangles sharing vertex 0: a big one facing +Y and a small one facing +X.
    std::vector<Vertex> vertices(5);
    vertices[1].position = {0.0f, 0.0f, 2.0f};
    vertices[2].position = {2.0f, 0.0f, 0.0f};
    vertices[3].position = {0.0f, 1.0f, 0.0f};
    vertices[4].position = {0.0f, 0.0f, 1.0f};
    compute_smooth_normals(vertices, {0, 1, 2, 0, 3, 4});
    EXPECT_GT(vertices[0].normal.y, vertices[0].normal.x * 3.9f);  // areas 2 and 0.5
}

TEST(MeshTools, ReverseWindingSwapsTheLastTwoCorners) {
    std::vector<uint32_t> indices{0, 1, 2, 3, 4, 5};
    reverse_winding(indices);
    EXPECT_EQ(indices, (std::vector<uint32_t>{0, 2, 1, 3, 5, 4}));
}

// A repeated corner, three corners on a line and a real triangle: only the last is kept,
// numbered from its first corner, and the vertices only the others used go.
TEST(MeshTools, DegenerateTrianglesAndTheirVerticesAreDropped) {
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {5, 5, 5}};
    std::vector<uint32_t> indices{0, 1, 1, 0, 1, 2, 3, 1, 0};
    const std::optional<std::vector<uint32_t>> kept = drop_degenerate_triangles(positions, indices);
    ASSERT_TRUE(kept);
    EXPECT_EQ(*kept, (std::vector<uint32_t>{3, 1, 0}));
    EXPECT_EQ(indices, (std::vector<uint32_t>{0, 1, 2}));

    std::vector<uint32_t> whole{0, 1, 3};
    EXPECT_FALSE(drop_degenerate_triangles(positions, whole)) << "nothing dropped, nothing renumbered";
    EXPECT_EQ(whole, (std::vector<uint32_t>{0, 1, 3}));
}

}  // namespace
}  // namespace penumbra

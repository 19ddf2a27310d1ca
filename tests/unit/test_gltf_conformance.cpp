// glTF 2.0 features that shape a shadow (issue 19), each in a small fixture that must load
// to exactly what a plain equivalent loads to (tests/data/gltf/make_fixtures.py,
// write_conformance_fixtures): sparse accessors (with and without a bufferView, positions
// and indices), textureInfo.texCoord = 1, morph targets posed by mesh and node weights,
// KHR_mesh_quantization; and the clear errors for their malformed or undeclared forms.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "penumbra/scene/loader.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

using ::testing::HasSubstr;
using testing::input_error_message;
using testing::test_data;

Scene load_fixture(const std::string& name) {
    Scene scene;
    append_gltf(scene, test_data("gltf/" + name), {glm::mat4{1.0f}});
    return scene;
}

std::string load_error(const std::string& name) {
    return input_error_message([&] { load_fixture(name); });
}

// Each triangle's world-space corners, normals and texture coordinates, in index order:
// equal lists mean the same shadow caster whatever the vertex layout or node transform.
struct WorldTriangles {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
};

WorldTriangles world_triangles(const Scene& scene) {
    WorldTriangles triangles;
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[instance.mesh];
        const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3{instance.world}));
        for (const uint32_t index : mesh.indices) {
            const Vertex& vertex = mesh.vertices[index];
            triangles.positions.push_back(glm::vec3{instance.world * glm::vec4{vertex.position, 1.0f}});
            triangles.normals.push_back(glm::normalize(normal_matrix * vertex.normal));
            triangles.uvs.push_back(vertex.uv);
        }
    }
    return triangles;
}

void expect_same_triangles(const std::string& fixture, const std::string& equivalent) {
    SCOPED_TRACE(fixture + " against " + equivalent);
    const WorldTriangles expected = world_triangles(load_fixture(equivalent));
    const WorldTriangles actual = world_triangles(load_fixture(fixture));
    ASSERT_EQ(actual.positions.size(), expected.positions.size());
    ASSERT_FALSE(actual.positions.empty());
    for (size_t i = 0; i < actual.positions.size(); ++i) {
        EXPECT_LE(glm::distance(actual.positions[i], expected.positions[i]), 1e-6f) << "corner " << i;
        EXPECT_LE(glm::distance(actual.normals[i], expected.normals[i]), 1e-6f) << "normal " << i;
        EXPECT_EQ(actual.uvs[i], expected.uvs[i]) << "uv " << i;
    }
}

TEST(GltfConformance, SparsePositionsAndIndicesLoadAsTheDenseQuad) {
    expect_same_triangles("sparse.gltf", "quad.gltf");
    expect_same_triangles("sparse_without_buffer_view.gltf", "quad.gltf");
}

TEST(GltfConformance, AlphaTextureReadsTheTexcoordSetItNames) {
    expect_same_triangles("texcoord1.gltf", "textured.gltf");
    const Scene scene = load_fixture("texcoord1.gltf");
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.materials.at(scene.meshes[0].material).base_color_texture, 0);
}

TEST(GltfConformance, MorphTargetsPoseTheMeshWithMeshOrNodeWeights) {
    expect_same_triangles("morph_mesh_weights.gltf", "quad.gltf");
    expect_same_triangles("morph_node_weights.gltf", "quad.gltf");
}

TEST(GltfConformance, QuantizedAttributesLoadAsTheFloatQuad) { expect_same_triangles("quantized.gltf", "quad.gltf"); }

TEST(GltfConformance, MalformedOrUndeclaredFormsAreClearErrors) {
    EXPECT_THAT(load_error("sparse_index_out_of_range.gltf"),
                HasSubstr(".sparse.indices: index 2 at position 1 is out of range (the accessor has 2 elements)"));
    EXPECT_THAT(load_error("quantized_undeclared.gltf"),
                HasSubstr("attributes.POSITION: 3 components of SHORT needs the KHR_mesh_quantization extension"));
}

}  // namespace
}  // namespace penumbra

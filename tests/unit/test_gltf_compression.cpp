// Compressed glTF geometry: KHR_draco_mesh_compression and EXT_meshopt_compression are
// decoded (Draco's and meshoptimizer's decoders) into what the uncompressed file holds, and
// damaged compressed data is one InputError naming the JSON path.
#include <dlfcn.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <fstream>
#include <glm/geometric.hpp>

#include "compressed_gltf.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::input_error_message;

// Debian's assimp-testmodels (scripts/setup.sh): the Khronos 2CylinderEngine, Draco-compressed
// and plain.
const fs::path kAssimpGltf = "/usr/share/assimp/models/glTF2";
const fs::path kDracoEngine = kAssimpGltf / "draco/2CylinderEngine.gltf";
const fs::path kPlainEngine = kAssimpGltf / "2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

class GltfCompression : public testing::ScratchFolderTest {
protected:
    static Scene load(const fs::path& file) {
        Scene scene;
        append_gltf(scene, file, {glm::mat4{1.0f}});
        return scene;
    }

    static std::string load_error(const fs::path& file) {
        return input_error_message([&] { load(file); });
    }
};

// libdraco.so.7 exports its own build of tinygltf; the loader's calls must reach Debian's
// libtinygltf (the classes differ in layout: the wrong one frees what it did not allocate).
TEST(GltfCompressionLinking, TinygltfIsDebiansLibrary) {
    Dl_info info{};
    ASSERT_NE(::dladdr(reinterpret_cast<void*>(&tinygltf::LoadImageData), &info), 0);
    EXPECT_THAT(info.dli_fname, HasSubstr("libtinygltf")) << "link TinyGLTF::TinyGLTF before draco::draco";
}

#define SKIP_WITHOUT_ENGINE_MODELS()                                                                        \
    if (!fs::exists(kDracoEngine) || !fs::exists(kPlainEngine))                                             \
    GTEST_SKIP() << kDracoEngine << " or " << kPlainEngine                                                  \
                 << " not found: Debian's assimp-testmodels package (scripts/setup.sh) brings the Khronos " \
                    "2CylinderEngine in both forms"

// The Draco file quantizes positions to 14 bits over each mesh's bounds (its meshes are a
// few hundred units across): a corner moves by at most half a step, well under 0.1 unit.
TEST_F(GltfCompression, DracoEngineMatchesTheUncompressedOne) {
    SKIP_WITHOUT_ENGINE_MODELS();
    const Scene draco = load(kDracoEngine);
    const Scene plain = load(kPlainEngine);
    // Not equal: the two files do not store the same triangles. Draco's encoder left out the
    // degenerate ones (65,311 indexed triangles against 75,730 over the 29 meshes), which the
    // loader drops from the plain file; as placed, 110,319 against 110,336 remain, the 17
    // (0.015 %) presumably thin triangles that 14-bit quantization flattened to no area.
    EXPECT_NEAR(double(draco.triangle_count()), double(plain.triangle_count()), 0.0005 * plain.triangle_count());
    EXPECT_EQ(draco.instances.size(), plain.instances.size());
    const Aabb draco_bounds = draco.world_bounds();
    const Aabb plain_bounds = plain.world_bounds();
    const float step = glm::length(plain_bounds.max - plain_bounds.min) / float(1 << 14);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(draco_bounds.min[axis], plain_bounds.min[axis], step) << "axis " << axis;
        EXPECT_NEAR(draco_bounds.max[axis], plain_bounds.max[axis], step) << "axis " << axis;
    }
    EXPECT_TRUE(draco.warnings.empty()) << draco.warnings.front();
}

TEST_F(GltfCompression, DracoSphereMatchesItsSource) {
    const Mesh source = testing::compressed_test_sphere();
    const Scene scene = load(write("sphere.glb", testing::draco_sphere_glb()));
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].indices.size(), source.indices.size());
    // 14-bit positions over the sphere's 2-unit extent.
    const float step = 2.0f / float((1 << 14) - 1);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(scene.meshes[0].bounds.min[axis], source.bounds.min[axis], step);
        EXPECT_NEAR(scene.meshes[0].bounds.max[axis], source.bounds.max[axis], step);
    }
    for (const Vertex& vertex : scene.meshes[0].vertices) {
        EXPECT_NEAR(glm::length(vertex.position), 1.0f, step);
        EXPECT_GT(glm::dot(vertex.normal, glm::normalize(vertex.position)), 0.99f);
    }
}

// Without a filter the attribute codec is lossless; the 8-bit octahedral filter keeps each
// normal within about 1/127 per component.
TEST_F(GltfCompression, MeshoptSphereMatchesItsSource) {
    const Mesh source = testing::compressed_test_sphere();
    const Scene scene = load(write("sphere.glb", testing::meshopt_sphere_glb()));
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    EXPECT_EQ(mesh.indices, source.indices);
    ASSERT_EQ(mesh.vertices.size(), source.vertices.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        EXPECT_EQ(mesh.vertices[i].position, source.vertices[i].position) << "vertex " << i;
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(mesh.vertices[i].normal[c], source.vertices[i].normal[c], 0.02f) << "vertex " << i;
        }
    }
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
}

TEST_F(GltfCompression, TruncatedMeshoptDataIsOneError) {
    const std::string message = load_error(write("cut.glb", testing::meshopt_sphere_glb(16)));
    EXPECT_THAT(message, HasSubstr("bufferViews[0].extensions.EXT_meshopt_compression: the compressed data is "
                                   "corrupt or cut short"));
}

TEST_F(GltfCompression, CorruptDracoDataIsOneError) {
    const std::string message = load_error(write("corrupt.glb", testing::draco_sphere_glb({0, "XXXXX"})));
    EXPECT_THAT(message, HasSubstr("meshes[0].primitives[0].extensions.KHR_draco_mesh_compression: cannot decode "
                                   "the Draco mesh in bufferViews[0]"));
}

// Draco's encoder may leave out degenerate faces, never add any.
TEST_F(GltfCompression, DracoMeshWithMoreIndicesThanDeclaredIsOneError) {
    const std::string message = load_error(write("indices.glb", testing::draco_sphere_glb({0, "", 3})));
    EXPECT_THAT(message, HasSubstr("meshes[0].primitives[0].extensions.KHR_draco_mesh_compression: the Draco mesh "
                                   "decodes 672 corners, more than the 669 of the index accessor"));
}

// Damage past the header: Draco may still decode something, but never a crash; what it
// decodes must agree with the accessors or be refused.
TEST_F(GltfCompression, DamagedDracoBodyIsRefusedOrDecodedWhole) {
    for (size_t offset = 8; offset < 200; offset += 7) {
        const fs::path file = write("damaged.glb", testing::draco_sphere_glb({offset, std::string(5, '\xA5')}));
        try {
            load(file);
        } catch (const InputError& error) {
            EXPECT_THAT(error.what(), HasSubstr("KHR_draco_mesh_compression")) << "offset " << offset;
        }
    }
}

TEST_F(GltfCompression, DracoEngineWithCorruptBytesIsOneError) {
    SKIP_WITHOUT_ENGINE_MODELS();
    fs::copy_file(kDracoEngine, dir_ / "engine.gltf");
    std::ifstream in(kDracoEngine.parent_path() / "2CylinderEngine.bin", std::ios::binary);
    std::string bin((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Each Draco view starts with the "DRACO" magic; the first one's is overwritten.
    const size_t magic = bin.find("DRACO");
    ASSERT_NE(magic, std::string::npos);
    bin.replace(magic, 5, "draco");
    write("2CylinderEngine.bin", bin);
    EXPECT_THAT(load_error(dir_ / "engine.gltf"), HasSubstr("cannot decode the Draco mesh"));
}

// The declared sizes are checked against the load budget before anything is decoded.
TEST_F(GltfCompression, MeshoptOverTheBudgetIsRefusedBeforeDecoding) {
    const fs::path file = write("sphere.glb", testing::meshopt_sphere_glb());
    const std::string message = input_error_message([&] {
        Scene scene;
        GltfImportOptions options;
        options.budget.max_bytes = 1000;
        append_gltf(scene, file, {glm::mat4{1.0f}}, options);
    });
    EXPECT_THAT(message, HasSubstr("bufferViews[0].extensions.EXT_meshopt_compression: decompresses to 1836 bytes, "
                                   "which would take the scene past the load budget of 1000 bytes"));
    EXPECT_THAT(message, HasSubstr("refused before decoding"));
}

}  // namespace
}  // namespace penumbra

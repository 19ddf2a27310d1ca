#pragma once
// Writes small glTF 2.0 models for tests: positions and 32-bit indices per primitive in
// one external .bin buffer, one root node per mesh (names optional, as in real files).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace penumbra::testing {

struct GltfTestPrimitive {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;  // counter-clockwise triangles
    std::vector<glm::vec4> colors;  // COLOR_0 (VEC4 of FLOAT) when not empty
};

struct GltfTestNode {
    std::string node_name;  // empty: the node has no "name"
    std::string mesh_name;  // empty: the mesh has no "name"
    std::vector<GltfTestPrimitive> primitives;
    nlohmann::json material = nullptr;  // the primitives' material, as glTF JSON; null: none
};

// `image_uris[i]` becomes images[i] and textures[i] (no sampler), for materials to name.
inline void write_test_gltf(const std::filesystem::path& file, const std::vector<GltfTestNode>& nodes,
                            const std::vector<std::string>& image_uris = {}) {
    nlohmann::json document = {{"asset", {{"version", "2.0"}}}, {"scene", 0}};
    for (size_t i = 0; i < image_uris.size(); ++i) {
        document["images"].push_back({{"uri", image_uris[i]}});
        document["textures"].push_back({{"source", i}});
    }
    std::string bytes;
    const auto append = [&](const void* data, size_t size, int target) {
        const size_t offset = bytes.size();
        bytes.append(static_cast<const char*>(data), size);
        document["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}, {"target", target}});
        return document["bufferViews"].size() - 1;
    };
    for (size_t n = 0; n < nodes.size(); ++n) {
        nlohmann::json mesh = {{"primitives", nlohmann::json::array()}};
        if (!nodes[n].mesh_name.empty()) mesh["name"] = nodes[n].mesh_name;
        for (const GltfTestPrimitive& primitive : nodes[n].primitives) {
            glm::vec3 low{1e30f}, high{-1e30f};
            for (const glm::vec3& p : primitive.positions) low = glm::min(low, p), high = glm::max(high, p);
            const size_t positions = append(primitive.positions.data(), primitive.positions.size() * 12, 34962);
            document["accessors"].push_back({{"bufferView", positions},
                                             {"componentType", 5126},
                                             {"count", primitive.positions.size()},
                                             {"type", "VEC3"},
                                             {"min", {low.x, low.y, low.z}},
                                             {"max", {high.x, high.y, high.z}}});
            const size_t indices = append(primitive.indices.data(), primitive.indices.size() * 4, 34963);
            document["accessors"].push_back({{"bufferView", indices},
                                             {"componentType", 5125},
                                             {"count", primitive.indices.size()},
                                             {"type", "SCALAR"}});
            const size_t accessors = document["accessors"].size();
            nlohmann::json written = {{"attributes", {{"POSITION", accessors - 2}}}, {"indices", accessors - 1}};
            if (!primitive.colors.empty()) {
                const size_t colors = append(primitive.colors.data(), primitive.colors.size() * 16, 34962);
                document["accessors"].push_back({{"bufferView", colors},
                                                 {"componentType", 5126},
                                                 {"count", primitive.colors.size()},
                                                 {"type", "VEC4"}});
                written["attributes"]["COLOR_0"] = document["accessors"].size() - 1;
            }
            if (!nodes[n].material.is_null()) {
                written["material"] = document["materials"].size();
                document["materials"].push_back(nodes[n].material);
            }
            mesh["primitives"].push_back(written);
        }
        document["meshes"].push_back(mesh);
        nlohmann::json node = {{"mesh", n}};
        if (!nodes[n].node_name.empty()) node["name"] = nodes[n].node_name;
        document["nodes"].push_back(node);
        document["scenes"][0]["nodes"].push_back(n);
    }
    const std::filesystem::path buffer = std::filesystem::path(file).replace_extension(".bin");
    document["buffers"] = {{{"byteLength", bytes.size()}, {"uri", buffer.filename().string()}}};
    std::ofstream(buffer, std::ios::binary) << bytes;
    std::ofstream(file) << document.dump();
}

// Two counter-clockwise triangles of the quad a, b, c, d (in order around it).
inline void add_test_quad(GltfTestPrimitive& primitive, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    const auto first = static_cast<uint32_t>(primitive.positions.size());
    primitive.positions.insert(primitive.positions.end(), {a, b, c, d});
    primitive.indices.insert(primitive.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
}

// Face `face` (0 to 5: -X, +X, -Y, +Y, -Z, +Z) of the cube of half-size `half` around `center`.
inline void add_test_box_face(GltfTestPrimitive& primitive, glm::vec3 center, float half, int face) {
    const int axis = face / 2;
    const float side = face % 2 ? half : -half;
    glm::vec3 corners[4];
    for (int k = 0; k < 4; ++k) {
        glm::vec3 p{0.0f};
        p[axis] = side;
        p[(axis + 1) % 3] = (k == 1 || k == 2) ? half : -half;
        p[(axis + 2) % 3] = (k >= 2) ? half : -half;
        corners[k] = center + p;
    }
    // Counter-clockwise seen from outside: the +side faces keep the order, the -side ones flip it.
    if (face % 2) {
        add_test_quad(primitive, corners[0], corners[1], corners[2], corners[3]);
    } else {
        add_test_quad(primitive, corners[0], corners[3], corners[2], corners[1]);
    }
}

inline GltfTestPrimitive test_box(glm::vec3 center, float half) {
    GltfTestPrimitive box;
    for (int face = 0; face < 6; ++face) add_test_box_face(box, center, half, face);
    return box;
}

}  // namespace penumbra::testing

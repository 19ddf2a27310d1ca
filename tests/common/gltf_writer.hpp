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
};

struct GltfTestNode {
    std::string node_name;  // empty: the node has no "name"
    std::string mesh_name;  // empty: the mesh has no "name"
    std::vector<GltfTestPrimitive> primitives;
};

inline void write_test_gltf(const std::filesystem::path& file, const std::vector<GltfTestNode>& nodes) {
    nlohmann::json document = {{"asset", {{"version", "2.0"}}}, {"scene", 0}};
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
            mesh["primitives"].push_back({{"attributes", {{"POSITION", accessors - 2}}}, {"indices", accessors - 1}});
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

}  // namespace penumbra::testing

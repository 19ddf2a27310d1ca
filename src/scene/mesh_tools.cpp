#include "scene/mesh_tools.hpp"

#include <glm/geometric.hpp>
#include <utility>

namespace penumbra {

Aabb compute_mesh_bounds(const std::vector<Vertex>& vertices) {
    Aabb bounds;
    for (const Vertex& vertex : vertices) bounds.expand(vertex.position);
    return bounds;
}

std::optional<std::vector<uint32_t>> drop_degenerate_triangles(const std::vector<glm::vec3>& positions,
                                                               std::vector<uint32_t>& indices) {
    const auto has_area = [&](size_t first) {
        const glm::vec3& a = positions[indices[first]];
        return glm::cross(positions[indices[first + 1]] - a, positions[indices[first + 2]] - a) != glm::vec3{0.0f};
    };
    size_t kept_corners = 0;
    for (size_t first = 0; first + 2 < indices.size(); first += 3) {
        if (!has_area(first)) continue;
        for (size_t corner = 0; corner < 3; ++corner) indices[kept_corners++] = indices[first + corner];
    }
    if (kept_corners == indices.size()) return std::nullopt;
    indices.resize(kept_corners);
    constexpr uint32_t kUnused = ~uint32_t{0};
    std::vector<uint32_t> new_index(positions.size(), kUnused);
    std::vector<uint32_t> old_index;
    for (uint32_t& index : indices) {
        if (new_index[index] == kUnused) {
            new_index[index] = static_cast<uint32_t>(old_index.size());
            old_index.push_back(index);
        }
        index = new_index[index];
    }
    return old_index;
}

void compute_smooth_normals(std::vector<Vertex>& vertices, const std::vector<uint32_t>& indices) {
    std::vector<glm::vec3> normal_sums(vertices.size(), glm::vec3{0.0f});
    for (size_t first = 0; first + 2 < indices.size(); first += 3) {
        const uint32_t a = indices[first];
        const uint32_t b = indices[first + 1];
        const uint32_t c = indices[first + 2];
        const glm::vec3 area_weighted_normal =
            glm::cross(vertices[b].position - vertices[a].position, vertices[c].position - vertices[a].position);
        normal_sums[a] += area_weighted_normal;
        normal_sums[b] += area_weighted_normal;
        normal_sums[c] += area_weighted_normal;
    }
    for (size_t i = 0; i < vertices.size(); ++i) {
        const float length = glm::length(normal_sums[i]);
        vertices[i].normal = length > 0.0f ? normal_sums[i] / length : glm::vec3{0.0f, 1.0f, 0.0f};
    }
}

void reverse_winding(std::vector<uint32_t>& indices) {
    for (size_t first = 0; first + 2 < indices.size(); first += 3) std::swap(indices[first + 1], indices[first + 2]);
}

}  // namespace penumbra

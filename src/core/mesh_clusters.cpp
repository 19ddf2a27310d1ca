#include "core/mesh_clusters.hpp"

#include <algorithm>
#include <numeric>

namespace penumbra::core {
namespace {

// Spreads the low 10 bits of `v` to every third bit (a 30-bit Morton code's one axis).
uint32_t spread_bits(uint32_t v) {
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

uint32_t morton_code(const glm::vec3& unit) {
    const glm::uvec3 cell = glm::uvec3(glm::clamp(unit, glm::vec3(0.0f), glm::vec3(1.0f)) * 1023.0f);
    return spread_bits(cell.x) | (spread_bits(cell.y) << 1) | (spread_bits(cell.z) << 2);
}

}  // namespace

Aabb index_range_bounds(std::span<const glm::vec3> positions, std::span<const uint32_t> indices, uint32_t first,
                        uint32_t count) {
    Aabb bounds;
    for (uint32_t i = first; i < first + count; ++i) bounds.expand(positions[indices[i]]);
    return bounds;
}

std::vector<MeshCluster> cluster_triangles(std::span<const glm::vec3> positions, std::span<uint32_t> indices,
                                           uint32_t max_triangles) {
    const size_t triangles = indices.size() / 3;
    if (triangles == 0 || max_triangles == 0) return {};
    Aabb mesh;
    for (const uint32_t index : indices) mesh.expand(positions[index]);
    // One scale for every axis: a flat mesh spends its code on its two long axes.
    const float extent = std::max({mesh.extent().x, mesh.extent().y, mesh.extent().z, 1e-30f});
    const glm::vec3 scale(1.0f / extent);
    std::vector<uint32_t> codes(triangles);
    for (size_t t = 0; t < triangles; ++t) {
        const glm::vec3 centroid =
            (positions[indices[3 * t]] + positions[indices[3 * t + 1]] + positions[indices[3 * t + 2]]) / 3.0f;
        codes[t] = morton_code((centroid - mesh.min) * scale);
    }
    std::vector<uint32_t> order(triangles);
    std::iota(order.begin(), order.end(), 0u);
    // Stable: triangles of one Morton cell keep the caller's order.
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return codes[a] < codes[b]; });
    const std::vector<uint32_t> original(indices.begin(), indices.end());
    for (size_t t = 0; t < triangles; ++t) {
        for (size_t corner = 0; corner < 3; ++corner) indices[3 * t + corner] = original[3 * order[t] + corner];
    }
    std::vector<MeshCluster> clusters;
    for (size_t first = 0; first < triangles; first += max_triangles) {
        MeshCluster cluster;
        cluster.first_index = static_cast<uint32_t>(3 * first);
        cluster.index_count = static_cast<uint32_t>(3 * std::min<size_t>(max_triangles, triangles - first));
        cluster.bounds = index_range_bounds(positions, indices, cluster.first_index, cluster.index_count);
        clusters.push_back(cluster);
    }
    return clusters;
}

}  // namespace penumbra::core

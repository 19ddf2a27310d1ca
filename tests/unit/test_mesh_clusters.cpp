// Clusters of a triangle mesh (core/mesh_clusters.hpp): the reordered list holds every
// triangle once with its corners in their order (windings kept), the runs cover it in
// order with at most 128 triangles each and bound exactly their vertices, and a grid listed
// row by row comes out in compact blocks rather than strips.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "core/mesh_clusters.hpp"

namespace penumbra::core {
namespace {

// A flat grid of `cells` x `cells` unit quads, two triangles each, listed row by row.
struct Grid {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
};

Grid row_by_row_grid(uint32_t cells) {
    Grid grid;
    for (uint32_t z = 0; z <= cells; ++z) {
        for (uint32_t x = 0; x <= cells; ++x) grid.positions.emplace_back(float(x), 0.0f, float(z));
    }
    for (uint32_t z = 0; z < cells; ++z) {
        for (uint32_t x = 0; x < cells; ++x) {
            const uint32_t a = z * (cells + 1) + x, b = a + 1, c = a + cells + 1, d = c + 1;
            grid.indices.insert(grid.indices.end(), {a, c, d, a, d, b});
        }
    }
    return grid;
}

// Each triangle as its corners rotated to start at the smallest index (the same triangle
// with the same winding compares equal whatever corner a list starts it at).
std::vector<std::array<uint32_t, 3>> triangles_of(const std::vector<uint32_t>& indices) {
    std::vector<std::array<uint32_t, 3>> triangles;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        std::array<uint32_t, 3> corners{indices[t], indices[t + 1], indices[t + 2]};
        std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
        triangles.push_back(corners);
    }
    std::sort(triangles.begin(), triangles.end());
    return triangles;
}

TEST(MeshClusters, EveryTriangleStaysOnceWithItsWindingAndTheRunsCoverTheList) {
    const Grid grid = row_by_row_grid(40);  // 3,200 triangles: 25 runs of 128
    std::vector<uint32_t> indices = grid.indices;
    const std::vector<MeshCluster> clusters = cluster_triangles(grid.positions, indices);
    EXPECT_EQ(triangles_of(indices), triangles_of(grid.indices));
    ASSERT_EQ(clusters.size(), 25u);
    uint32_t next = 0;
    for (const MeshCluster& cluster : clusters) {
        EXPECT_EQ(cluster.first_index, next);
        EXPECT_GT(cluster.index_count, 0u);
        EXPECT_LE(cluster.index_count, 3 * kMaxClusterTriangles);
        EXPECT_EQ(cluster.index_count % 3, 0u);
        const Aabb exact = index_range_bounds(grid.positions, indices, cluster.first_index, cluster.index_count);
        EXPECT_EQ(cluster.bounds.min, exact.min);
        EXPECT_EQ(cluster.bounds.max, exact.max);
        next += cluster.index_count;
    }
    EXPECT_EQ(next, indices.size());
}

TEST(MeshClusters, ARowByRowGridComesOutInBlocksNotStrips) {
    const Grid grid = row_by_row_grid(64);  // 8,192 triangles; a row is 128 triangles
    std::vector<uint32_t> indices = grid.indices;
    const std::vector<MeshCluster> clusters = cluster_triangles(grid.positions, indices);
    ASSERT_EQ(clusters.size(), 64u);
    // In the caller's order a run is a strip 64 cells long and 1 wide; along the Morton
    // curve, 64 cells of the same 8 x 8 block.
    for (const MeshCluster& cluster : clusters) {
        const glm::vec3 extent = cluster.bounds.extent();
        EXPECT_LE(std::max(extent.x, extent.z), 8.0f) << "a run " << extent.x << " x " << extent.z;
    }
}

TEST(MeshClusters, SmallAndEmptyListsAndSmallerRuns) {
    const Grid grid = row_by_row_grid(2);  // 8 triangles
    std::vector<uint32_t> indices = grid.indices;
    const std::vector<MeshCluster> one = cluster_triangles(grid.positions, indices);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one[0].index_count, 24u);
    std::vector<uint32_t> again = grid.indices;
    EXPECT_EQ(cluster_triangles(grid.positions, again, 3).size(), 3u) << "8 triangles in runs of 3";
    std::vector<uint32_t> none;
    EXPECT_TRUE(cluster_triangles(grid.positions, none).empty());
}

}  // namespace
}  // namespace penumbra::core

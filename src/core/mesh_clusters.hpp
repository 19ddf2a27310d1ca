#pragma once
// Clusters of a triangle mesh: runs of nearby triangles with their own bounds, so that a
// pass can cull finer than a mesh instance (the cluster culling of GPU-driven renderers:
// Wihlidal, "Optimizing the Graphics Pipeline with Compute", GDC 2016; UE5's Nanite and
// its virtual shadow maps cull clusters against the pages they draw).

#include <cstdint>
#include <span>
#include <vector>

#include "core/shadow_inputs.hpp"

namespace penumbra::core {

// Triangles per cluster: small enough that a cluster rarely reaches far beyond one page of
// a fine level, large enough that a 1 M-triangle scene has ~10^4 of them to cull.
inline constexpr uint32_t kMaxClusterTriangles = 128;

struct MeshCluster {
    uint32_t first_index = 0;  // into the mesh's index list, a multiple of 3
    uint32_t index_count = 0;  // a positive multiple of 3
    Aabb bounds;               // of the vertices its indices reach
};

// Reorders the triangles of `indices` (each triangle's three indices stay together and in
// their order, so windings are kept) along a Morton curve through their centroids, and
// returns the runs of at most `max_triangles` consecutive triangles that cover the list.
// Every index must be < positions.size().
std::vector<MeshCluster> cluster_triangles(std::span<const glm::vec3> positions, std::span<uint32_t> indices,
                                           uint32_t max_triangles = kMaxClusterTriangles);

// The bounds of the vertices that indices [first, first + count) reach.
Aabb index_range_bounds(std::span<const glm::vec3> positions, std::span<const uint32_t> indices, uint32_t first,
                        uint32_t count);

}  // namespace penumbra::core

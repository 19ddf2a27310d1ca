#pragma once
// Small operations on penumbra::Mesh shared by the primitive generators and the glTF
// loader: bounds, smooth normals for models that ship without them, and mirrored copies.
#include <cstdint>
#include <optional>
#include <vector>

#include "penumbra/scene/scene.hpp"

namespace penumbra {

// Bounds of the mesh's vertex positions (empty Aabb for a mesh without vertices).
Aabb compute_mesh_bounds(const std::vector<Vertex>& vertices);

// Replaces every vertex normal with the area-weighted average of the normals of the
// triangles that use it (the cross product's length is twice the area, so summing
// unnormalised face normals weights by area). Vertices used by no triangle, or only by
// degenerate ones, get +Y.
void compute_smooth_normals(std::vector<Vertex>& vertices, const std::vector<uint32_t>& indices);

// Drops the triangles of zero area (two corners on one point, or three on a line, exactly):
// they rasterise no fragment in a shadow map or the image but cost their vertices and their
// share of every draw. When any is dropped the vertices no kept triangle uses go too, and
// the result lists the old index of each kept vertex (`indices` renumbered to match); when
// none is, nothing changes and the result is empty. An accessor of millions of default
// (zero) positions with a few sparse ones keeps only the few that make area.
std::optional<std::vector<uint32_t>> drop_degenerate_triangles(const std::vector<glm::vec3>& positions,
                                                               std::vector<uint32_t>& indices);

// Reverses the winding of every triangle (a, b, c) -> (a, c, b).
void reverse_winding(std::vector<uint32_t>& indices);

}  // namespace penumbra

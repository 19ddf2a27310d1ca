#pragma once
// Small operations on penumbra::Mesh shared by the primitive generators and the glTF
// loader: bounds, smooth normals for models that ship without them, and mirrored copies.
#include <cstdint>
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

// Reverses the winding of every triangle (a, b, c) -> (a, c, b).
void reverse_winding(std::vector<uint32_t>& indices);

}  // namespace penumbra

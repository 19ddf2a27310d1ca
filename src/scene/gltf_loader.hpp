#pragma once
// glTF 2.0 (.gltf with external or embedded buffers, and .glb) into a penumbra::Scene:
// node hierarchy and transforms, triangle meshes with 16/32-bit indices, positions,
// normals (computed when missing), UV0, base colour factor and texture, alphaMode with
// alphaCutoff, doubleSided.
#include <filesystem>
#include <vector>

#include "core/scene.hpp"

namespace penumbra {

// Appends the model's meshes, materials and textures to `scene` and one Instance per
// (mesh primitive, placement): instance.world = placement * node world transform.
// Triangle strips and fans become lists; points and lines are skipped. A placement whose
// world transform mirrors (negative determinant) gets a copy of the mesh with reversed
// winding, so front faces stay counter-clockwise in world space.
// Throws InputError naming the file and the problem (missing file, malformed JSON,
// out-of-range accessor or index, missing buffer, unsupported primitive mode...); the
// scene is then left as it was.
void append_gltf(Scene& scene, const std::filesystem::path& file, const std::vector<glm::mat4>& placements);

}  // namespace penumbra

#pragma once
// Procedural meshes for the scene file's primitive objects (Penumbra::scene). All are centred on the
// origin with outward normals and counter-clockwise front faces.
#include <cstdint>

#include "penumbra/scene/scene.hpp"

namespace penumbra {

Mesh make_plane(float size_x, float size_z);  // in XZ, facing +Y
Mesh make_box(const glm::vec3& size);         // full extents
Mesh make_sphere(float radius, uint32_t segments = 32, uint32_t rings = 16);
Mesh make_cylinder(float radius, float height, uint32_t segments = 32);  // axis +Y, capped

// Euler angles in degrees applied X, then Y, then Z (R = Rz * Ry * Rx), then the
// translation: T * R * S.
glm::mat4 compose_transform(const glm::vec3& translation, const glm::vec3& rotation_degrees, const glm::vec3& scale);

}  // namespace penumbra

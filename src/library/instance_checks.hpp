#pragma once
// The checks of the geometry a caller hands to a ShadowSystem that go beyond "finite":
// coordinates within kMaxWorldMagnitude, instance transforms that are the invertible affine
// maps the header promises, and flags that InstanceFlags defines. Each failure is one
// InputError "ShadowSystem::<call>: <argument>: <problem, with the value>".
#include <cstdint>
#include <span>

#include "core/shadow_inputs.hpp"
#include "penumbra/math.hpp"

namespace penumbra::library {

// Every position finite and within kMaxWorldMagnitude (MeshData::positions).
void check_positions(std::span<const Vec3> positions, const char* call);

// A mesh's bounds within kMaxWorldMagnitude (MeshDesc::bounds; finite and ordered are
// checked with the rest of the MeshDesc).
void check_bounds_magnitude(const Bounds& bounds, const char* call);

// `world` finite, affine (bottom row 0, 0, 0, 1), invertible (its 3x3 part not singular)
// and placing `mesh_bounds` within kMaxWorldMagnitude; returns the instance's world bounds.
core::Aabb checked_world_bounds(const Mat4& world, const core::Aabb& mesh_bounds, const char* call);

// Only bits that InstanceFlags defines (kInstanceAllFlags).
void check_instance_flags(uint32_t flags, const char* call);

}  // namespace penumbra::library

#pragma once
// Penumbra, real-time shadows on your Vulkan device: the one header an application
// includes (docs/library.md). Everything public is under include/penumbra/.
#include "penumbra/device.hpp"         // DeviceDesc, device requirements, VulkanContext
#include "penumbra/errors.hpp"         // the exceptions Penumbra throws
#include "penumbra/lights.hpp"         // LightDesc
#include "penumbra/math.hpp"           // Vec2, Vec3, Mat4, Bounds
#include "penumbra/memory.hpp"         // DeviceMemoryAllocator: where images and buffers get memory
#include "penumbra/settings.hpp"       // Settings and their validation
#include "penumbra/shadow_system.hpp"  // ShadowSystem: meshes, instances, frames
#include "penumbra/version.hpp"        // PENUMBRA_VERSION_*

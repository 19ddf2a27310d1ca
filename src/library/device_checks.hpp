#pragma once
// Checks that a caller's device can run a ShadowSystem (docs/library.md, "Device
// requirements") and reads which optional features it has.
#include "penumbra/device.hpp"
#include "penumbra/gpu/device.hpp"

namespace penumbra::library {

// Throws InputError for a description with null handles, DeviceError naming the first
// missing version, feature or queue capability. Returns the optional features enabled.
gpu::EnabledFeatures check_device(const DeviceDesc& desc, PFN_vkGetInstanceProcAddr get_instance_proc_addr);

}  // namespace penumbra::library

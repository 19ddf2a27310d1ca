#pragma once
// Where Penumbra's images and buffers get their device memory. By default Penumbra
// sub-allocates from a few large blocks of its own (one vkAllocateMemory per block, not per
// resource); an engine that manages device memory itself (VMA, its own heaps, budgets)
// gives a DeviceMemoryAllocator in DeviceDesc::allocator and every image and buffer of the
// ShadowSystem is bound to memory it returns.
#include <vulkan/vulkan_core.h>

namespace penumbra {

// What one image or buffer needs.
struct MemoryRequest {
    VkMemoryRequirements requirements{};  // from vkGet{Image,Buffer}MemoryRequirements
    // Properties the memory type must have: VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT for maps and
    // GPU buffers; HOST_VISIBLE | HOST_COHERENT for uniforms, uploads and readbacks.
    VkMemoryPropertyFlags required_properties = 0;
    // Penumbra reads or writes the memory from the host: MemoryAllocation::mapped must be
    // the host address of the allocation (kept mapped until it is freed; Penumbra never
    // calls vkMapMemory on memory it did not allocate itself).
    bool host_access = false;
    // A buffer (linear) or an optimal-tiling image: where both share a VkDeviceMemory,
    // VkPhysicalDeviceLimits::bufferImageGranularity separates them.
    bool linear = false;
    const char* purpose = "";  // what it is for, e.g. "cascade maps" (debug names and errors)
};

// Where a request was placed.
struct MemoryAllocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;    // a multiple of MemoryRequest::requirements.alignment
    void* mapped = nullptr;     // with MemoryRequest::host_access: the host address of `offset`
    void* user_data = nullptr;  // the allocator's own, given back to free()
};

// An engine's allocator. Called from the thread that uses the ShadowSystem, only during
// its calls; it must outlive the ShadowSystem. allocate() throws (any exception, which
// reaches the ShadowSystem's caller) or returns memory == VK_NULL_HANDLE when it cannot
// (Penumbra then throws a DeviceError naming the request). free() comes once per
// allocation, after the GPU has finished using it (Penumbra keeps what frames in flight
// may still use until their slots are reused) and at the latest when the ShadowSystem is
// destroyed.
class DeviceMemoryAllocator {
public:
    virtual ~DeviceMemoryAllocator() = default;
    virtual MemoryAllocation allocate(const MemoryRequest& request) = 0;
    virtual void free(const MemoryAllocation& allocation) noexcept = 0;
};

}  // namespace penumbra

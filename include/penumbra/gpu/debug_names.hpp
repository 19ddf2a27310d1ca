#pragma once
// Debug names and command labels (VK_EXT_debug_utils). When the caller's instance has the
// extension enabled, every object the gpu helpers create is named after what it is for
// ("penumbra cascade maps: image") and every timed pass is a command label ("penumbra
// shadow_cascade_2"), so RenderDoc, Nsight and the validation layer's messages name
// Penumbra's objects instead of showing anonymous handles. Without the extension nothing
// is called.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

#include "penumbra/gpu/device.hpp"

namespace penumbra::gpu {

// While it lives, the objects the gpu helpers create on `device` are named
// "penumbra <purpose>: <kind>"; the previous purpose comes back when it ends.
class ObjectNames {
public:
    ObjectNames(const Device& device, const std::string& purpose);
    ~ObjectNames();
    ObjectNames(const ObjectNames&) = delete;
    ObjectNames& operator=(const ObjectNames&) = delete;

private:
    const Device& device_;
    std::string previous_;
};

// Makes an object with `make()` while the Vulkan objects it creates are named for
// `purpose`: for member initialisers, which an ObjectNames cannot enclose. The result is
// returned as the prvalue make() gives, so non-movable objects work too.
template <typename Make>
auto named(const Device& device, const std::string& purpose, Make&& make) -> decltype(make()) {
    const ObjectNames names(device, purpose);
    return make();
}

// Names one object "<the current purpose>: <kind>" (the helpers call it for what they create).
void name_object(const Device& device, VkObjectType type, uint64_t handle, const char* kind);

template <typename Handle>
void name_object(const Device& device, VkObjectType type, Handle handle, const char* kind) {
    // Vulkan handles are pointers on the 64-bit platforms Penumbra builds for.
    static_assert(sizeof(Handle) == sizeof(uint64_t));
    name_object(device, type, reinterpret_cast<uint64_t>(handle), kind);
}

// A command label "penumbra <name>" around the commands recorded while it lives.
class CommandLabel {
public:
    CommandLabel(const Device& device, VkCommandBuffer cmd, const std::string& name);
    ~CommandLabel();
    CommandLabel(const CommandLabel&) = delete;
    CommandLabel& operator=(const CommandLabel&) = delete;

private:
    const Device& device_;
    VkCommandBuffer cmd_;
};

}  // namespace penumbra::gpu

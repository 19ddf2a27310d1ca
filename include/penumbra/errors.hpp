#pragma once
// Penumbra reports every failure by throwing one of these (docs/library.md, "Errors").
// Each message is one line that names what went wrong and where it came from
// ("ShadowSystem::add_mesh: positions.stride: 0 must be at least 12 bytes"), so a caller
// can print it verbatim. Nothing is printed by the library itself.
#include <vulkan/vulkan_core.h>

#include <stdexcept>
#include <string>

namespace penumbra {

// The base of every error Penumbra throws.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A value, description or file the caller passed is invalid: out of range, malformed,
// inconsistent. The message names the field or setting and the offending value.
class InputError : public Error {
public:
    using Error::Error;
};

// The API was used out of order or with something it does not know: an unknown or removed
// handle, record_shadow_maps() before prepare(), settings that need a new ShadowSystem.
class UsageError : public Error {
public:
    using Error::Error;
};

// No usable Vulkan device, or the caller's device lacks a version, feature or queue
// capability Penumbra needs; the message names it.
class DeviceError : public Error {
public:
    using Error::Error;
};

// A Vulkan call failed. The message names the call, the source location and the result.
class VulkanError : public Error {
public:
    VulkanError(const std::string& message, VkResult result) : Error(message), result_(result) {}
    VkResult result() const { return result_; }

private:
    VkResult result_;
};

}  // namespace penumbra

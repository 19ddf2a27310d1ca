#pragma once
// Penumbra reports every failure by throwing one of these (docs/library.md, "Errors").
// Each message is one line that names what went wrong and where it came from
// ("ShadowSystem::add_mesh: positions.stride: 0 must be at least 12 bytes"), so a caller
// can print it verbatim. Nothing is printed by the library itself.
#include <vulkan/vulkan_core.h>

#include <stdexcept>
#include <string>

namespace penumbra {

// Text made printable on one line: control characters (a newline in a file name, a NUL in
// a glTF string) become escapes (\n, \r, \t, \xHH). Every Error's message goes through
// it, so that text from a caller or a file cannot split a message into several lines.
inline std::string escape_control_characters(const std::string& text) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string result;
    result.reserve(text.size());
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '\n') {
            result += "\\n";
        } else if (c == '\r') {
            result += "\\r";
        } else if (c == '\t') {
            result += "\\t";
        } else if (byte < 0x20 || byte == 0x7f) {
            result += {'\\', 'x', kHex[byte >> 4], kHex[byte & 0xf]};
        } else {
            result += c;
        }
    }
    return result;
}

// The base of every error Penumbra throws.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(escape_control_characters(message)) {}
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

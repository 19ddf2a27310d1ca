#pragma once
// Error types that map to the CLI's exit codes. Anything a user can cause by
// bad input is an InputError (exit 2); a missing or unusable Vulkan device is
// a DeviceError (exit 3). Messages name the offending value and its origin
// ("scene.toml: camera.fov: ..."), so callers print them verbatim on one line.
#include <stdexcept>
#include <string>

namespace penumbra {

class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class DeviceError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace penumbra

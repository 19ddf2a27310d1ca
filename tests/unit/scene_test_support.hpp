#pragma once
// Helpers shared by the scene and glTF unit tests.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <string_view>

#include "penumbra/errors.hpp"
#include "penumbra/scene/loader.hpp"

namespace penumbra::testing {

inline std::filesystem::path test_data(const std::string& relative) {
    return std::filesystem::path(PENUMBRA_TEST_DATA_DIR) / relative;
}

// Runs `action`, which must throw InputError; returns the message ("" and a failure otherwise).
template <typename Action>
std::string input_error_message(Action&& action) {
    try {
        action();
    } catch (const InputError& error) {
        return error.what();
    } catch (const std::exception& error) {
        ADD_FAILURE() << "expected InputError, got another exception: " << error.what();
        return {};
    }
    ADD_FAILURE() << "expected InputError, nothing was thrown";
    return {};
}

inline Scene parse_scene_text(std::string_view text) {
    return parse_scene_toml(text, "scene.toml", test_data("scenes"));
}

// The InputError message of parsing `text` as "scene.toml".
inline std::string scene_error(std::string_view text) {
    return input_error_message([&] { parse_scene_text(text); });
}

}  // namespace penumbra::testing

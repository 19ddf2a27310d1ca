#pragma once
// Helpers shared by the scene and glTF unit tests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
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

// A fixture whose tests write files into `dir_`: an empty folder named after the test suite,
// the process (runs from several build folders at once stay apart) and the test, created
// before each test and removed after it.
class ScratchFolderTest : public ::testing::Test {
protected:
    void SetUp() override {
        const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() / ("penumbra_" + std::string(test->test_suite_name()) + "_" +
                                                         std::to_string(::getpid()) + "_" + test->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    // Writes `bytes` to `dir_ / name` and returns that path.
    std::filesystem::path write(const std::string& name, const std::string& bytes) const {
        std::ofstream(dir_ / name, std::ios::binary) << bytes;
        return dir_ / name;
    }

    std::filesystem::path dir_;
};

}  // namespace penumbra::testing

#pragma once
// Command-line tests: run the real `penumbra` binary (PENUMBRA_BINARY) in a fresh temporary
// folder per test, capture its exit code, stdout and stderr, and check the failure contract
// (exit code, one stderr line naming the problem, no output left behind).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace penumbra::testing {

struct RunResult {
    int exit_code = -1;
    std::string out;
    std::string err;
};

// The `penumbra` binary under test, for commands that run it more than once at a time.
const char* penumbra_binary();

// The whole file as text; empty when it cannot be read.
std::string read_text(const std::filesystem::path& path);

// A fixture whose tests run `penumbra` in `dir_`, a folder named after the test (and the
// process, so that runs from several build folders at once stay apart), created empty
// before each test and removed after it.
class CliTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;

    // Runs `penumbra <arguments>` in `dir_` through the shell; `environment` goes before the
    // binary (variable assignments, or a wrapper such as `env -u DISPLAY` or `xvfb-run`).
    RunResult run(const std::string& arguments, const std::string& environment = "") const;

    // Writes `text` to `dir_ / name` and returns that path.
    std::filesystem::path write_file(const std::string& name, const std::string& text) const;

    // The failure contract: exit code `code`, exactly one stderr line containing `needle`,
    // no `out.png` and no temporary (`.<name>.penumbra-tmp`) file left in `dir_`.
    void expect_failure(const RunResult& result, int code, const std::string& needle) const;

    std::filesystem::path dir_;
};

}  // namespace penumbra::testing

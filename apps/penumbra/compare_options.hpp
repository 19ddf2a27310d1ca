#pragma once
// The options of `penumbra compare` beyond the shared render options (docs/cli.md).
#include <CLI/CLI.hpp>

#include <string>

#include "compare/compare_job.hpp"

namespace penumbra::cli {

// `json` receives --json as typed (empty when absent).
void add_compare_options(CLI::App& compare, compare::CompareJob& job, std::string& json);

}  // namespace penumbra::cli

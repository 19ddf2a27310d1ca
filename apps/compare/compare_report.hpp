#pragma once
// The outputs of `penumbra compare`: a one-screen text summary, the JSON report
// (docs/QUALITY.md documents its schema) and the images, written into the output folder.
#include <filesystem>
#include <string>
#include <vector>

#include "compare/compare_job.hpp"

namespace penumbra::compare {

std::string format_compare_summary(const CompareResult& result);

std::string compare_json(const CompareResult& result);

// Writes the images and the JSON report (each file atomically); returns the paths written.
// Every file write_compare_outputs() writes, checked before the comparison runs (fails
// with an InputError naming the first that cannot be written).
void check_compare_outputs(const CompareJob& job);
std::vector<std::filesystem::path> write_compare_outputs(const CompareResult& result);

}  // namespace penumbra::compare

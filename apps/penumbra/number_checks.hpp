#pragma once
// Numbers on the command line: finite and within penumbra::kMaxNumberMagnitude, the range
// the 32-bit float math carries. CLI11 would read 1e39 as infinity, and a range check lets
// "nan" through (no comparison with it is true).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <string>

#include "penumbra/scene/scene.hpp"

namespace penumbra::cli {

inline bool sane_number(double value) { return std::isfinite(value) && std::abs(value) <= kMaxNumberMagnitude; }

// For every floating-point option: the text must read as a finite number within +-1e9.
inline const CLI::Validator& finite_number() {
    static const CLI::Validator validator(
        [](std::string& text) -> std::string {
            char* end = nullptr;
            const double value = std::strtod(text.c_str(), &end);
            if (end == text.c_str()) return {};  // not a number: CLI11's conversion says so
            if (!sane_number(value)) return "expected a finite number within +-1e9, got " + text;
            return {};
        },
        "");  // no word in --help: the option's own type and range say it
    return validator;
}

}  // namespace penumbra::cli

#pragma once
// Command-line parsing for `penumbra`: turns argv into a command for the library.
#include <cstdint>
#include <optional>
#include <string>
#include <variant>

#include "bench/bench_job.hpp"
#include "compare/compare_job.hpp"
#include "inspect.hpp"
#include "renderer/render_job.hpp"
#include "view/view_job.hpp"

namespace penumbra::cli {

struct DevicesCommand {};
struct RenderCommand {
    RenderJob job;
};
struct BenchCommand {
    bench::BenchJob job;
};
struct CompareCommand {
    compare::CompareJob job;
};
struct ViewCommand {
    view::ViewJob job;
};
struct InspectCommand {
    InspectJob job;
};
struct ExitNow {
    int code = 0;  // --help / --version printed, or a parse error already reported
};

using Command =
    std::variant<DevicesCommand, RenderCommand, BenchCommand, CompareCommand, ViewCommand, InspectCommand, ExitNow>;

// N of `shadow:N` (`--aov`, `--screenshot-aov`): a light index, 0 or more. Throws InputError
// naming `flag`; the scene checks the index later (prepare_render_job).
int32_t parse_light_index(const std::string& text, const std::string& flag);

// Parses arguments; usage errors are printed as one line on stderr (ExitNow{2}).
Command parse_command_line(int argc, char** argv);

}  // namespace penumbra::cli

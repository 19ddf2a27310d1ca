#pragma once
// Command-line parsing for `penumbra`: turns argv into a command for the library.
#include <optional>
#include <string>
#include <variant>

#include "renderer/render_job.hpp"

namespace penumbra::cli {

struct DevicesCommand {};
struct RenderCommand {
    RenderJob job;
};
struct ExitNow {
    int code = 0;  // --help / --version printed, or a parse error already reported
};

using Command = std::variant<DevicesCommand, RenderCommand, ExitNow>;

// Parses arguments; usage errors are printed as one line on stderr (ExitNow{2}).
Command parse_command_line(int argc, char** argv);

}  // namespace penumbra::cli

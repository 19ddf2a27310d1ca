// penumbra: the command-line client of the Penumbra library. main() parses arguments,
// calls the library and maps its errors to exit codes:
//   0 success, 1 internal/GPU failure, 2 bad input, 3 no usable Vulkan device,
//   4 the validation layer reported a message (--validate).
#include <cstdio>
#include <variant>

#include "bench/bench_report.hpp"
#include "cli.hpp"
#include "compare/compare_report.hpp"
#include "penumbra/device.hpp"
#include "penumbra/errors.hpp"
#include "progress_bar.hpp"
#include "view/view_job.hpp"

namespace {

int list_devices() {
    const auto devices = penumbra::list_physical_devices();
    std::printf("%-5s %-40s %-10s %-40s %s\n", "index", "name", "type", "driver", "api");
    for (const auto& device : devices) {
        std::printf("%-5u %-40s %-10s %-40s %s%s\n", device.index, device.name.c_str(), device.type.c_str(),
                    device.driver.c_str(), penumbra::vulkan_version_string(device.api_version).c_str(),
                    device.usable ? "" : " (unusable: needs Vulkan 1.3)");
    }
    return 0;
}

int render(const penumbra::RenderJob& job) {
    const penumbra::RenderSummary summary = penumbra::run_render_job(job);
    std::printf("penumbra: wrote %s (%ux%u, %s)\n", summary.output.c_str(), summary.width, summary.height,
                summary.device_name.c_str());
    return 0;
}

int bench(penumbra::bench::BenchJob job) {
    job.progress = penumbra::cli::terminal_progress_bar();
    const penumbra::bench::BenchResult result = penumbra::bench::run_bench_job(job);
    std::printf("%s", penumbra::bench::format_bench_table(result).c_str());
    if (job.json) penumbra::bench::write_bench_json(result, *job.json);
    return 0;
}

int compare(penumbra::compare::CompareJob job) {
    job.progress = penumbra::cli::terminal_trace_progress_bar();
    const penumbra::compare::CompareResult result = penumbra::compare::run_compare_job(job);
    std::printf("%s", penumbra::compare::format_compare_summary(result).c_str());
    const auto written = penumbra::compare::write_compare_outputs(result);
    std::printf("penumbra: wrote %zu files to %s\n", written.size(), job.out_dir.c_str());
    return 0;
}

int view(const penumbra::view::ViewJob& job) {
    const penumbra::view::ViewSummary summary = penumbra::view::run_view(job);
    if (summary.screenshot) std::printf("penumbra: wrote %s\n", summary.screenshot->c_str());
    std::printf("penumbra: presented %u frames (%s)\n", summary.frames, summary.device_name.c_str());
    return 0;
}

// One line whatever the message holds (penumbra::Error escapes its own; others may not).
int fail(int code, const char* message) {
    std::fprintf(stderr, "penumbra: %s\n", penumbra::escape_control_characters(message).c_str());
    return code;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const penumbra::cli::Command command = penumbra::cli::parse_command_line(argc, argv);
        if (const auto* exit_now = std::get_if<penumbra::cli::ExitNow>(&command)) return exit_now->code;
        if (std::holds_alternative<penumbra::cli::DevicesCommand>(command)) return list_devices();
        if (const auto* inspect_command = std::get_if<penumbra::cli::InspectCommand>(&command)) {
            std::printf("%s", penumbra::cli::inspect_scene(inspect_command->job).c_str());
            return 0;
        }
        if (const auto* bench_command = std::get_if<penumbra::cli::BenchCommand>(&command)) {
            return bench(bench_command->job);
        }
        if (const auto* compare_command = std::get_if<penumbra::cli::CompareCommand>(&command)) {
            return compare(compare_command->job);
        }
        if (const auto* view_command = std::get_if<penumbra::cli::ViewCommand>(&command)) {
            return view(view_command->job);
        }
        return render(std::get<penumbra::cli::RenderCommand>(command).job);
    } catch (const penumbra::InputError& error) {
        return fail(2, error.what());
    } catch (const penumbra::DeviceError& error) {
        return fail(3, error.what());
    } catch (const penumbra::ValidationFailure& error) {
        return fail(4, error.what());
    } catch (const penumbra::VulkanError& error) {
        return fail(1, error.what());
    } catch (const std::exception& error) {
        return fail(1, error.what());
    }
}

// penumbra: the command-line client of the Penumbra library. main() parses arguments,
// calls the library and maps its errors to exit codes:
//   0 success, 1 internal/GPU failure, 2 bad input, 3 no usable Vulkan device,
//   4 the validation layer reported a message (--validate).
#include <cstdio>
#include <variant>

#include "cli.hpp"
#include "core/errors.hpp"
#include "gpu/check.hpp"
#include "gpu/context.hpp"

namespace {

int list_devices() {
    const auto devices = penumbra::gpu::list_devices();
    std::printf("%-5s %-40s %-10s %-40s %s\n", "index", "name", "type", "driver", "api");
    for (const auto& device : devices) {
        std::printf("%-5u %-40s %-10s %-40s %s%s\n", device.index, device.name.c_str(),
                    penumbra::gpu::device_type_name(device.type), device.driver.c_str(),
                    penumbra::gpu::api_version_string(device.api_version).c_str(),
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

int fail(int code, const char* message) {
    std::fprintf(stderr, "penumbra: %s\n", message);
    return code;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const penumbra::cli::Command command = penumbra::cli::parse_command_line(argc, argv);
        if (const auto* exit_now = std::get_if<penumbra::cli::ExitNow>(&command)) return exit_now->code;
        if (std::holds_alternative<penumbra::cli::DevicesCommand>(command)) return list_devices();
        return render(std::get<penumbra::cli::RenderCommand>(command).job);
    } catch (const penumbra::InputError& error) {
        return fail(2, error.what());
    } catch (const penumbra::DeviceError& error) {
        return fail(3, error.what());
    } catch (const penumbra::ValidationFailure& error) {
        return fail(4, error.what());
    } catch (const penumbra::gpu::GpuError& error) {
        return fail(1, error.what());
    } catch (const std::exception& error) {
        return fail(1, error.what());
    }
}

#include "compare_options.hpp"

#include <cstdint>
#include <limits>

namespace penumbra::cli {

void add_compare_options(CLI::App& compare, compare::CompareJob& job, std::string& json) {
    compare.add_option("--rays", job.rays, "Soft-reference shadow rays per pixel over the light's disk (default 64)")
        ->check(CLI::Range(1u, compare::kMaxRays));
    compare
        .add_option("--light", job.light,
                    "Compare light N of the scene's [[lights]] (a spot or point light; default: the sun)")
        ->check(CLI::Range(0, std::numeric_limits<int32_t>::max()));
    compare
        .add_option("--edge-band", job.edge_band,
                    "Pixels around true shadow edges excluded from the *_outside_edges numbers (default 2)")
        ->check(CLI::Range(0u, compare::kMaxEdgeBand));
    compare
        .add_option("--stability-frames", job.stability_frames,
                    "Frames under small camera motions for the shimmer measurement (default 8; 1 = none)")
        ->check(CLI::Range(1u, compare::kMaxStabilityFrames));
    compare.add_option("--out-dir", job.out_dir, "Folder for the images and compare.json (default ./compare)");
    compare.add_option("--json", json, "Write the JSON report here instead of OUT_DIR/compare.json");
}

}  // namespace penumbra::cli

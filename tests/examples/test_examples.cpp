// The examples, built against the installed package by scripts/build_examples.sh, run
// with the validation layer (any message makes them fail) and must draw their scene's
// shadow: a 2 m box floating over a plane, its shadow the box projected along the sun
// (analytic_shadow.hpp), faces turned away from the sun dark, everything else lit.
// The forward example (shadows sampled in the application's fragment shader) and the
// deferred one (Penumbra's compute resolve from the application's depth) must agree.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <sys/wait.h>

#include "analytic_shadow.hpp"
#include "image/png_io.hpp"

namespace penumbra::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kWorkDir = PENUMBRA_EXAMPLES_WORK_DIR;
const glm::vec3 kSunDirection = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
constexpr float kPlaneHalfSize = 20.0f;
constexpr uint32_t kWidth = 640;
constexpr uint32_t kHeight = 360;
// Ground pixels closer than this to the analytic shadow's edge are not judged: the default
// PCF kernel and the normal offset blur the edge over a few texels (about 4 cm each here).
// Nor are box pixels this close to an edge of their face: there the kernel reaches over
// the edge onto the neighbouring face, which from the sun lies in front of a steeply lit
// face (the +Z face, lit at 75 degrees, darkens by up to 6% within 5 cm of its top edge).
constexpr float kEdgeBand = 0.25f;

Box box_at(const glm::vec3& centre) { return {centre - glm::vec3(1.0f), centre + glm::vec3(1.0f)}; }

// scripts/build_examples.sh builds penumbra_<name> in WORK/<name>.
fs::path binary_path(const std::string& binary) { return kWorkDir / binary.substr(binary.find('_') + 1) / binary; }

// Runs an example binary in `dir`; its exit code.
int run_example(const std::string& binary, const std::string& arguments, const fs::path& dir) {
    const fs::path path = binary_path(binary);
    if (!fs::exists(path)) return -1;
    const std::string command = "cd '" + dir.string() + "' && '" + path.string() + "' " + arguments + " > log.txt 2>&1";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = kWorkDir / "runs" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string log_of(const fs::path& dir) {
    std::ifstream file(dir / "log.txt");
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// What a pixel sees: the sky, the ground, or one face of the box (0-5: -X, +X, -Y, +Y, -Z, +Z).
enum class Surface { Sky, Ground, Face0, Face1, Face2, Face3, Face4, Face5 };

struct PixelTruth {
    Surface surface = Surface::Sky;
    glm::vec3 point{0.0f};
};

PixelTruth classify(const Box& box, const PinholeCamera& camera, uint32_t x, uint32_t y) {
    const PixelRay ray = pixel_ray(camera, kWidth, kHeight, x, y);
    const auto ground = intersect_ground(ray, kPlaneHalfSize);
    const auto box_hit = intersect_box(ray, box);
    if (box_hit && (!ground || *box_hit < *ground)) {
        const glm::vec3 point = ray.origin + ray.direction * *box_hit;
        const glm::vec3 centre = (box.min + box.max) * 0.5f;
        const glm::vec3 local = point - centre;
        const glm::vec3 a = glm::abs(local);
        const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
        const int face = 2 * axis + (local[axis] > 0.0f ? 1 : 0);
        return {static_cast<Surface>(static_cast<int>(Surface::Face0) + face), point};
    }
    if (ground) return {Surface::Ground, ray.origin + ray.direction * *ground};
    return {};
}

// Distance from a point on the box's surface to the nearest edge of the face it lies on.
float distance_to_face_edge(const Box& box, const glm::vec3& point) {
    const glm::vec3 to_min = point - box.min;
    const glm::vec3 to_max = box.max - point;
    // On its face one axis is at 0; the edges are where another axis reaches 0.
    float smallest_zero = 1e9f;
    float distances[3];
    int face_axis = 0;
    for (int axis = 0; axis < 3; ++axis) {
        distances[axis] = std::min(to_min[axis], to_max[axis]);
        if (distances[axis] < smallest_zero) {
            smallest_zero = distances[axis];
            face_axis = axis;
        }
    }
    float nearest = 1e9f;
    for (int axis = 0; axis < 3; ++axis) {
        if (axis != face_axis) nearest = std::min(nearest, distances[axis]);
    }
    return nearest;
}

bool faces_sun(Surface face) {
    const int index = static_cast<int>(face) - static_cast<int>(Surface::Face0);
    glm::vec3 normal(0.0f);
    normal[index / 2] = index % 2 ? 1.0f : -1.0f;
    return glm::dot(normal, -kSunDirection) > 0.0f;
}

struct ImageCheck {
    size_t judged = 0;
    size_t wrong = 0;
    size_t shadowed_ground = 0;  // judged ground pixels inside the analytic shadow
    size_t dark_faces = 0;       // judged box pixels on faces turned away from the sun
    double iou = 0.0;            // rendered (< half) vs analytic shadow over all ground pixels
    std::string first_wrong;
};

// Compares a visibility image (16-bit, 65535 lit) seen by `camera` with the analytic answer
// for the box at `centre`. Pixels whose 4-neighbours see another surface (silhouettes) are
// not judged.
ImageCheck check_image(const PngImage& image, const glm::vec3& centre, const PinholeCamera& camera) {
    const Box box = box_at(centre);
    const auto polygon = shadow_polygon(box, kSunDirection);
    ImageCheck check;
    size_t intersection = 0, union_count = 0;
    for (uint32_t y = 1; y + 1 < kHeight; ++y) {
        for (uint32_t x = 1; x + 1 < kWidth; ++x) {
            const PixelTruth truth = classify(box, camera, x, y);
            const uint16_t value = image.samples[size_t{y} * kWidth + x];
            if (truth.surface == Surface::Ground) {
                const glm::vec2 ground(truth.point.x, truth.point.z);
                const bool shadowed = inside_convex_polygon(polygon, ground);
                intersection += shadowed && value < 32768;
                union_count += shadowed || value < 32768;
            }
            const auto differs = [&](uint32_t nx, uint32_t ny) {
                return classify(box, camera, nx, ny).surface != truth.surface;
            };
            const bool silhouette = differs(x - 1, y) || differs(x + 1, y) || differs(x, y - 1) || differs(x, y + 1);
            if (silhouette) continue;
            uint16_t expected = 65535;
            if (truth.surface == Surface::Ground) {
                const glm::vec2 ground(truth.point.x, truth.point.z);
                if (distance_to_polygon_edge(polygon, ground) < kEdgeBand) continue;
                if (inside_convex_polygon(polygon, ground)) {
                    expected = 0;
                    ++check.shadowed_ground;
                }
            } else if (truth.surface != Surface::Sky) {
                if (distance_to_face_edge(box, truth.point) < kEdgeBand) continue;
                if (!faces_sun(truth.surface)) {
                    expected = 0;
                    ++check.dark_faces;
                }
            }
            ++check.judged;
            if (value != expected) {
                if (check.wrong++ == 0) {
                    check.first_wrong = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is " +
                                        std::to_string(value) + ", expected " + std::to_string(expected);
                }
            }
        }
    }
    check.iou = union_count ? static_cast<double>(intersection) / static_cast<double>(union_count) : 0.0;
    return check;
}

void expect_matches_scene(const fs::path& png, const glm::vec3& box_centre, size_t min_dark_faces,
                          const PinholeCamera& camera = {}) {
    const PngImage image = read_png(png);
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);
    ASSERT_EQ(image.channels, 1u);
    ASSERT_EQ(image.bit_depth, 16u);
    const ImageCheck check = check_image(image, box_centre, camera);
    EXPECT_GT(check.judged, 150000u);
    EXPECT_GT(check.shadowed_ground, 300u) << "the visible part of the shadow";
    EXPECT_GE(check.dark_faces, min_dark_faces);
    EXPECT_EQ(check.wrong, 0u) << png << ": " << check.first_wrong;
    EXPECT_GE(check.iou, 0.97) << png << ": the shadow differs from the analytic projection";
}

::testing::AssertionResult built(const std::string& binary) {
    if (fs::exists(binary_path(binary))) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << binary
                                         << " was not built (the examples_build test, scripts/build_examples.sh)";
}

TEST(Examples, MinimalForwardShadowMatchesTheAnalyticShadow) {
    ASSERT_TRUE(built("penumbra_minimal"));
    const fs::path dir = fresh_dir("minimal");
    ASSERT_EQ(run_example("penumbra_minimal", "out.png --validate", dir), 0) << log_of(dir);
    expect_matches_scene(dir / "out.png", {0.0f, 3.0f, 0.0f}, 0);
}

TEST(Examples, DeferredShadowFollowsTheMovedBox) {
    ASSERT_TRUE(built("penumbra_deferred"));
    const fs::path dir = fresh_dir("deferred");
    ASSERT_EQ(run_example("penumbra_deferred", "first.png second.png --validate", dir), 0) << log_of(dir);
    expect_matches_scene(dir / "first.png", {0.0f, 3.0f, 0.0f}, 0);
    // Moved to (3, 3, -2) the box shows its -X face, which is turned away from the sun.
    expect_matches_scene(dir / "second.png", {3.0f, 3.0f, -2.0f}, 100);
}

// The engine example: two views of one ShadowSystem with TAA-jittered projections, a live
// filter change from PCF to PCSS, view 0 shaded by the HLSL pixel shader, view 1 resolved
// into the application's own image (on an async compute queue where the device has a
// compute-only family): each view's last frame is its camera's analytic shadow.
TEST(Examples, EngineViewsMatchTheAnalyticShadow) {
    ASSERT_TRUE(built("penumbra_engine"));
    const fs::path dir = fresh_dir("engine");
    ASSERT_EQ(run_example("penumbra_engine", "view0.png view1.png --validate", dir), 0) << log_of(dir);
    const std::string log = log_of(dir);
    EXPECT_NE(log.find("filter pcf -> pcss"), std::string::npos) << log;
    EXPECT_NE(log.find("the forward pipeline rebuilt"), std::string::npos) << log;
    EXPECT_NE(log.find("visibility_view1"), std::string::npos) << "view 1's resolve is timed: " << log;
    expect_matches_scene(dir / "view0.png", {0.0f, 3.0f, 0.0f}, 0);
    PinholeCamera second;
    second.eye = {-9.0f, 7.0f, 6.0f};
    // From there the box shows its -X face, which is turned away from the sun.
    expect_matches_scene(dir / "view1.png", {0.0f, 3.0f, 0.0f}, 1000, second);
}

// The Vulkan helper component, installed and used by a client of its own
// (tests/examples/gpu_component): its buffer, one-off commands and host barrier work on
// the device of a VulkanContext, validation-clean.
TEST(Examples, GpuComponentWorksFromTheInstalledPackage) {
    ASSERT_TRUE(built("penumbra_gpu_component"));
    const fs::path dir = fresh_dir("gpu_component");
    EXPECT_EQ(run_example("penumbra_gpu_component", "", dir), 0) << log_of(dir);
    EXPECT_NE(log_of(dir).find("0 of 1024 words wrong"), std::string::npos) << log_of(dir);
}

// Forward (interpolated positions and normals) and deferred (positions rebuilt from depth,
// normals from its derivatives) sample the same maps: away from silhouettes and shadow
// edges they must give the same visibility, and the whole images must be nearly equal.
TEST(Examples, ForwardAndDeferredAgree) {
    ASSERT_TRUE(built("penumbra_minimal"));
    ASSERT_TRUE(built("penumbra_deferred"));
    const fs::path dir = fresh_dir("agree");
    ASSERT_EQ(run_example("penumbra_minimal", "forward.png", dir), 0) << log_of(dir);
    ASSERT_EQ(run_example("penumbra_deferred", "deferred.png moved.png", dir), 0) << log_of(dir);
    const PngImage forward = read_png(dir / "forward.png");
    const PngImage deferred = read_png(dir / "deferred.png");
    ASSERT_EQ(forward.samples.size(), deferred.samples.size());
    size_t differing = 0;
    double total_difference = 0.0;
    for (size_t i = 0; i < forward.samples.size(); ++i) {
        const double difference = std::abs(double(forward.samples[i]) - double(deferred.samples[i])) / 65535.0;
        total_difference += difference;
        differing += difference > 0.1;
    }
    const double pixels = static_cast<double>(forward.samples.size());
    EXPECT_LT(static_cast<double>(differing) / pixels, 0.002) << differing << " pixels differ by more than 0.1";
    EXPECT_LT(total_difference / pixels, 0.001);
}

// The minimal example's pixel shader in HLSL (penumbra/shadow.hlsl and
// penumbra/shadow_fragment.hlsl, with derivatives) draws the GLSL shader's image and is as
// clean under the validation layer (the shadow set's textures and samplers share their
// combined-image-sampler bindings). The two front ends round a few float operations
// differently: a handful of penumbra pixels differ by at most 16 / 65535 on lavapipe; a
// wrong texel, tap or read would differ by far more than the bound.
TEST(Examples, MinimalHlslPixelShaderDrawsTheGlslImage) {
    ASSERT_TRUE(built("penumbra_minimal"));
    const fs::path dir = fresh_dir("hlsl");
    ASSERT_EQ(run_example("penumbra_minimal", "glsl.png --validate", dir), 0) << log_of(dir);
    ASSERT_EQ(run_example("penumbra_minimal", "hlsl.png --validate --hlsl", dir), 0) << log_of(dir);
    const PngImage glsl = read_png(dir / "glsl.png");
    const PngImage hlsl = read_png(dir / "hlsl.png");
    ASSERT_EQ(glsl.samples.size(), hlsl.samples.size());
    size_t differing = 0;
    int largest = 0;
    size_t shadowed = 0;
    for (size_t i = 0; i < glsl.samples.size(); ++i) {
        const int difference = std::abs(int(glsl.samples[i]) - int(hlsl.samples[i]));
        largest = std::max(largest, difference);
        differing += difference != 0;
        shadowed += glsl.samples[i] < 32768;
    }
    EXPECT_LE(largest, 65);                            // 1 / 1000
    EXPECT_LT(differing, glsl.samples.size() / 1000);  // the penumbrae's few pixels
    EXPECT_GT(shadowed, 1000u);                        // a comparison of images with shadows in them
    expect_matches_scene(dir / "hlsl.png", {0.0f, 3.0f, 0.0f}, 0);
}

}  // namespace
}  // namespace penumbra::testing

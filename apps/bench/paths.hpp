#pragma once
// Deterministic camera and light paths for benchmarks: pure functions of the scene's
// own camera (or sun) and a path parameter t in [0, 1), so that every run of a
// benchmark renders exactly the same frames.
#include "penumbra/scene/scene.hpp"

namespace penumbra::bench {

enum class CameraPath {
    Orbit,       // one turn around the camera's target at the camera's distance and height
    Flythrough,  // straight ahead over the target and as far beyond it, weaving gently
};

enum class LightPath {
    Fixed,   // the scene's sun
    Rotate,  // the sun turns once around the vertical, keeping its elevation
};

Camera camera_on_path(CameraPath path, const Camera& start, float t);

// `start` is the direction the sunlight travels (need not be normalised).
glm::vec3 sun_on_path(LightPath path, const glm::vec3& start, float t);

const char* camera_path_name(CameraPath path);
const char* light_path_name(LightPath path);

}  // namespace penumbra::bench

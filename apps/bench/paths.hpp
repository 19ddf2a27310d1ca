#pragma once
// Deterministic camera and light paths for benchmarks: pure functions of the scene's
// own camera (or sun) and a path parameter t in [0, 1), so that every run of a
// benchmark renders exactly the same frames.
#include <cstdint>

#include "penumbra/scene/scene.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::bench {

enum class CameraPath {
    Orbit,       // one turn around the camera's target at the camera's distance and height
    Flythrough,  // straight ahead over the target and as far beyond it, weaving gently
    Walk,        // straight ahead at a walker's 1.4 m/s at 60 frames a second, looking ahead
    Still,       // the scene's camera, every frame
};
inline constexpr ChoiceName<CameraPath> kCameraPathChoices[] = {{"orbit", CameraPath::Orbit},
                                                                {"flythrough", CameraPath::Flythrough},
                                                                {"walk", CameraPath::Walk},
                                                                {"still", CameraPath::Still}};

enum class LightPath {
    Fixed,   // the scene's sun
    Rotate,  // the sun turns once around the vertical, keeping its elevation
};
inline constexpr ChoiceName<LightPath> kLightPathChoices[] = {{"fixed", LightPath::Fixed},
                                                              {"rotate", LightPath::Rotate}};

// The camera at path parameter t of a run of `frames` frames (the walk's speed is per frame).
Camera camera_on_path(CameraPath path, const Camera& start, float t, uint32_t frames);

// `start` is the direction the sunlight travels (need not be normalised).
glm::vec3 sun_on_path(LightPath path, const glm::vec3& start, float t);

const char* camera_path_name(CameraPath path);
const char* light_path_name(LightPath path);

}  // namespace penumbra::bench

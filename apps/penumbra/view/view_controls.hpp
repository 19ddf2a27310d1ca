#pragma once
// Camera and sun controls of the viewer: pure math on penumbra::Camera and a sun
// direction, no window or Vulkan, so that they can be unit tested.
//
// Free-fly: move the eye (and target) along the camera's axes, turn about the eye.
// Orbit: turn the eye about the target, zoom changes the eye-target distance.
// Both keep the camera's up vector as the world's up and never let the view direction
// come within 1 degree of it.
#include <glm/glm.hpp>
#include "penumbra/scene/scene.hpp"

namespace penumbra::view {

enum class CameraMode { Fly, Orbit };

class CameraController {
public:
    explicit CameraController(const Camera& initial);

    const Camera& camera() const { return camera_; }
    void set_camera(const Camera& camera) { camera_ = camera; }
    void reset() { camera_ = initial_; }
    CameraMode mode() const { return mode_; }
    void set_mode(CameraMode mode) { mode_ = mode; }

    // Metres along the camera's right, the world up and the view direction.
    void move(const glm::vec3& right_up_forward);
    // Degrees: yaw about the world up (positive turns left), pitch (positive looks up).
    void turn(float yaw_degrees, float pitch_degrees);
    // Orbit: multiplies the eye-target distance (clamped to >= 0.05 m); fly: no-op.
    void zoom(float factor);

    float speed = 5.0f;  // metres per second for held movement keys

private:
    Camera initial_;
    Camera camera_;
    CameraMode mode_ = CameraMode::Fly;
};

// A sun direction as angles (world up = +Y): azimuth about +Y from +Z toward +X, and
// elevation above the horizon, both of the direction *toward* the sun, in degrees.
struct SunAngles {
    float azimuth_degrees = 0.0f;
    float elevation_degrees = 45.0f;
};

SunAngles sun_angles(const glm::vec3& travel_direction);
glm::vec3 sun_travel_direction(const SunAngles& angles);  // normalised

}  // namespace penumbra::view

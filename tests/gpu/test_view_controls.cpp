// The viewer's pure parts: camera controls, sun angles and the script parser.
#include <gtest/gtest.h>

#include "penumbra/errors.hpp"
#include "script.hpp"
#include "view_controls.hpp"

namespace penumbra::view {
namespace {

Camera test_camera() {
    Camera camera;
    camera.eye = {0.0f, 2.0f, 10.0f};
    camera.target = {0.0f, 2.0f, 0.0f};
    return camera;
}

void expect_near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-4f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(CameraController, FlyMovesAlongCameraAxes) {
    CameraController controller(test_camera());
    controller.move({1.0f, 0.5f, 2.0f});  // right, up, forward (forward is -Z here)
    expect_near(controller.camera().eye, {1.0f, 2.5f, 8.0f});
    expect_near(controller.camera().target, {1.0f, 2.5f, -2.0f});
}

TEST(CameraController, FlyTurnKeepsEyeAndDistance) {
    CameraController controller(test_camera());
    controller.turn(90.0f, 0.0f);  // yaw left: from -Z to -X
    expect_near(controller.camera().eye, {0.0f, 2.0f, 10.0f});
    expect_near(controller.camera().target, {-10.0f, 2.0f, 10.0f});
}

TEST(CameraController, PitchStopsShortOfStraightUp) {
    CameraController controller(test_camera());
    controller.turn(0.0f, 120.0f);
    const glm::vec3 forward = glm::normalize(controller.camera().target - controller.camera().eye);
    EXPECT_LT(glm::dot(forward, glm::vec3(0, 1, 0)), std::cos(glm::radians(0.9f)));
    EXPECT_GT(glm::dot(forward, glm::vec3(0, 1, 0)), std::cos(glm::radians(1.1f)));
}

TEST(CameraController, OrbitTurnsAboutTheTargetAndZooms) {
    CameraController controller(test_camera());
    controller.set_mode(CameraMode::Orbit);
    controller.turn(90.0f, 0.0f);
    expect_near(controller.camera().target, {0.0f, 2.0f, 0.0f});
    EXPECT_NEAR(glm::length(controller.camera().eye - controller.camera().target), 10.0f, 1e-4f);
    controller.zoom(0.5f);
    EXPECT_NEAR(glm::length(controller.camera().eye - controller.camera().target), 5.0f, 1e-4f);
    controller.reset();
    expect_near(controller.camera().eye, test_camera().eye);
}

TEST(SunAngles, RoundTripThroughDirection) {
    const glm::vec3 direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
    expect_near(sun_travel_direction(sun_angles(direction)), direction);
    const SunAngles overhead = sun_angles({0.0f, -1.0f, 0.0f});
    EXPECT_NEAR(overhead.elevation_degrees, 90.0f, 1e-3f);
    // Azimuth 90 degrees puts the sun toward +X, so its light travels toward -X.
    expect_near(sun_travel_direction({90.0f, 0.0f}), {-1.0f, 0.0f, 0.0f});
}

TEST(Script, ParsesEveryAction) {
    const auto actions = parse_script(
        "# comment\n"
        "0 set shadow.cascades = 2   # trailing comment\n"
        "0 set camera.eye = [1, 2, 3]\n"
        "1 move 1 0 -2\n2 turn 10 -5\n2 mode orbit\n3 zoom 0.5\n4 sun 120 35\n4 animate-sun 30\n"
        "5 resize 640 480\n5 reset-camera\n6 ui hide\n7 screenshot a.png\n7 save-settings b.toml\n\n9 quit\n",
        "s.txt");
    ASSERT_EQ(actions.size(), 14u);
    const auto& set = std::get<action::Set>(actions[0].action);
    EXPECT_EQ(*set.overrides.settings.find("cascades"), penumbra::SettingValue(int64_t{2}));
    EXPECT_EQ(actions[0].origin, "s.txt:2");
    EXPECT_EQ(std::get<action::Set>(actions[1].action).overrides.eye, glm::vec3(1, 2, 3));
    EXPECT_EQ(std::get<action::Move>(actions[2].action).right_up_forward, glm::vec3(1, 0, -2));
    EXPECT_EQ(std::get<action::Mode>(actions[4].action).mode, CameraMode::Orbit);
    EXPECT_EQ(std::get<action::Resize>(actions[8].action).width, 640u);
    EXPECT_FALSE(std::get<action::Ui>(actions[10].action).show);
    EXPECT_EQ(std::get<action::Screenshot>(actions[11].action).file, "a.png");
    EXPECT_EQ(actions[13].frame, 9u);
}

TEST(Script, ErrorsNameTheLine) {
    auto expect_error = [](const std::string& text, const std::string& needle) {
        try {
            parse_script(text, "s.txt");
            ADD_FAILURE() << "no error for: " << text;
        } catch (const InputError& error) {
            EXPECT_NE(std::string(error.what()).find(needle), std::string::npos) << error.what();
        }
    };
    expect_error("0 jump\n", "s.txt:1: unknown action \"jump\"");
    expect_error("2 quit\n1 quit\n", "s.txt:2: frames must not decrease");
    expect_error("x quit\n", "s.txt:1: expected a frame number");
    expect_error("0 move 1 2\n", "s.txt:1: expected move RIGHT UP FORWARD");
    expect_error("0 move 1 2 z\n", "\"z\" is not a number");
    expect_error("0 set shadow.no_such_key = 1\n", "s.txt:1: shadow.no_such_key: unknown key");
    expect_error("0 set shadow.cascades = \"two\"\n", "expected an integer");
    expect_error("0 resize 0 10\n", "not a size in pixels");
    expect_error("0 mode walk\n", "unknown camera mode");
}

}  // namespace
}  // namespace penumbra::view

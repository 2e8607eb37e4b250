// fluid::gl camera: fitting a rectangle, pixel <-> world round trips, aspect handling.
#include <catch2/catch.hpp>
#include <fluid/gl/camera.h>

using fluid::gl::Camera;

TEST_CASE("Camera::fit shows the rectangle whole and centred", "[gl][camera]") {
    // A 0.6 m x 0.8 m tank in a 960 x 540 target: the height is the tighter axis.
    const Camera camera = Camera::fit({0.0f, 0.0f}, {0.6f, 0.8f}, {960, 540}, 0.05f);
    CHECK(camera.center.x == Approx(0.3f));
    CHECK(camera.center.y == Approx(0.4f));
    // 540 px over 0.8 m x (1 + 2 x 0.05).
    CHECK(camera.pixelsPerMetre == Approx(540.0f / 0.88f));
    const glm::vec2 lo = camera.worldMin(), hi = camera.worldMax();
    CHECK(lo.x < 0.0f);
    CHECK(lo.y == Approx(-0.04f).margin(1e-5));
    CHECK(hi.x > 0.6f);
    CHECK(hi.y == Approx(0.84f).margin(1e-5));
    // The tank's corners land inside the target, the top-left corner towards pixel (0, 0).
    const glm::vec2 topLeft = camera.worldToPixel({0.0f, 0.8f});
    const glm::vec2 bottomRight = camera.worldToPixel({0.6f, 0.0f});
    CHECK(topLeft.x > 0.0f);
    CHECK(topLeft.y == Approx(540.0f * 0.04f / 0.88f).margin(1e-3));
    CHECK(bottomRight.x < 960.0f);
    CHECK(bottomRight.y == Approx(540.0f - 540.0f * 0.04f / 0.88f).margin(1e-3));
    // Centred horizontally: equal room left and right.
    CHECK(topLeft.x == Approx(960.0f - bottomRight.x).margin(1e-3));
}

TEST_CASE("Camera::fit picks the tighter axis for wide and tall rectangles", "[gl][camera]") {
    // Wide rectangle in a tall target: the width decides.
    const Camera wide = Camera::fit({-2.0f, 0.0f}, {2.0f, 0.5f}, {300, 800}, 0.0f);
    CHECK(wide.pixelsPerMetre == Approx(300.0f / 4.0f));
    CHECK(wide.worldMin().x == Approx(-2.0f));
    CHECK(wide.worldMax().x == Approx(2.0f));
    CHECK(wide.worldMax().y - wide.worldMin().y == Approx(800.0f / 75.0f));
    // Tall rectangle in a wide target: the height decides.
    const Camera tall = Camera::fit({0.0f, 0.0f}, {0.1f, 1.0f}, {1280, 720}, 0.0f);
    CHECK(tall.pixelsPerMetre == Approx(720.0f));
    // Reversed corners describe the same rectangle.
    const Camera reversed = Camera::fit({0.1f, 1.0f}, {0.0f, 0.0f}, {1280, 720}, 0.0f);
    CHECK(reversed.pixelsPerMetre == Approx(tall.pixelsPerMetre));
    CHECK(reversed.center.x == Approx(tall.center.x));
}

TEST_CASE("Camera::fit widens a degenerate rectangle and clamps bad arguments", "[gl][camera]") {
    const Camera point = Camera::fit({1.0f, 2.0f}, {1.0f, 2.0f}, {100, 100}, 0.0f);
    CHECK(point.pixelsPerMetre == Approx(100.0f / 1e-3f));
    CHECK(point.center.x == Approx(1.0f));
    const Camera bad = Camera::fit({0.0f, 0.0f}, {1.0f, 1.0f}, {0, -5}, -1.0f);
    CHECK(bad.viewport.x == 1);
    CHECK(bad.viewport.y == 1);
    CHECK(bad.pixelsPerMetre == Approx(1.0f));
}

TEST_CASE("Camera pixel <-> world round trip, y points down in pixels", "[gl][camera]") {
    Camera camera;
    camera.center = {0.25f, -0.5f};
    camera.pixelsPerMetre = 373.0f;
    camera.viewport = {640, 360};
    // The centre maps to the middle of the target.
    const glm::vec2 middle = camera.worldToPixel(camera.center);
    CHECK(middle.x == Approx(320.0f));
    CHECK(middle.y == Approx(180.0f));
    // Up in the world is up on screen: a smaller pixel y.
    CHECK(camera.worldToPixel(camera.center + glm::vec2(0.0f, 0.1f)).y < 180.0f);
    CHECK(camera.worldToPixel(camera.center + glm::vec2(0.1f, 0.0f)).x > 320.0f);
    for (const glm::vec2 world :
         {glm::vec2(0.0f, 0.0f), glm::vec2(1.3f, -0.7f), glm::vec2(-0.4f, 0.9f)}) {
        const glm::vec2 back = camera.pixelToWorld(camera.worldToPixel(world));
        CHECK(back.x == Approx(world.x).margin(1e-5));
        CHECK(back.y == Approx(world.y).margin(1e-5));
    }
    // The pixel corners are the world rectangle's corners.
    const glm::vec2 topLeft = camera.pixelToWorld({0.0f, 0.0f});
    CHECK(topLeft.x == Approx(camera.worldMin().x));
    CHECK(topLeft.y == Approx(camera.worldMax().y));
    const glm::vec2 bottomRight = camera.pixelToWorld({640.0f, 360.0f});
    CHECK(bottomRight.x == Approx(camera.worldMax().x));
    CHECK(bottomRight.y == Approx(camera.worldMin().y));
}

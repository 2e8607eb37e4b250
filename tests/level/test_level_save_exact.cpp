// fluid tests — level saves of levels with Box2D bodies continue bit-identically: every shipped
// level with bodies, saved at several frames and played on beside the uninterrupted run, with 1
// and 2 worker threads (Box2D's contacts, broad phase, sweeps and joint impulses are saved:
// docs/box2d.md, "Saving").
#include <catch2/catch.hpp>

#include "level_support.h"

#include <fluid/level.h>

#include <box2d/box2d.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

// A save restored on `workers` workers.
Level restore(const std::string& bytes, uint32_t workers) {
    LevelOptions options;
    options.workerCount = workers;
    return test::restore(bytes, options);
}

// Every body's pose and velocities (Box2D's list order) and every particle's position and
// velocity (slot order), as bits.
std::vector<float> levelBits(const Level& level) {
    std::vector<float> out;
    for (const b2Body* b = level.physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
        const b2Vec2 p = b->GetPosition(), c = b->GetWorldCenter(), v = b->GetLinearVelocity();
        out.insert(out.end(), {p.x, p.y, c.x, c.y, b->GetAngle(), v.x, v.y, b->GetAngularVelocity(),
                               b->IsAwake() ? 1.0f : 0.0f});
    }
    const World& w = level.world;
    for (const auto span : {w.positionX(), w.positionY(), w.velocityX(), w.velocityY()}) {
        out.insert(out.end(), span.begin(), span.end());
    }
    return out;
}

// Plays `name` with `workers` threads; at each frame of `saveAt` saves it, restores the save and
// plays the copy `after` frames beside the original: both must end in the same state, bit for
// bit, and write the same save.
void continuesExactly(const std::string& name, uint32_t workers, const std::vector<int>& saveAt,
                      int after) {
    INFO(name << " with " << workers << " worker(s)");
    LevelOptions options;
    options.workerCount = workers;
    Level level = parseLevel(readLevel(name.c_str()), name, builtins(), options);
    REQUIRE(level.physics != nullptr);
    int frame = 0;
    for (const int k : saveAt) {
        for (; frame < k; ++frame) {
            level.step();
        }
        INFO("saved at frame " << k);
        Level copy = restore(saveOf(level), workers);
        for (int f = 0; f < after; ++f, ++frame) {
            level.step();
            copy.step();
        }
        CHECK(levelBits(copy) == levelBits(level));
        CHECK(saveOf(copy) == saveOf(level));
    }
}

// The shipped levels that declare Box2D bodies.
std::vector<std::string> levelsWithBodies() {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(FLUID_LEVELS_DIR)) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() == ".json" &&
            readLevel(name.c_str()).find("\"bodies\"") != std::string::npos) {
            names.push_back(name);
        }
    }
    std::sort(names.begin(), names.end());
    return names;
}

} // namespace

TEST_CASE("every shipped level with bodies continues bit-identically from a save at frame 20",
          "[save]") {
    const std::vector<std::string> names = levelsWithBodies();
    REQUIRE(names.size() >= 4); // crates, cup_and_planks, paddle_wheel, sticky_plank
    for (const std::string& name : names) {
        for (const uint32_t workers : {1u, 2u}) {
            continuesExactly(name, workers, {20}, 20);
        }
    }
}

TEST_CASE("paddle_wheel, sticky_plank and cup_and_planks saved at frames 120 and 300 continue "
          "bit-identically",
          "[save][slow]") {
    for (const char* name : {"paddle_wheel.json", "sticky_plank.json", "cup_and_planks.json"}) {
        for (const uint32_t workers : {1u, 2u}) {
            continuesExactly(name, workers, {120, 300}, 30);
        }
    }
}

TEST_CASE("crates.json saved at frames 120 and 300 continues bit-identically", "[save][slow]") {
    for (const uint32_t workers : {1u, 2u}) {
        continuesExactly("crates.json", workers, {120, 300}, 30);
    }
}

// fluid tests — level saves of coupled levels continue bit-identically: every shipped level with
// Box2D bodies, saved at several frames and played on, with 1 and 2 worker threads.
#include <catch2/catch.hpp>

#include "level_support.h"

#include <fluid/level.h>
#include <fluid/box2d/physics_save.h>

#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

std::string saveOf(const Level& level) {
    std::ostringstream out;
    level.save(out);
    return out.str();
}

Level restore(const std::string& bytes, uint32_t workers) {
    std::istringstream in(bytes);
    LevelOptions options;
    options.workerCount = workers;
    return readLevelSave(in, "s.sav", builtins(), options);
}

// The largest distance between the same body (Box2D's list order) or particle (slot order) of
// two levels (unit: m); infinite when the counts differ.
double worstDistance(const Level& a, const Level& b) {
    double worst = 0.0;
    const b2Body* x = a.physics->GetBodyList();
    const b2Body* y = b.physics->GetBodyList();
    for (; x != nullptr && y != nullptr; x = x->GetNext(), y = y->GetNext()) {
        worst = std::max(worst, double((x->GetPosition() - y->GetPosition()).Length()));
        worst = std::max(worst, double((x->GetWorldCenter() - y->GetWorldCenter()).Length()));
        worst = std::max(worst, double(std::abs(x->GetAngle() - y->GetAngle())));
    }
    std::printf("bodies %.3g ", worst);
    if (x != nullptr || y != nullptr || a.world.particleCount() != b.world.particleCount()) {
        return INFINITY;
    }
    const auto ax = a.world.positionX(), ay = a.world.positionY();
    const auto bx = b.world.positionX(), by = b.world.positionY();
    for (std::size_t i = 0; i < ax.size(); ++i) {
        worst = std::max(worst, std::hypot(double(ax[i]) - bx[i], double(ay[i]) - by[i]));
    }
    return worst;
}

} // namespace

TEST_CASE("measure: coupled level saves", "[.measure]") {
    for (const char* name : {"paddle_wheel.json", "cup_and_planks.json", "sticky_plank.json",
                             "crates.json"}) {
        for (const uint32_t workers : {1u, 2u}) {
            LevelOptions options;
            options.workerCount = workers;
            Level level = parseLevel(readLevel(name), name, builtins(), options);
            const std::vector<int> at{30, 120, 300};
            const int after = 60;
            std::vector<Level> restored;
            int frame = 0;
            std::vector<double> worst;
            for (const int k : at) {
                for (; frame < k; ++frame) {
                    level.step();
                    for (Level& r : restored) {
                        r.step();
                    }
                }
                restored.push_back(restore(saveOf(level), workers));
            }
            for (; frame < at.back() + after; ++frame) {
                level.step();
                for (Level& r : restored) {
                    r.step();
                }
            }
            for (std::size_t s = 0; s < at.size(); ++s) {
                std::printf("[measure] %s workers %u saved at %d, frame %d: %.3g m\n", name,
                            workers, at[s], frame, worstDistance(level, restored[s]));
            }
        }
    }
}

TEST_CASE("debug: round trip", "[.debug]") {
    Level level = parseLevel(readLevel("paddle_wheel.json"), "paddle_wheel.json", builtins());
    for (int f = 0; f < 30; ++f) level.step();
    const std::string a = saveOf(level);
    Level r = restore(a, 1);
    const std::string b = saveOf(r);
    std::printf("sizes %zu %zu\n", a.size(), b.size());
    for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
        if (a[k] != b[k]) { std::printf("first diff at %zu\n", k); break; }
    }
    {
        std::ostringstream pa, pb;
        box2d::savePhysics(*level.physics, pa);
        box2d::savePhysics(*r.physics, pb);
        const std::string sa = pa.str(), sb = pb.str();
        std::printf("physics sizes %zu %zu\n", sa.size(), sb.size());
        for (std::size_t k = 0; k < std::min(sa.size(), sb.size()); ++k) {
            if (sa[k] != sb[k]) { std::printf("physics first diff at %zu\n", k); break; }
        }
    }
    level.step(); r.step();
    const b2Body* x = level.physics->GetBodyList();
    const b2Body* y = r.physics->GetBodyList();
    for (; x && y; x = x->GetNext(), y = y->GetNext())
        std::printf("%.9g %.9g | %.9g %.9g  awake %d %d\n", x->GetAngle(), y->GetAngle(), x->GetAngularVelocity(), y->GetAngularVelocity(), x->IsAwake(), y->IsAwake());
}

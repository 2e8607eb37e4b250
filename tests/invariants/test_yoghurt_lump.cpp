// A lump of yoghurt in water (issue 67): it sinks and rests as one piece.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

// Sizes of the connected pieces of `material`'s particles, largest first: two particles are in
// one piece when a chain of them links them, each link shorter than `link` (unit: m).
std::vector<uint32_t> lumpPieces(const World& world, MaterialId material, float link) {
    const auto px = world.positionX(), py = world.positionY();
    const auto mat = world.materialIndex();
    std::vector<uint32_t> ids;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (mat[i] == material.index) {
            ids.push_back(i);
        }
    }
    std::vector<uint32_t> parent(ids.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto root = [&](uint32_t a) {
        while (parent[a] != a) {
            parent[a] = parent[parent[a]];
            a = parent[a];
        }
        return a;
    };
    const float link2 = link * link;
    for (size_t a = 0; a < ids.size(); ++a) {
        for (size_t b = a + 1; b < ids.size(); ++b) {
            const float dx = px[ids[a]] - px[ids[b]], dy = py[ids[a]] - py[ids[b]];
            if (dx * dx + dy * dy < link2) {
                parent[root(uint32_t(a))] = root(uint32_t(b));
            }
        }
    }
    std::vector<uint32_t> size(ids.size(), 0);
    for (size_t a = 0; a < ids.size(); ++a) {
        ++size[root(uint32_t(a))];
    }
    std::vector<uint32_t> pieces;
    for (const uint32_t n : size) {
        if (n > 0) {
            pieces.push_back(n);
        }
    }
    std::sort(pieces.rbegin(), pieces.rend());
    return pieces;
}

// The lump's state: its pieces, where it stands and how fast it moves.
struct Lump {
    std::vector<uint32_t> pieces; // sizes, largest first
    float bottom = 0.0f;          // lowest particle (m)
    double cx = 0.0, cy = 0.0;    // centroid (m)
    double speed = 0.0;           // mean speed (m/s)
};

Lump lumpOf(const World& world, MaterialId material) {
    Lump l;
    l.pieces = lumpPieces(world, material, 1.5f * world.spacing(material));
    const auto px = world.positionX(), py = world.positionY();
    const auto vx = world.velocityX(), vy = world.velocityY();
    const auto mat = world.materialIndex();
    l.bottom = INFINITY;
    uint32_t n = 0;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (mat[i] == material.index) {
            l.bottom = std::min(l.bottom, py[i]);
            l.cx += px[i];
            l.cy += py[i];
            l.speed += std::sqrt(double(vx[i]) * vx[i] + double(vy[i]) * vy[i]);
            ++n;
        }
    }
    l.cx /= n;
    l.cy /= n;
    l.speed /= n;
    return l;
}

// A rested yoghurt lump in a water tank and how it came to rest (the test below).
struct RestedLump {
    World world{WorldDef{}}; // the game preset
    MaterialId yoghurt{};
    uint32_t count = 0;     // the lump's particles
    int floorFrame = -1;    // the frame it reached the floor at (-1: never)
    Lump landed, rested;    // when it reached the floor, 5 s later
    double drift = 0.0;     // its centre's move over the last 2 s (m)
    double restSpeed = 0.0; // its largest mean speed over the last 2 s (m/s)
};

// A 10 cm lump (1,050 kg/m^3 against the water's 1,000) dropped from 2 cm over the surface of
// 0.3 m of water in a 0.6 m tank, stepped until it reaches the floor, then 5 s more.
RestedLump restLump() {
    RestedLump r;
    World& world = r.world;
    const MaterialId w = world.addMaterial(water());
    const MaterialId y = world.addMaterial(yoghurt());
    r.yoghurt = y;
    const float s = world.spacing(w);
    const float width = 0.6f, depth = 0.3f, top = 0.8f;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, width, top));
    world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, uint32_t(width / s), uint32_t(depth / s)));
    for (int frame = 0; frame < 30; ++frame) {
        world.step(kFrame);
    }
    BlobDef drop;
    drop.shape = Shape::circle({0.5f * width, depth + 0.07f}, 0.05f);
    drop.material = y;
    r.count = world.spawnBlob(drop);
    const float spacing = world.spacing(y);
    for (int frame = 1; frame <= 15 * 60 && r.floorFrame < 0; ++frame) {
        world.step(kFrame);
        if (lumpOf(world, y).bottom < 2.0f * spacing) {
            r.floorFrame = frame;
        }
    }
    r.landed = lumpOf(world, y);
    // Five seconds on the floor: it stays where it came to lie (its particles jitter at about
    // 1 cm/s, as resting water's do at the game preset).
    Lump before;
    for (int frame = 1; frame <= 5 * 60; ++frame) {
        world.step(kFrame);
        if (frame == 3 * 60) {
            before = lumpOf(world, y);
        }
        if (frame > 3 * 60) {
            r.restSpeed = std::max(r.restSpeed, lumpOf(world, y).speed);
        }
    }
    r.rested = lumpOf(world, y);
    r.drift = std::hypot(r.rested.cx - before.cx, r.rested.cy - before.cy);
    return r;
}

// A hard push on the rested lump: the demo's pointer (40 m/s^2, here 0.1 m reach) swept
// through it from the left at `sweep` (m/s) for 1 s, then 2 s to settle, from a copy of the
// rested world.
Lump pushLump(const RestedLump& r, float sweep) {
    World pushedWorld = reloaded(r.world);
    auto& pointer = static_cast<PointerForce&>(
        pushedWorld.addForce(std::make_unique<PointerForce>(0.1f, 40.0f)));
    const float lumpY = r.rested.bottom + 0.04f;
    for (int frame = 0; frame < 60; ++frame) {
        pointer.setPointer({0.1f + sweep * float(frame) / 60.0f, lumpY}, 1.0f);
        pushedWorld.step(kFrame);
    }
    pointer.setPointer({0.0f, 0.0f}, 0.0f);
    for (int frame = 0; frame < 120; ++frame) {
        pushedWorld.step(kFrame);
    }
    return lumpOf(pushedWorld, pushedWorld.adopt(r.yoghurt));
}

} // namespace

TEST_CASE("a yoghurt lump dropped into water sinks, rests on the floor as one piece, and a hard "
          "push tears it into a few pieces",
          "[slow][invariants][materials][yield]") {
    Stopwatch sw("yoghurt lump in water");
    const RestedLump r = restLump();
    const uint32_t ny = r.count;
    REQUIRE(ny > 60);
    const float spacing = r.world.spacing(r.yoghurt);
    const Lump& rested = r.rested;
    std::printf("[measure] yoghurt lump in water: %u particles reach the floor after %.2f s (%zu "
                "pieces, largest %u); after 5 s on it %zu pieces, largest %u, bottom %.4f m, its "
                "centre moved %.4f m over the last 2 s, mean speed at most %.4f m/s\n",
                ny, double(r.floorFrame) / 60.0, r.landed.pieces.size(), r.landed.pieces[0],
                rested.pieces.size(), rested.pieces[0], double(rested.bottom), r.drift,
                r.restSpeed);
    CHECK(r.floorFrame > 0);                              // it sank
    CHECK(rested.bottom < 2.0f * spacing);                // and lies on the floor
    CHECK(double(rested.pieces[0]) >= 0.98 * double(ny)); // as one piece: 2% apart at most
    CHECK(r.drift < 0.003);                               // at rest

    // A hard push at nine sweep speeds, 0.2 to 1.0 m/s, each from the rested lump. It deforms
    // and keeps together: what tears off is a few particles of its skin, not the lump, in at
    // most 5 pieces at every speed (issue 67's target), since its skin holds against the water
    // (tuning::kSkinCohesion). Held together it slides less than a torn lump, so the push need
    // only move it 3 cm (figures: docs/yield_stress.md, "Its skin against the water").
    for (int k = 2; k <= 10; ++k) {
        const float sweep = 0.1f * float(k);
        const Lump pushed = pushLump(r, sweep);
        std::printf("[measure] yoghurt lump pushed at %.1f m/s: centroid x %.3f -> %.3f m, %zu "
                    "pieces:",
                    double(sweep), rested.cx, pushed.cx, pushed.pieces.size());
        for (const uint32_t n : pushed.pieces) {
            std::printf(" %u", n);
        }
        std::printf(" of %u\n", ny);
        CAPTURE(sweep, pushed.pieces.size());
        CHECK(pushed.cx > rested.cx + 0.03); // the push reached it and moved it
        CHECK(double(pushed.pieces[0]) >= 0.9 * double(ny));
        CHECK(pushed.pieces.size() <= 5);
    }
}

// Not run by ctest (hidden): the test's nine pushes, for scripts/readings.sh (two builds side by
// side).
TEST_CASE("readings: the yoghurt lump pushed at nine sweep speeds", "[.readings]") {
    const RestedLump r = restLump();
    std::printf("[reading] lump/rested/largest %u\n", r.rested.pieces[0]);
    for (int k = 2; k <= 10; ++k) {
        const float sweep = 0.1f * float(k);
        const Lump pushed = pushLump(r, sweep);
        std::printf("[reading] lump/sweep=%.1f/pieces %zu\n", double(sweep), pushed.pieces.size());
        std::printf("[reading] lump/sweep=%.1f/largest %u\n", double(sweep), pushed.pieces[0]);
        std::printf("[reading] lump/sweep=%.1f/moved-cm %.1f\n", double(sweep),
                    100.0 * (pushed.cx - r.rested.cx));
    }
}

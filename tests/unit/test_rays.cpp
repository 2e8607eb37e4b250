// Ray casts and the liquid at a point (fluid/query.h, fluid/surface_field.h): a ray's hit lies
// where a brute-force march over every particle finds the drawn field crossing its threshold,
// for the explicit solver and both position-based presets; the particle form reports what a
// scan finds, in order, and its visitor steers it as LiquidFun's does; rays that start inside;
// refusals; the same results for 1, 2 and 4 workers, after a save and load, and from several
// threads. A resting tank's surface, pressure and depth: tests/invariants/test_rays_tank.cpp.
#include "test_support.h"

#include <fluid/query.h>
#include <fluid/surface_field.h>

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <sstream>
#include <thread>

using namespace fluid;
using namespace fluid::test;

namespace {

// A tank with a few blobs of water (and yoghurt) at random places, stepped a random number of
// frames: a surface with splashes and droplets.
World randomWorld(Setting setting, uint32_t seed, uint32_t workers = 1) {
    std::mt19937 rng(seed);
    World world(defFor(setting, workers));
    const MaterialId w = world.addMaterial(water());
    const MaterialId y = world.addMaterial(forSolver(yoghurt(), world.def().solver));
    world.addForce(std::make_unique<GravityForce>());
    world.addBoundary(std::make_unique<BoxContainer>(-0.4f, 0.0f, 0.4f, 0.8f));
    std::uniform_real_distribution<float> x(-0.38f, 0.2f), h(0.0f, 0.5f);
    const int blobs = 2 + int(rng() % 3);
    for (int b = 0; b < blobs; ++b) {
        const MaterialId m = b % 2 == 0 ? w : y;
        // Drawn one statement at a time: a function's arguments are evaluated in an order the
        // compiler picks (g++ and clang differ), and the world would differ with it.
        const float x0 = x(rng);
        const float y0 = h(rng);
        const uint32_t cols = 6 + rng() % 12;
        const uint32_t rows = 6 + rng() % 12;
        world.spawnBlob(latticeBlock(world, m, x0, y0, cols, rows, {0.0f, -1.0f}));
    }
    const int frames = 8 + int(rng() % 20);
    for (int f = 0; f < frames; ++f) {
        world.step(kFrame);
    }
    return world;
}

// The drawn field from a list of particles, summed as the renderer sums it.
struct Brute {
    std::vector<double> x, y, R;
    std::vector<uint32_t> index;
    SurfaceField field;

    // Every particle of `world`, or those whose field reaches the segment p1 -> p2.
    Brute(const World& world, const SurfaceField& f = {}) : field(f) {
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            x.push_back(world.positionX()[i]);
            y.push_back(world.positionY()[i]);
            R.push_back(f.fieldRadius * world.spacing(MaterialId{world.materialIndex()[i]}));
            index.push_back(i);
        }
    }
    Brute near(glm::dvec2 a, glm::dvec2 b) const {
        Brute out = *this;
        out.x.clear(), out.y.clear(), out.R.clear(), out.index.clear();
        const glm::dvec2 d = b - a;
        const double l2 = glm::dot(d, d);
        for (std::size_t k = 0; k < x.size(); ++k) {
            const glm::dvec2 q{x[k], y[k]};
            const double t = l2 > 0.0 ? std::clamp(glm::dot(q - a, d) / l2, 0.0, 1.0) : 0.0;
            if (glm::length(a + t * d - q) < R[k]) {
                out.x.push_back(x[k]), out.y.push_back(y[k]), out.R.push_back(R[k]);
                out.index.push_back(index[k]);
            }
        }
        return out;
    }
    double at(double px, double py) const {
        double sum = 0.0, most = 0.0;
        for (std::size_t k = 0; k < x.size(); ++k) {
            const double rx = px - x[k], ry = py - y[k];
            const double q = 1.0 - (rx * rx + ry * ry) / (R[k] * R[k]);
            if (q > 0.0) {
                sum += q * q * q;
                most = std::max(most, q * q * q);
            }
        }
        return std::max(field.kernelWeight() * sum, field.dropletLevel() * most);
    }
    // The outward normal at (px, py): minus the gradient of the field's larger term.
    glm::dvec2 normal(double px, double py) const {
        double sum = 0.0, most = 0.0;
        glm::dvec2 gSum{0.0}, gMost{0.0};
        for (std::size_t k = 0; k < x.size(); ++k) {
            const glm::dvec2 r{px - x[k], py - y[k]};
            const double q = 1.0 - glm::dot(r, r) / (R[k] * R[k]);
            if (q > 0.0) {
                const glm::dvec2 g = -6.0 * q * q / (R[k] * R[k]) * r;
                sum += q * q * q;
                gSum += g;
                if (q * q * q > most) {
                    most = q * q * q;
                    gMost = g;
                }
            }
        }
        const glm::dvec2 g =
            field.kernelWeight() * sum >= field.dropletLevel() * most ? gSum : gMost;
        return -g / glm::length(g);
    }
};

// The first distance along p1 -> p2 where the brute-force field reaches the threshold, marching
// in steps of `step` (m) and bisecting the last one; -1 when it never does.
double bruteMarch(const Brute& all, glm::vec2 p1, glm::vec2 p2, double step) {
    const glm::dvec2 a{p1}, b{p2};
    const Brute f = all.near(a, b);
    const double length = glm::length(b - a);
    const glm::dvec2 u = (b - a) / length;
    const auto inside = [&](double t) {
        const glm::dvec2 p = a + t * u;
        return f.at(p.x, p.y) >= f.field.threshold;
    };
    if (inside(0.0)) {
        return 0.0;
    }
    for (double t = step;; t += step) {
        const double end = std::min(t, length);
        if (inside(end)) {
            double lo = end - step, hi = end;
            for (int k = 0; k < 40; ++k) {
                const double mid = 0.5 * (lo + hi);
                (inside(mid) ? hi : lo) = mid;
            }
            return hi;
        }
        if (end >= length) {
            return -1.0;
        }
    }
}

// A random ray over the tank: half of them through a random particle (from outside it, on past
// it), a quarter from a particle's position, the rest anywhere.
std::pair<glm::vec2, glm::vec2> randomRay(const World& world, std::mt19937& rng) {
    std::uniform_real_distribution<float> x(-0.45f, 0.45f), y(-0.05f, 0.7f);
    const glm::vec2 a{x(rng), y(rng)}, b{x(rng), y(rng)};
    const uint32_t kind = rng() % 4, i = rng() % world.particleCount();
    const glm::vec2 p{world.positionX()[i], world.positionY()[i]};
    if (kind < 2) {
        return {a, a + 1.5f * (p - a)};
    }
    if (kind == 2) {
        return {p, b};
    }
    return {a, b};
}

} // namespace

TEST_CASE("rays: the hit lies where a brute-force march finds the drawn field crossing its "
          "threshold",
          "[unit][rays]") {
    const Setting setting = GENERATE(Setting::Explicit, Setting::Game, Setting::Precise);
    CAPTURE(settingName(setting));
    uint32_t hits = 0, misses = 0, inside = 0;
    for (uint32_t seed = 1; seed <= 3; ++seed) {
        const World world = randomWorld(setting, seed);
        const Brute all(world);
        const double s = world.spacing(MaterialId{0}); // the finest
        std::mt19937 rng(100 + seed);
        for (int k = 0; k < 40; ++k) {
            const auto [p1, p2] = randomRay(world, rng);
            CAPTURE(seed, k, p1.x, p1.y, p2.x, p2.y);
            const RayHit hit = rayCast(world, p1, p2);
            const double expected = bruteMarch(all, p1, p2, 0.02 * s);
            const double length = glm::length(glm::dvec2(p2) - glm::dvec2(p1));
            REQUIRE(hit.hit == (expected >= 0.0));
            if (!hit.hit) {
                ++misses;
                continue;
            }
            CHECK(std::fabs(double(hit.fraction) * length - expected) <= 0.1 * s);
            CHECK(hit.startsInside == (expected == 0.0));
            // The point is on the ray at the fraction; the nearest particle is the nearest of
            // those the field reaches from; the material is its.
            const glm::dvec2 onRay =
                glm::dvec2(p1) + double(hit.fraction) * (glm::dvec2(p2) - glm::dvec2(p1));
            CHECK(glm::length(onRay - glm::dvec2(hit.point)) < 1e-5);
            REQUIRE(world.isValid(hit.particle));
            CHECK(world.handleAt(hit.index) == hit.particle);
            CHECK(hit.material.index == world.materialIndex()[hit.index]);
            const Brute here = all.near(glm::dvec2(hit.point), glm::dvec2(hit.point));
            REQUIRE(!here.index.empty());
            double best = 1e9;
            uint32_t nearest = 0;
            for (std::size_t j = 0; j < here.index.size(); ++j) {
                const double r = std::hypot(here.x[j] - hit.point.x, here.y[j] - hit.point.y);
                if (r < best) {
                    best = r;
                    nearest = here.index[j];
                }
            }
            CHECK(hit.index == nearest);
            if (hit.startsInside) {
                ++inside;
                CHECK(hit.fraction == 0.0f);
                CHECK(hit.point == p1);
                CHECK(hit.normal == glm::vec2(0.0f));
                continue;
            }
            ++hits;
            // The normal: unit length, facing the ray, the field's gradient's direction.
            CHECK(std::fabs(glm::length(hit.normal) - 1.0f) < 1e-5f);
            CHECK(glm::dot(hit.normal, p2 - p1) <= 1e-6f);
            const glm::dvec2 n = here.normal(hit.point.x, hit.point.y);
            CHECK(glm::dot(n, glm::dvec2(hit.normal)) > 0.9999);
            // The field at the hit is the threshold's, and just before it is below.
            CHECK(surfaceField(world, hit.point) == Approx(0.6).margin(0.02));
        }
    }
    CAPTURE(hits, misses, inside);
    CHECK(hits >= 30);
    CHECK(misses >= 10);
    CHECK(inside >= 10);
}

TEST_CASE("rays: the field at a point is the renderer's sum, its droplet discs included",
          "[unit][rays]") {
    const World world = randomWorld(Setting::Game, 9);
    const Brute all(world);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> x(-0.45f, 0.45f), y(-0.05f, 0.7f);
    for (int k = 0; k < 200; ++k) {
        const glm::vec2 p{x(rng), y(rng)};
        CHECK(surfaceField(world, p) == Approx(all.at(p.x, p.y)).margin(1e-6));
    }
    // A lone particle: a disc of half a spacing at the default threshold (the droplet level).
    World lone;
    const MaterialId w = lone.addMaterial(water());
    lone.addParticle({0.0f, 0.0f}, {0.0f, 0.0f}, w);
    const float s = lone.spacing(w);
    CHECK(surfaceField(lone, {0.0f, 0.0f}) == Approx(SurfaceField{}.dropletLevel()));
    CHECK(surfaceField(lone, {0.5f * s, 0.0f}) == Approx(0.6f));
    const RayHit hit = rayCast(lone, {-1.0f, 0.0f}, {1.0f, 0.0f});
    REQUIRE(hit.hit);
    CHECK(hit.point.x == Approx(-0.5f * s).margin(0.01f * s));
    CHECK(hit.normal.x == Approx(-1.0f));
    CHECK(hit.fraction == Approx((1.0f - 0.5f * s) / 2.0f).margin(0.005f * s));
    // A fatter threshold, a wider radius: the field's settings are the renderer's.
    SurfaceField fat;
    fat.threshold = 0.3f;
    fat.fieldRadius = 3.0f;
    const Brute wide(world, fat);
    for (int k = 0; k < 50; ++k) {
        const glm::vec2 p{x(rng), y(rng)};
        CHECK(surfaceField(world, p, fat) == Approx(wide.at(p.x, p.y)).margin(1e-6));
    }
}

TEST_CASE("rays: particle casts report what a scan finds, in order, steered by the visitor",
          "[unit][rays]") {
    const Setting setting = GENERATE(Setting::Explicit, Setting::Game, Setting::Precise);
    CAPTURE(settingName(setting));
    const World world = randomWorld(setting, 21);
    const float radius = world.spacing(MaterialId{0});
    std::mt19937 rng(8);
    uint32_t nonEmpty = 0;
    for (int k = 0; k < 40; ++k) {
        const auto [p1, p2] = randomRay(world, rng);
        CAPTURE(k);
        // The scan: every particle whose circle the segment meets, by entry, then index.
        const glm::dvec2 a{p1}, d = glm::dvec2(p2) - a;
        const double length = glm::length(d);
        std::vector<std::pair<double, uint32_t>> expected;
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            const glm::dvec2 q = glm::dvec2(world.positionX()[i], world.positionY()[i]) - a;
            const double r2 = double(radius) * radius;
            if (glm::dot(q, q) <= r2) {
                expected.push_back({0.0, i});
                continue;
            }
            const double tc = glm::dot(q, d) / length;
            const double across2 = glm::dot(q, q) - tc * tc;
            if (across2 > r2) {
                continue;
            }
            const double t = tc - std::sqrt(r2 - across2);
            if (t >= 0.0 && t <= length) {
                expected.push_back({t / length, i});
            }
        }
        std::sort(expected.begin(), expected.end());
        nonEmpty += expected.empty() ? 0u : 1u;
        std::vector<RayParticleHit> all;
        CHECK(rayCastParticles(world, p1, p2, radius, [&](const RayParticleHit& h) {
                  all.push_back(h);
                  return 1.0f;
              }) == expected.size());
        REQUIRE(all.size() == expected.size());
        for (std::size_t j = 0; j < all.size(); ++j) {
            CHECK(all[j].index == expected[j].second);
            CHECK(all[j].handle == world.handleAt(expected[j].second));
            CHECK(all[j].fraction == Approx(expected[j].first).margin(1e-6));
            const glm::vec2 c{world.positionX()[all[j].index], world.positionY()[all[j].index]};
            if (expected[j].first > 0.0) {
                CHECK(glm::length(all[j].point - c) == Approx(radius).epsilon(1e-3));
                CHECK(glm::dot(all[j].normal, p2 - p1) <= 1e-6f);
            }
        }
        if (expected.size() < 3) {
            continue;
        }
        // -1 ignores a particle and goes on: the same visits.
        uint32_t filtered = 0;
        CHECK(rayCastParticles(world, p1, p2, radius, [&](const RayParticleHit&) {
                  ++filtered;
                  return -1.0f;
              }) == expected.size());
        // 0 stops at once.
        CHECK(rayCastParticles(world, p1, p2, radius,
                               [&](const RayParticleHit&) { return 0.0f; }) == 1);
        // Returning the hit's own fraction finds the closest: after the first, only ties.
        std::vector<float> seen;
        rayCastParticles(world, p1, p2, radius, [&](const RayParticleHit& h) {
            seen.push_back(h.fraction);
            return h.fraction;
        });
        REQUIRE(!seen.empty());
        CHECK(seen.size() < expected.size());
        for (const float f : seen) {
            CHECK(f == seen[0]);
        }
        // Clipping at the middle one's fraction: only those up to it.
        const float middle = float(expected[expected.size() / 2].first);
        if (middle > 0.0f) {
            uint32_t upTo = 0;
            for (const auto& e : expected) {
                upTo += float(e.first) <= middle ? 1u : 0u;
            }
            CHECK(rayCastParticles(world, p1, p2, radius,
                                   [&](const RayParticleHit&) { return middle; }) == upTo);
        }
    }
    CHECK(nonEmpty > 15);
    // A radius over the whole tank: every particle (the scan path), in order.
    uint32_t wide = 0;
    float last = -1.0f;
    bool ordered = true;
    rayCastParticles(world, {-0.5f, 0.3f}, {0.5f, 0.3f}, 10.0f, [&](const RayParticleHit& h) {
        ++wide;
        ordered = ordered && h.fraction >= last;
        last = h.fraction;
        return 1.0f;
    });
    CHECK(wide == world.particleCount());
    CHECK(ordered);
}

TEST_CASE("rays: a ray that starts inside, one of zero length, one that misses", "[unit][rays]") {
    World world(defFor(Setting::Game, 1));
    const MaterialId w = world.addMaterial(water());
    world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, 20, 20));
    const float s = world.spacing(w);
    const float top = 20.0f * s; // the block's top edge: the field's surface, about
    // From inside, up and out: fraction 0, the start, no normal.
    const RayHit in = rayCast(world, {0.1f * 20 * s, 0.5f * top}, {0.1f, 1.0f});
    CHECK(in.hit);
    CHECK(in.startsInside);
    CHECK(in.fraction == 0.0f);
    CHECK(in.point == glm::vec2(0.1f * 20 * s, 0.5f * top));
    CHECK(in.normal == glm::vec2(0.0f));
    CHECK(world.isValid(in.particle));
    // Zero length: a hit inside, none outside.
    const RayHit dot = rayCast(world, {0.1f, 0.1f}, {0.1f, 0.1f});
    CHECK((dot.hit && dot.startsInside && dot.fraction == 0.0f));
    CHECK_FALSE(rayCast(world, {0.1f, 0.5f}, {0.1f, 0.5f}).hit);
    // Down from above: the surface about half a spacing over the top row.
    const RayHit down = rayCast(world, {0.1f, 0.5f}, {0.1f, -0.5f});
    REQUIRE(down.hit);
    CHECK_FALSE(down.startsInside);
    CHECK(down.point.y == Approx(top).margin(0.5f * s));
    CHECK(down.normal.y > 0.99f);
    // A ray that ends short of the liquid, one beside it, one far away, an empty world.
    CHECK_FALSE(rayCast(world, {0.1f, 0.5f}, {0.1f, top + s}).hit);
    CHECK_FALSE(rayCast(world, {0.5f, 0.5f}, {0.5f, -0.5f}).hit);
    CHECK_FALSE(rayCast(world, {-4e3f, 1e3f}, {4e3f, 1e3f}).hit);
    World empty;
    empty.addMaterial(water());
    CHECK_FALSE(rayCast(empty, {0.0f, 0.0f}, {1.0f, 1.0f}).hit);
    CHECK_FALSE(sample(empty, {0.0f, 0.0f}).inLiquid);
    // A very long ray across it still hits at the right place.
    const RayHit longer = rayCast(world, {0.1f, 1000.0f}, {0.1f, -1000.0f});
    REQUIRE(longer.hit);
    CHECK(longer.point.y == Approx(down.point.y).margin(0.01f * s));
}

TEST_CASE("rays: sample interpolates the particles' values with the solvers' kernel",
          "[unit][rays]") {
    const World world = randomWorld(Setting::Game, 4);
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> x(-0.45f, 0.45f), y(-0.05f, 0.5f);
    // 200 points, of which about a third land near particles: more than 30 for the comparisons
    // below to mean something.
    uint32_t reached = 0;
    for (int k = 0; k < 200; ++k) {
        const glm::vec2 p{x(rng), y(rng)};
        // The Shepard sum over every particle, each weighted by its rest area and Wendland C2.
        double wsum = 0.0, rho = 0.0, pressure = 0.0, vx = 0.0;
        std::vector<double> share(world.materialCount(), 0.0);
        uint32_t neighbours = 0;
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            const MaterialId m{world.materialIndex()[i]};
            const Material& mat = world.material(m);
            const double h = mat.smoothingDistance;
            const double r = std::hypot(p.x - world.positionX()[i], p.y - world.positionY()[i]);
            if (r >= h) {
                continue;
            }
            const double q = r / h;
            const double W = 7.0 / (3.14159265358979 * h * h) * std::pow(1.0 - q, 4) * (1 + 4 * q);
            const double wt = particleArea(mat, world.def().depth) * W;
            ++neighbours;
            wsum += wt;
            rho += wt * world.density()[i] / mat.restDensity;
            pressure += wt * world.pressure()[i];
            vx += wt * world.velocityX()[i];
            share[m.index] += wt;
        }
        std::vector<float> fractions(world.materialCount() + 1, 9.0f);
        const LiquidSample got = sample(world, p, fractions);
        CAPTURE(k, p.x, p.y);
        CHECK(got.neighbours == neighbours);
        CHECK(fractions.back() == 0.0f); // beyond the materials: 0
        if (neighbours == 0) {
            CHECK(got.pressure == 0.0f);
            CHECK(fractions[0] == 0.0f);
            continue;
        }
        ++reached;
        CHECK(got.densityRatio == Approx(rho / wsum).epsilon(1e-5));
        CHECK(got.pressure == Approx(pressure / wsum).epsilon(1e-4).margin(1e-3));
        CHECK(got.velocity.x == Approx(vx / wsum).epsilon(1e-4).margin(1e-6));
        for (uint32_t m = 0; m < world.materialCount(); ++m) {
            CHECK(fractions[m] == Approx(share[m] / wsum).margin(1e-5));
        }
        // In the liquid exactly where the drawn field says so.
        CHECK(got.inLiquid == (got.field >= 0.6f));
    }
    CHECK(reached > 30);
}

namespace {

// A force plugin whose prepare casts rays into the world that runs it.
struct RayHook final : public ForcePlugin {
    static constexpr std::array<ParamDecl, 0> kParams{};
    explicit RayHook(const World& w) : ForcePlugin("force.test-ray", kParams), world(w) {}
    void prepare(const StepContext&) override {
        for (int k = 0; k < 3; ++k) {
            try {
                if (k == 0) {
                    rayCast(world, {0.0f, 0.5f}, {0.0f, 0.0f});
                } else if (k == 1) {
                    sample(world, {0.0f, 0.1f});
                } else {
                    rayCastParticles(world, {0.0f, 0.5f}, {0.0f, 0.0f}, 0.01f,
                                     [](const RayParticleHit&) { return 1.0f; });
                }
            } catch (const Error& e) {
                codes.push_back(e.code());
                messages.push_back(e.what());
            }
        }
    }
    void apply(const ForceContext&, uint32_t, uint32_t) override {}
    const World& world;
    std::vector<ErrorCode> codes;
    std::vector<std::string> messages;
};

} // namespace

TEST_CASE("rays: bad rays, points, fields and visitors, and casts during a step, are refused",
          "[unit][rays]") {
    World world = randomWorld(Setting::Game, 2);
    const auto go = [](const RayParticleHit&) { return 1.0f; };
    CHECK_THROWS_WITH(rayCast(world, {std::nanf(""), 0.0f}, {1.0f, 1.0f}),
                      "rayCast: p1 = (nan, 0) is not finite (unit: m)");
    CHECK_THROWS_WITH(rayCast(world, {0.0f, 0.0f}, {1.0f, -INFINITY}),
                      "rayCast: p2 = (1, -inf) is not finite (unit: m)");
    SurfaceField field;
    field.fieldRadius = 5.0f;
    CHECK_THROWS_WITH(rayCast(world, {0.0f, 0.0f}, {1.0f, 1.0f}, field),
                      "rayCast: field.fieldRadius = 5 is out of range [1, 4] (unit: 1)");
    field = {};
    field.threshold = std::nanf("");
    CHECK_THROWS_WITH(sample(world, {0.0f, 0.0f}, {}, field),
                      "sample: field.threshold = nan is out of range [0.05, 4] (unit: 1)");
    CHECK_THROWS_WITH(sample(world, {INFINITY, 0.0f}),
                      "sample: point = (inf, 0) is not finite (unit: m)");
    CHECK_THROWS_WITH(surfaceField(world, {0.0f, std::nanf("")}),
                      "surfaceField: point = (0, nan) is not finite (unit: m)");
    CHECK_THROWS_WITH(rayCastParticles(world, {0.0f, 0.0f}, {1.0f, 1.0f}, 0.0f, go),
                      "rayCastParticles: radius = 0 is out of range (0, inf) (unit: m)");
    CHECK_THROWS_WITH(rayCastParticles(world, {0.0f, 0.0f}, {1.0f, 1.0f}, INFINITY, go),
                      "rayCastParticles: radius = inf is out of range (0, inf) (unit: m)");
    CHECK_THROWS_WITH(rayCastParticles(world, {0.0f, 0.0f}, {1.0f, std::nanf("")}, 0.01f, go),
                      "rayCastParticles: p2 = (1, nan) is not finite (unit: m)");
    CHECK_THROWS_WITH(rayCastParticles(world, {0.0f, 0.0f}, {1.0f, 1.0f}, 0.01f, RayVisitor{}),
                      "rayCastParticles: the visitor is empty");
    CHECK_THROWS_WITH(rayCastParticles(world, {-0.5f, 0.02f}, {0.5f, 0.02f}, 0.01f,
                                       [](const RayParticleHit&) { return std::nanf(""); }),
                      "rayCastParticles: the visitor returned nan; expected -1 (ignore the "
                      "particle), 0 (stop), a fraction in (0, 1) (clip the ray) or 1 (go on)");
    // From a plugin's hook during the step: refused with WrongState.
    auto& hook = static_cast<RayHook&>(world.addForce(std::make_unique<RayHook>(world)));
    world.step(kFrame);
    CHECK(hook.codes == std::vector<ErrorCode>(3, ErrorCode::WrongState));
    REQUIRE(hook.messages.size() == 3);
    CHECK(hook.messages[0] == "rayCast: called during the world's own step (from a plugin's hook "
                              "or a task); query the world between its steps");
    CHECK(hook.messages[1] == "sample: called during the world's own step (from a plugin's hook "
                              "or a task); query the world between its steps");
    CHECK(hook.messages[2] == "rayCastParticles: called during the world's own step (from a "
                              "plugin's hook or a task); query the world between its steps");
}

namespace {

// Every number the casts and samples of a fixed set of rays and points give, as bits.
std::vector<uint32_t> castBits(const World& world) {
    std::vector<uint32_t> out;
    const auto put = [&](float v) {
        uint32_t b = 0;
        std::memcpy(&b, &v, 4);
        out.push_back(b);
    };
    std::mt19937 rng(77);
    std::uniform_real_distribution<float> x(-0.45f, 0.45f), y(-0.05f, 0.7f);
    for (int k = 0; k < 60; ++k) {
        const glm::vec2 p1{x(rng), y(rng)}, p2{x(rng), y(rng)};
        const RayHit h = rayCast(world, p1, p2);
        out.push_back(h.hit + 2u * h.startsInside);
        put(h.fraction), put(h.point.x), put(h.point.y), put(h.normal.x), put(h.normal.y);
        out.push_back(h.index);
        std::array<float, 2> share{};
        const LiquidSample s = sample(world, p1, share);
        put(s.field), put(s.pressure), put(s.depth), put(s.densityRatio), put(s.velocity.x);
        put(share[0]), put(share[1]);
        rayCastParticles(world, p1, p2, 0.01f, [&](const RayParticleHit& hit) {
            out.push_back(hit.index);
            put(hit.fraction);
            return 1.0f;
        });
    }
    return out;
}

} // namespace

// [slow]: the worker matrix is too slow for the asan preset (docs/building.md), where the casts'
// other tests still run on one worker; the release and tsan presets run it.
TEST_CASE("rays: the same results for 1, 2 and 4 workers and after a save and load",
          "[unit][rays][slow]") {
    const Setting setting = GENERATE(Setting::Explicit, Setting::Game);
    CAPTURE(settingName(setting));
    std::vector<std::vector<uint32_t>> results;
    for (const uint32_t workers : {1u, 2u, 4u}) {
        const World world = randomWorld(setting, 31, workers);
        results.push_back(castBits(world));
        if (workers == 4) {
            const World loaded = reloaded(world, 1);
            CHECK(castBits(loaded) == results.back());
        }
    }
    CHECK(results[0].size() > 600);
    CHECK(results[1] == results[0]);
    CHECK(results[2] == results[0]);
}

TEST_CASE("rays: casts and samples from several threads at once between steps", "[unit][rays]") {
    World world = randomWorld(Setting::Game, 6);
    const std::vector<uint32_t> expected = castBits(world);
    world.step(kFrame); // the grid is stale: the threads race to build it
    const std::vector<uint32_t> after = [&] {
        World copy = randomWorld(Setting::Game, 6);
        copy.step(kFrame);
        return castBits(copy);
    }();
    CHECK(after != expected);
    std::vector<uint32_t> wrong(4, 0);
    std::vector<std::thread> threads;
    for (uint32_t t = 0; t < 4; ++t) {
        threads.emplace_back([&, t] { wrong[t] = castBits(world) == after ? 0u : 1u; });
    }
    for (std::thread& t : threads) {
        t.join();
    }
    CHECK(wrong == std::vector<uint32_t>(4, 0));
}

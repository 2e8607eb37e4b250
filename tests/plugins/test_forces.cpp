// Built-in force plugins: point gravity, vortex, wind, pointer, explosion, damping zone. Each is
// checked twice: `apply` on hand-built particles (direction, falloff, exact magnitudes) and in
// a zero-g world without walls on lone particles far apart (no neighbours, so the fluid adds
// nothing and the motion is the field's alone) or on a small blob. Then the registry, the
// exact parameter errors, range independence, finiteness under extreme numbers and the
// snapshot hooks.
#include "test_support.h"

#include <fluid/plugins/forces.h>

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {


// Particles for calling `apply` directly: plain vectors, one context over them.
struct Bench {
    std::vector<float> px, py, vx, vy, ax, ay;
    std::vector<uint16_t> material;
    std::vector<Material> materials{water()};

    void add(glm::vec2 x, glm::vec2 v = {0.0f, 0.0f}) {
        px.push_back(x.x);
        py.push_back(x.y);
        vx.push_back(v.x);
        vy.push_back(v.y);
        ax.push_back(0.0f);
        ay.push_back(0.0f);
        material.push_back(0);
    }
    uint32_t size() const { return uint32_t(px.size()); }
    ForceContext context(float dt, double time = 0.0) {
        const ParticleView view{px, py, vx, vy, material, materials, size()};
        return ForceContext{view, ax, ay, dt, time};
    }
    // Zeroes the accumulators and applies `force` to every particle.
    void run(ForcePlugin& force, float dt = 0.0f, double time = 0.0) {
        std::fill(ax.begin(), ax.end(), 0.0f);
        std::fill(ay.begin(), ay.end(), 0.0f);
        force.apply(context(dt, time), 0, size());
    }
    glm::dvec2 a(size_t i) const { return {ax[i], ay[i]}; }
};

// The acceleration `force` gives one particle at x moving at v.
glm::dvec2 accelAt(ForcePlugin& force, glm::vec2 x, glm::vec2 v = {0.0f, 0.0f}, float dt = 0.0f) {
    Bench b;
    b.add(x, v);
    b.run(force, dt);
    return b.a(0);
}

double length(glm::dvec2 v) {
    return std::sqrt(v.x * v.x + v.y * v.y);
}
double dot(glm::dvec2 a, glm::dvec2 b) {
    return a.x * b.x + a.y * b.y;
}
double cross(glm::dvec2 a, glm::dvec2 b) {
    return a.x * b.y - a.y * b.x;
}

// The exact drag factor the plugins use: lambda = (1 - exp(-k dt)) / dt.
double lambdaOf(double rate, double dt) {
    return -std::expm1(-rate * dt) / dt;
}

// A zero-g world without walls (one worker: these scenes hold a handful of particles).
struct Scene {
    World world;
    MaterialId water;
    std::vector<ParticleHandle> handles;

    explicit Scene(Solver solver = Solver::PositionBased) : world(makeDef(solver)) {
        water = world.addMaterial(fluid::water());
    }
    static WorldDef makeDef(Solver solver) {
        WorldDef def;
        def.solver = solver;
        return def;
    }
    ParticleHandle add(glm::vec2 x, glm::vec2 v = {0.0f, 0.0f}) {
        handles.push_back(world.addParticle(x, v, water));
        return handles.back();
    }
    // `count` particles on a circle of `radius` around `centre`, velocity from `velocity`.
    template <class F> void ring(glm::vec2 centre, float radius, int count, F velocity) {
        for (int k = 0; k < count; ++k) {
            const double t = 2.0 * kPi * k / count;
            const glm::vec2 u{float(std::cos(t)), float(std::sin(t))};
            add(centre + radius * u, velocity(u));
        }
    }
    void ring(glm::vec2 centre, float radius, int count) {
        ring(centre, radius, count, [](glm::vec2) { return glm::vec2{0.0f, 0.0f}; });
    }
    template <class P> P& add(std::unique_ptr<P> plugin) {
        return static_cast<P&>(world.addForce(std::move(plugin)));
    }
    void frames(int n) {
        for (int k = 0; k < n; ++k) {
            world.step(kFrame);
        }
    }
    glm::dvec2 x(size_t k) const {
        const glm::vec2 p = world.position(handles[k]);
        return {p.x, p.y};
    }
    glm::dvec2 v(size_t k) const {
        const glm::vec2 u = world.velocity(handles[k]);
        return {u.x, u.y};
    }
    double mass() const { return world.material(water).mass; }
    // Angular momentum about `c` (unit: kg m^2/s).
    double angularMomentum(glm::dvec2 c) const {
        double l = 0.0;
        for (size_t k = 0; k < handles.size(); ++k) {
            l += mass() * cross(x(k) - c, v(k));
        }
        return l;
    }
};

} // namespace

// ---- point gravity ---------------------------------------------------------------------------

TEST_CASE("point gravity points at the centre and falls off as 1/r^n", "[unit][forces]") {
    const glm::vec2 c{0.5f, 0.2f};
    PointGravityForce g(c, 2.0f, 0.5f, 2.0f);
    g.setParam("softening", 0.0);
    for (const glm::vec2 d : {glm::vec2{1.0f, 0.0f}, glm::vec2{0.3f, -0.7f}, glm::vec2{-2.0f, 1.5f},
                              glm::vec2{0.0f, -0.01f}}) {
        CAPTURE(d.x, d.y);
        const glm::dvec2 a = accelAt(g, c + d);
        const glm::dvec2 r{d.x, d.y};
        CHECK(dot(a, r) < 0.0); // towards the centre
        CHECK(std::fabs(cross(a, r)) <= 1e-5 * length(a) * length(r));
    }
    for (const double n : {0.0, 1.0, 1.5, 2.0, 3.0}) {
        CAPTURE(n);
        g.setParam("falloff", n);
        const glm::vec2 u{0.6f, 0.8f};
        const double a1 = length(accelAt(g, c + 0.5f * u)); // at the reference radius
        const double a2 = length(accelAt(g, c + 1.0f * u));
        CHECK(a1 == Approx(2.0).epsilon(1e-5)); // the strength, at the reference radius
        CHECK(a1 / a2 == Approx(std::pow(2.0, n)).epsilon(1e-5));
        std::printf("[measure] point gravity n = %.1f: |a(r)|/|a(2r)| = %.6f (2^n = %.6f)\n", n,
                    a1 / a2, std::pow(2.0, n));
    }
    g.setParam("falloff", 2.0);

    SECTION("finite at the centre, softened inside epsilon") {
        // Unsoftened: exactly 0 on the centre, finite however close.
        CHECK(accelAt(g, c) == glm::dvec2{0.0, 0.0});
        for (const float e : {1e-3f, 1e-7f, 1e-20f, 1e-38f}) {
            const glm::dvec2 a = accelAt(g, c + glm::vec2{e, 0.0f});
            CHECK(std::isfinite(a.x));
            CHECK(a.y == 0.0);
        }
        // Softened (Plummer): |a| = k r / (r^2 + eps^2)^(3/2), k = g0 r0^2.
        const double eps = 0.1, k = 2.0 * 0.25;
        g.setParam("softening", eps);
        CHECK(accelAt(g, c) == glm::dvec2{0.0, 0.0});
        const glm::vec2 p = c + glm::vec2{0.1f, 0.0f};
        const double r = double(p.x) - c.x;
        CHECK(length(accelAt(g, p)) ==
              Approx(k * r / std::pow(r * r + eps * eps, 1.5)).epsilon(1e-5));
        // The softened pull is below the point-mass pull everywhere and nearly equal far away.
        for (const float rr : {0.05f, 0.2f, 1.0f, 5.0f}) {
            const double soft = length(accelAt(g, c + glm::vec2{0.0f, rr}));
            CHECK(soft < k / (double(rr) * rr));
        }
        CHECK(length(accelAt(g, c + glm::vec2{0.0f, 5.0f})) == Approx(k / 25.0).epsilon(1e-3));
    }
    SECTION("cut-off and repulsion") {
        g.setParam("cutoff", 1.0);
        CHECK(accelAt(g, c + glm::vec2{1.01f, 0.0f}) == glm::dvec2{0.0, 0.0});
        CHECK(accelAt(g, c + glm::vec2{0.99f, 0.0f}).x < 0.0);
        g.setParam("strength", -2.0);
        CHECK(accelAt(g, c + glm::vec2{0.5f, 0.0f}).x == Approx(2.0).epsilon(1e-5)); // away
    }
}

TEST_CASE("point gravity: a circular orbit keeps its radius and angular momentum",
          "[unit][forces]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    Scene s(solver);
    // Newton, 2 m/s^2 at 0.5 m: the circular speed at 0.5 m is sqrt(g r) = 1 m/s, period pi s.
    s.add(std::make_unique<PointGravityForce>(glm::vec2{0.0f, 0.0f}, 2.0f, 0.5f, 2.0f))
        .setParam("softening", 0.0);
    s.add({0.5f, 0.0f}, {0.0f, 1.0f});
    // A second body on the opposite side, orbiting too: the pair's momentum stays ~0.
    s.add({-0.5f, 0.0f}, {0.0f, -1.0f});
    const double l0 = cross(s.x(0), s.v(0));
    const double k = 2.0 * 0.25;
    const double e0 = 0.5 * dot(s.v(0), s.v(0)) - k / length(s.x(0));
    double rMin = 1e9, rMax = 0.0, eWorst = 0.0, lWorst = 0.0;
    const int frames = int(std::lround(kPi / kFrame)); // one orbit
    for (int f = 0; f < frames; ++f) {
        s.world.step(kFrame);
        const double r = length(s.x(0));
        rMin = std::min(rMin, r);
        rMax = std::max(rMax, r);
        const double e = 0.5 * dot(s.v(0), s.v(0)) - k / r;
        eWorst = std::max(eWorst, std::fabs(e / e0 - 1.0));
        lWorst = std::max(lWorst, std::fabs(cross(s.x(0), s.v(0)) / l0 - 1.0));
    }
    std::printf("[measure] point gravity orbit (%s): radius %.5f..%.5f m (0.5), energy drift "
                "%.2e, angular momentum drift %.2e\n",
                solverLabel(solver), rMin, rMax, eWorst, lWorst);
    CHECK(rMin > 0.49);
    CHECK(rMax < 0.51);
    CHECK(eWorst < 0.01);
    CHECK(lWorst < 1e-4); // a central force conserves it (exactly under symplectic Euler)
    // Back near the start after one period.
    CHECK(length(s.x(0) - glm::dvec2{0.5, 0.0}) < 0.02);
    CHECK(length(momentum(s.world)) < 1e-6 * s.mass());
}

TEST_CASE("point gravity: softened to at least the spacing, the pull capped per sub-step",
          "[unit][forces]") {
    const glm::vec2 c{0.0f, 0.0f};
    PointGravityForce g(c, 9.81f, 1.0f, 2.0f);
    g.setParam("softening", 0.0);
    StepContext step;
    step.sampleSpacing = 0.01f;
    g.prepare(step);
    const float dt = 1.0f / 240.0f;
    const double cap = PointGravityForce::kMaxPullShare * 0.01 / (double(dt) * dt); // 57.6
    // Far out the pull is Newton's, softened by the spacing (not by 0).
    const double r = 2.0, eps = 0.01;
    CHECK(length(accelAt(g, {float(r), 0.0f}, {}, dt)) ==
          Approx(9.81 * r / std::pow(r * r + eps * eps, 1.5)).epsilon(1e-5));
    // Near the centre it is the cap, never more, pointing in; 0 on the centre.
    for (const float x : {0.3f, 0.05f, 0.01f, 1e-4f}) {
        CAPTURE(x);
        const glm::dvec2 a = accelAt(g, {x, 0.0f}, {}, dt);
        CHECK(a.x == Approx(-cap).epsilon(1e-5));
        CHECK(a.y == 0.0);
    }
    CHECK(accelAt(g, c, {}, dt) == glm::dvec2{0.0, 0.0});
    // A softening wider than the spacing is kept: the pull at 2 cm is below the cap there.
    g.setParam("softening", 0.5);
    const double soft = 9.81 * 0.02 / std::pow(0.02 * 0.02 + 0.25, 1.5);
    CHECK(length(accelAt(g, {0.02f, 0.0f}, {}, dt)) == Approx(soft).epsilon(1e-5));
    // The cap follows the sub-step: twice the sub-steps, four times the cap.
    g.setParam("softening", 0.0);
    CHECK(length(accelAt(g, {0.05f, 0.0f}, {}, dt / 2.0f)) == Approx(4.0 * cap).epsilon(1e-5));
}

TEST_CASE("point gravity inside a resting blob holds it: no burst at any softening",
          "[physics][forces]") {
    // The report's case: the centre inside a 0.3 m blob of water in zero g, game preset. With a
    // softening of 0 the blob burst: 927 J, particles thrown 23 m; at the default 0.05 m, 800 J
    // and 2.7 m.
    const double softening = GENERATE(0.0, 0.05);
    CAPTURE(softening);
    WorldDef def;
    def.positionBased = positionBasedPreset(Quality::Game);
    World world(def);
    const MaterialId w = world.addMaterial(fluid::water());
    auto pull = std::make_unique<PointGravityForce>(glm::vec2{0.0f, 0.0f}, 9.81f, 1.0f, 2.0f);
    pull->setParam("softening", softening);
    world.addForce(std::move(pull));
    BlobDef blob;
    blob.shape = Shape::circle({0.0f, 0.0f}, 0.3f);
    blob.material = w;
    world.spawnBlob(blob);
    const double mass = world.material(w).mass * world.particleCount();
    double keMax = 0.0, reach = 0.0, ke = 0.0;
    for (int frame = 0; frame < 180; ++frame) {
        world.step(kFrame);
        ke = energy(world, 0.0).kinetic;
        keMax = std::max(keMax, ke);
        const Bounds b = bounds(world);
        reach = std::max({reach, -double(b.x0), -double(b.y0), double(b.x1), double(b.y1)});
    }
    std::printf("[measure] point gravity in a 0.3 m blob, softening %.2f m: largest kinetic "
                "energy %.3f J (%.3f J/kg), at 3 s %.4f J; farthest particle %.3f m\n",
                softening, keMax, keMax / mass, ke, reach);
    REQUIRE(allFinite(world));
    CHECK(reach < 0.31);        // it only packs in
    CHECK(keMax / mass < 0.2);  // the collapse's speeds: well under 1 m/s
    CHECK(ke / mass < 0.01);    // and it comes to rest
}

// ---- vortex --------------------------------------------------------------------------------

TEST_CASE("vortex: tangential Rankine drag, no radial part, optional pull", "[unit][forces]") {
    const glm::vec2 c{0.2f, -0.1f};
    VortexForce v(c, 1.5f, 0.3f, 4.0f); // V = 1.5 m/s at R = 0.3 m, k = 4/s
    // The swirl adds no radial acceleration, whatever the particle's velocity.
    for (const glm::vec2 d : {glm::vec2{0.1f, 0.05f}, glm::vec2{-0.25f, 0.2f},
                              glm::vec2{0.0f, -0.9f}, glm::vec2{3.0f, 1.0f}}) {
        for (const glm::vec2 vel :
             {glm::vec2{0.0f, 0.0f}, glm::vec2{2.0f, -1.0f}, glm::vec2{-0.3f, 0.7f}}) {
            for (const float dt : {0.0f, 1.0f / 240.0f}) {
                CAPTURE(d.x, d.y, vel.x, vel.y, dt);
                const glm::dvec2 a = accelAt(v, c + d, vel, dt);
                const glm::dvec2 r{d.x, d.y};
                CHECK(std::fabs(dot(a, r)) <= 1e-5 * (length(a) * length(r) + 1e-9));
            }
        }
    }
    // At rest: counter-clockwise with |a| = k u(r) (dt = 0), or lambda u(r) over a sub-step.
    const glm::vec2 inner = c + glm::vec2{0.15f, 0.0f}; // u = V r / R = 0.75 m/s
    const glm::vec2 outer = c + glm::vec2{0.0f, 0.6f};  // u = V R / r = 0.75 m/s
    for (const glm::vec2 p : {inner, outer}) {
        const glm::dvec2 r = glm::dvec2(p.x, p.y) - glm::dvec2(c.x, c.y);
        const glm::dvec2 a = accelAt(v, p);
        CHECK(cross(r, a) > 0.0); // counter-clockwise
        CHECK(length(a) == Approx(4.0 * 0.75).epsilon(1e-4));
        const float dt = 1.0f / 240.0f;
        CHECK(length(accelAt(v, p, {0.0f, 0.0f}, dt)) ==
              Approx(lambdaOf(4.0, dt) * 0.75).epsilon(1e-4));
    }
    // Already turning with the vortex: nothing to add.
    CHECK(length(accelAt(v, inner, {0.0f, 0.75f})) < 1e-5);
    // Negative speed turns clockwise.
    v.setParam("speed", -1.5);
    CHECK(cross(glm::dvec2(0.15, 0.0), accelAt(v, inner)) < 0.0);
    // The centre has no direction: exactly 0.
    CHECK(accelAt(v, c, {1.0f, 2.0f}) == glm::dvec2{0.0, 0.0});

    SECTION("pull: inward, r/R inside the core and R/r outside") {
        v.setParam("speed", 0.0);
        v.setParam("pull", 2.0);
        const glm::dvec2 ai = accelAt(v, inner), ao = accelAt(v, outer);
        CHECK(ai.x == Approx(-2.0 * 0.5).epsilon(1e-4));
        CHECK(ai.y == Approx(0.0).margin(1e-6));
        CHECK(ao.y == Approx(-2.0 * 0.5).epsilon(1e-4));
        CHECK(ao.x == Approx(0.0).margin(1e-6));
    }
    SECTION("cut-off") {
        v.setParam("cutoff", 0.5);
        CHECK(accelAt(v, outer) == glm::dvec2{0.0, 0.0});
        CHECK(length(accelAt(v, inner)) > 0.0);
    }
}

TEST_CASE("vortex spins a ring with the sign of its speed, momentum stays ~0", "[unit][forces]") {
    const glm::vec2 c{0.1f, -0.2f};
    auto run = [&](float speed, std::vector<double>& lz, double& pWorst, double& vtMax) {
        Scene s;
        s.add(std::make_unique<VortexForce>(c, speed, 0.3f, 3.0f));
        s.ring(c, 0.25f, 16); // 0.1 m apart: lone particles
        const glm::dvec2 cd{c.x, c.y};
        for (int f = 0; f < 30; ++f) {
            s.world.step(kFrame);
            lz.push_back(s.angularMomentum(cd));
            pWorst = std::max(pWorst, length(momentum(s.world)));
            for (size_t k = 0; k < s.handles.size(); ++k) {
                const glm::dvec2 r = s.x(k) - cd;
                vtMax = std::max(vtMax, std::fabs(cross(r, s.v(k))) / length(r));
            }
        }
        return s.mass() * 16;
    };
    std::vector<double> ccw, cw;
    double pCcw = 0.0, pCw = 0.0, vtCcw = 0.0, vtCw = 0.0;
    const double mass = run(1.0f, ccw, pCcw, vtCcw);
    run(-1.0f, cw, pCw, vtCw);
    for (size_t f = 0; f < ccw.size(); ++f) {
        CAPTURE(f);
        CHECK(ccw[f] > (f == 0 ? 0.0 : ccw[f - 1]));   // grows, counter-clockwise
        CHECK(cw[f] == Approx(-ccw[f]).epsilon(1e-4)); // the mirror image
    }
    // After the first frame, while the ring is still at r = 0.25 (it drifts outward later: no
    // centripetal pull), L = M r u(r) (1 - exp(-k t)) with u(r) = V r / R.
    const double lExpected = mass * 0.25 * (1.0 * 0.25 / 0.3) * -std::expm1(-3.0 * kFrame);
    std::printf("[measure] vortex ring: Lz(1 frame) = %.5e (M r u (1 - e^-kt) = %.5e), Lz(0.5 s) "
                "= %.4e, |P| max %.2e kg m/s, tangential speed max %.4f m/s (vortex max 1)\n",
                ccw[0], lExpected, ccw.back(), pCcw, vtCcw);
    CHECK(ccw[0] == Approx(lExpected).epsilon(0.01));
    CHECK(pCcw < 1e-5 * mass * 1.0); // symmetric: no net push
    CHECK(vtCcw <= 1.0 + 1e-4);      // never faster than the vortex
}

TEST_CASE("vortex with pull V^2/R holds a spinning ring at the core radius", "[unit][forces]") {
    Scene s;
    auto& v = s.add(std::make_unique<VortexForce>(glm::vec2{0.0f, 0.0f}, 0.8f, 0.3f, 3.0f));
    v.setParam("pull", 0.8 * 0.8 / 0.3);
    s.ring({0.0f, 0.0f}, 0.3f, 12, [](glm::vec2 u) { return 0.8f * glm::vec2{-u.y, u.x}; });
    double rMin = 1.0, rMax = 0.0;
    for (int f = 0; f < 60; ++f) {
        s.world.step(kFrame);
        for (size_t k = 0; k < s.handles.size(); ++k) {
            rMin = std::min(rMin, length(s.x(k)));
            rMax = std::max(rMax, length(s.x(k)));
        }
    }
    std::printf("[measure] vortex with pull V^2/R: ring radius %.5f..%.5f m over 1 s (0.3)\n", rMin,
                rMax);
    CHECK(rMin > 0.3 * 0.99);
    CHECK(rMax < 0.3 * 1.01);
}

// ---- wind ------------------------------------------------------------------------------------

TEST_CASE("wind: exact exponential drag towards the wind, region only", "[unit][forces]") {
    WindForce w({2.0f, -1.0f}, 3.0f);
    const glm::vec2 v0{0.5f, 0.5f};
    const glm::dvec2 a = accelAt(w, {0.0f, 0.0f}, v0);
    CHECK(a.x == Approx(3.0 * 1.5));
    CHECK(a.y == Approx(3.0 * -1.5));
    const float dt = 1.0f / 240.0f;
    const glm::dvec2 b = accelAt(w, {0.0f, 0.0f}, v0, dt);
    CHECK(b.x == Approx(lambdaOf(3.0, dt) * 1.5).epsilon(1e-5));
    CHECK(b.y == Approx(lambdaOf(3.0, dt) * -1.5).epsilon(1e-5));
    CHECK(accelAt(w, {0.0f, 0.0f}, {2.0f, -1.0f}, dt) == glm::dvec2{0.0, 0.0}); // at the wind
    // A huge rate reaches the wind in one sub-step without overshooting it.
    w.setParam("rate", 1e4);
    const glm::dvec2 h = accelAt(w, {0.0f, 0.0f}, v0, 1.0f / 60.0f);
    CHECK(v0.x + h.x / 60.0 == Approx(2.0).epsilon(1e-5));
    CHECK(v0.y + h.y / 60.0 == Approx(-1.0).epsilon(1e-5));
    // Region [0, 1] x [0, 1], edges included.
    w.setParam("rate", 3.0);
    for (const char* key : {"minX", "minY"}) {
        w.setParam(key, 0.0);
    }
    for (const char* key : {"maxX", "maxY"}) {
        w.setParam(key, 1.0);
    }
    CHECK(length(accelAt(w, {0.5f, 0.5f})) > 0.0);
    CHECK(length(accelAt(w, {1.0f, 0.0f})) > 0.0);
    CHECK(accelAt(w, {1.01f, 0.5f}) == glm::dvec2{0.0, 0.0});
    CHECK(accelAt(w, {0.5f, -0.01f}) == glm::dvec2{0.0, 0.0});
}

TEST_CASE("wind: velocities relax to the wind as exp(-k t), terminal velocity under gravity",
          "[unit][forces]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    SECTION("relaxation, and nothing outside the region") {
        Scene s(solver);
        auto& w = s.add(std::make_unique<WindForce>(glm::vec2{1.5f, 0.5f}, 2.0f));
        w.setParam("minX", -5.0);
        w.setParam("maxX", 5.0);
        const std::array<glm::vec2, 3> v0{{{0.0f, 0.0f}, {2.0f, -1.0f}, {-1.0f, 3.0f}}};
        for (int k = 0; k < 3; ++k) {
            s.add({0.0f, -2.0f + 2.0f * float(k)}, v0[k]);
        }
        const ParticleHandle outside = s.add({8.0f, 0.0f}, {0.0f, 0.0f});
        s.frames(30);
        const glm::dvec2 wind{1.5, 0.5};
        const double expected = std::exp(-2.0 * 0.5);
        for (int k = 0; k < 3; ++k) {
            CAPTURE(k);
            const double ratio = length(s.v(size_t(k)) - wind) / length(glm::dvec2(v0[k]) - wind);
            std::printf("[measure] wind (%s): |v - w| / |v0 - w| = %.6f after 0.5 s "
                        "(exp(-k t) = %.6f)\n",
                        solverLabel(solver), ratio, expected);
            CHECK(ratio == Approx(expected).epsilon(1e-3));
            // The error shrinks along its own direction (the drag is linear).
            CHECK(std::fabs(cross(s.v(size_t(k)) - wind, glm::dvec2(v0[k]) - wind)) <
                  1e-4 * length(glm::dvec2(v0[k]) - wind));
        }
        CHECK(s.world.velocity(outside) == glm::vec2{0.0f, 0.0f});
        CHECK(s.world.position(outside) == glm::vec2{8.0f, 0.0f});
    }
    SECTION("with gravity the terminal velocity is w + g / k") {
        Scene s(solver);
        s.add(std::make_unique<GravityForce>(0.0f, -9.81f));
        s.add(std::make_unique<WindForce>(glm::vec2{1.0f, 0.0f}, 5.0f));
        s.add({0.0f, 0.0f});
        s.frames(120); // 10 time constants
        // The discrete balance g = lambda (v - w) with the sub-step's lambda = (1 - exp(-k dt))
        // / dt (k (1 - k dt / 2) to first order): the exact exponential drag is slightly weaker
        // than k against a constant force.
        const double h = double(kFrame) / s.world.lastSubsteps();
        const double terminal = -9.81 / lambdaOf(5.0, h);
        std::printf("[measure] wind + gravity (%s): terminal vy %.5f m/s, discrete w + g / "
                    "lambda %.5f, continuous w + g / k %.5f\n",
                    solverLabel(solver), s.v(0).y, terminal, -9.81 / 5.0);
        CHECK(s.v(0).x == Approx(1.0).epsilon(1e-4));
        CHECK(s.v(0).y == Approx(terminal).epsilon(1e-3));
        CHECK(s.v(0).y == Approx(-9.81 / 5.0).epsilon(0.015));
    }
}

// ---- pointer ---------------------------------------------------------------------------------

TEST_CASE("pointer: push and pull inside the radius, nothing beyond or when inactive",
          "[unit][forces]") {
    const glm::vec2 c{0.4f, -0.2f};
    const float radius = 0.3f;
    PointerForce p(radius, 20.0f);
    p.setPointer(c, 1.0f);
    const double peakR = radius / std::sqrt(5.0);
    for (const double angle : {0.0, 1.0, 2.5, 4.0}) {
        const glm::vec2 u{float(std::cos(angle)), float(std::sin(angle))};
        CAPTURE(angle);
        const glm::dvec2 a = accelAt(p, c + float(peakR) * u);
        CHECK(dot(a, glm::dvec2(u)) > 0.0); // away from the pointer
        CHECK(std::fabs(cross(a, glm::dvec2(u))) <= 1e-5 * length(a));
        CHECK(length(a) == Approx(20.0).epsilon(1e-4)); // the peak is the strength
        // Smaller everywhere else; eases to 0 at the radius.
        for (const double q : {0.05, 0.2, 0.6, 0.9, 0.99}) {
            CHECK(length(accelAt(p, c + float(q * radius) * u)) < 20.0);
        }
        CHECK(length(accelAt(p, c + 0.99f * radius * u)) < 0.02 * 20.0);
        CHECK(accelAt(p, c + 1.001f * radius * u) == glm::dvec2{0.0, 0.0});
        CHECK(accelAt(p, c + 5.0f * u) == glm::dvec2{0.0, 0.0});
    }
    CHECK(accelAt(p, c) == glm::dvec2{0.0, 0.0}); // safe on the pointer
    const glm::vec2 probe = c + glm::vec2{0.1f, 0.05f};
    const glm::dvec2 push = accelAt(p, probe);
    p.setParam("strength", -20.0);
    const glm::dvec2 pull = accelAt(p, probe);
    CHECK(dot(pull, glm::dvec2(0.1, 0.05)) < 0.0); // towards the pointer
    CHECK(pull.x == Approx(-push.x));
    CHECK(pull.y == Approx(-push.y));
    p.setParam("active", 0.5);
    CHECK(accelAt(p, probe).x == Approx(0.5 * pull.x));
    // Inactive: the accumulators are not touched at all.
    p.setParam("active", 0.0);
    Bench b;
    b.add(probe);
    b.ax[0] = 1.25f;
    p.apply(b.context(1.0f / 240.0f), 0, 1);
    CHECK(b.ax[0] == 1.25f);
    CHECK(b.ay[0] == 0.0f);
}

TEST_CASE("pointer in a world: push moves particles away, pull draws them in", "[unit][forces]") {
    const glm::vec2 c{0.2f, 0.3f};
    // 8 lone particles 0.1 m from the pointer and one at 0.4 m (beyond the 0.25 m radius).
    auto run = [&](float strength, float active, std::vector<double>& dist, glm::dvec2& far,
                   int frames) {
        Scene s;
        auto& p = s.add(std::make_unique<PointerForce>(0.25f, strength));
        p.setPointer(c, active);
        s.ring(c, 0.1f, 8);
        s.add(c + glm::vec2{0.4f, 0.0f});
        s.frames(frames);
        for (size_t k = 0; k < 8; ++k) {
            dist.push_back(length(s.x(k) - glm::dvec2(c.x, c.y)));
        }
        far = s.x(8);
        CHECK(s.v(8) == glm::dvec2{0.0, 0.0});
        CHECK(length(momentum(s.world)) < 1e-5 * 8 * s.mass());
    };
    const glm::dvec2 farStart{c.x + 0.4f, c.y};
    std::vector<double> pushed, pulled, idle;
    glm::dvec2 far;
    run(10.0f, 1.0f, pushed, far, 10);
    CHECK(far == farStart);
    run(-10.0f, 1.0f, pulled, far, 5);
    run(10.0f, 0.0f, idle, far, 10);
    for (size_t k = 0; k < 8; ++k) {
        CAPTURE(k);
        CHECK(pushed[k] > 0.1 + 0.01);
        CHECK(pulled[k] < 0.1 - 0.005);
        CHECK(idle[k] == Approx(0.1).epsilon(1e-6)); // active = 0: nothing moves
    }
    std::printf("[measure] pointer: distance 0.1 m -> %.4f m after 10 frames of push (10 m/s^2), "
                "%.4f m after 5 frames of pull\n",
                pushed[0], pulled[0]);
}

TEST_CASE("pointer: a particle follows a pull pointer the host moves each frame",
          "[unit][forces]") {
    Scene s;
    auto& p = s.add(std::make_unique<PointerForce>(0.2f, -30.0f));
    s.add(std::make_unique<DampingZoneForce>(4.0f, glm::vec2{-10.0f, -10.0f},
                                             glm::vec2{10.0f, 10.0f}));
    s.add({0.0f, 0.0f});
    double worst = 0.0;
    for (int f = 0; f < 60; ++f) {
        const glm::vec2 mouse{0.5f * float(f) * kFrame, 0.0f}; // 0.5 m/s along x
        p.setPointer(mouse, 1.0f);
        s.world.step(kFrame);
        worst = std::max(worst, length(s.x(0) - glm::dvec2(mouse.x, mouse.y)));
    }
    std::printf("[measure] pointer drag at 0.5 m/s: particle at most %.4f m from the pointer, "
                "x = %.4f m after 1 s\n",
                worst, s.x(0).x);
    CHECK(worst < 0.2);          // it never escaped the pointer's reach
    CHECK(s.x(0).x > 0.5 - 0.2); // it came along
}

// ---- explosion -------------------------------------------------------------------------------

TEST_CASE("explosion: fires once, radially, in the first sub-step only", "[unit][forces]") {
    const glm::vec2 c{0.3f, 0.1f};
    ExplosionForce e(c, 0.5f, 2.0f);
    Bench b;
    b.add(c + glm::vec2{0.2f, 0.0f});   // q = 0.4: dv = 2 (1 - 0.16)^2
    b.add(c + glm::vec2{-0.1f, 0.1f});  // q^2 = 0.08
    b.add(c + glm::vec2{0.0f, 0.6f});   // beyond the radius
    b.add(c);                           // on the centre
    b.add(c + glm::vec2{0.0f, 0.002f}); // inside the core c = spacing / 2 = 0.005 m
    const float dt = 1.0f / 240.0f;
    const StepContext step{1.0f / 60.0f, 1.5, 0.01f, 0.032f};

    // Not triggered: nothing.
    e.prepare(step);
    CHECK_FALSE(e.armed());
    b.run(e, dt, 1.5);
    CHECK(b.a(0) == glm::dvec2{0.0, 0.0});
    e.finish(step);

    e.fire();
    CHECK(e.param("trigger") == 1.0);
    e.prepare(step);
    CHECK(e.armed());
    b.run(e, dt, 1.5); // the first sub-step starts at the step's time
    CHECK(b.a(0).x * dt == Approx(2.0 * 0.84 * 0.84).epsilon(1e-5));
    CHECK(b.a(0).y == 0.0);
    const glm::dvec2 dv1 = b.a(1) * double(dt);
    const double q2 = (0.1 * 0.1 + 0.1 * 0.1) / 0.25;
    CHECK(length(dv1) == Approx(2.0 * (1 - q2) * (1 - q2)).epsilon(1e-4));
    CHECK(dv1.x == Approx(-dv1.y).epsilon(1e-4)); // along (-1, 1): radial
    CHECK(b.a(2) == glm::dvec2{0.0, 0.0});
    CHECK(b.a(3) == glm::dvec2{0.0, 0.0});
    // Fading linearly inside the core (0.002 of 0.005 m), still radial.
    const double q4 = 0.002 * 0.002 / 0.25;
    CHECK(b.a(4).y * dt == Approx(2.0 * (1 - q4) * (1 - q4) * 0.4).epsilon(1e-4));
    CHECK(b.a(4).x == 0.0);
    // The step's later sub-steps: nothing.
    b.run(e, dt, 1.5 + dt);
    CHECK(b.a(0) == glm::dvec2{0.0, 0.0});
    e.finish(step);
    CHECK_FALSE(e.armed());
    CHECK(e.param("trigger") == 0.0); // reset by the plugin
    // The next step: nothing.
    e.prepare(StepContext{1.0f / 60.0f, 1.5 + 1.0 / 60.0, 0.01f, 0.032f});
    b.run(e, dt, 1.5 + 1.0 / 60.0);
    CHECK(b.a(0) == glm::dvec2{0.0, 0.0});
    // Negative impulse implodes.
    e.setParam("impulse", -2.0);
    e.fire();
    e.prepare(step);
    b.run(e, dt, 1.5);
    CHECK(b.a(0).x * dt == Approx(-2.0 * 0.84 * 0.84).epsilon(1e-5));
}

TEST_CASE("explosion in a world: one kick of the chosen falloff, zero net momentum",
          "[unit][forces]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    const glm::vec2 c{0.3f, 0.1f};
    Scene s(solver);
    auto& e = s.add(std::make_unique<ExplosionForce>(c, 0.5f, 2.0f));
    s.ring(c, 0.2f, 12);              // q = 0.4
    s.ring(c, 0.35f, 12);             // q = 0.7
    s.add(c + glm::vec2{0.6f, 0.0f}); // beyond the radius
    s.frames(1); // the explicit solver's first step probes the field: fire on a later step
    e.fire();
    s.world.step(kFrame);
    CHECK(e.param("trigger") == 0.0);
    const glm::dvec2 cd{c.x, c.y};
    const double expected[2] = {2.0 * 0.84 * 0.84, 2.0 * 0.51 * 0.51};
    std::vector<glm::dvec2> after(s.handles.size());
    for (size_t k = 0; k < 24; ++k) {
        CAPTURE(k);
        const glm::dvec2 r = s.x(k) - cd;
        const glm::dvec2 v = s.v(k);
        CHECK(length(v) == Approx(expected[k / 12]).epsilon(1e-4));
        CHECK(std::fabs(cross(r, v)) <= 1e-4 * length(r) * length(v)); // radial
        CHECK(dot(r, v) > 0.0);
        after[k] = v;
    }
    CHECK(s.v(24) == glm::dvec2{0.0, 0.0});
    const double scale = 24 * s.mass() * expected[0];
    std::printf("[measure] explosion (%s): ring speeds %.5f and %.5f m/s (expected %.5f, %.5f), "
                "|P| / sum m|v| = %.2e\n",
                solverLabel(solver), length(s.v(0)), length(s.v(12)), expected[0], expected[1],
                length(momentum(s.world)) / scale);
    CHECK(length(momentum(s.world)) < 1e-5 * scale);
    // The next step adds nothing: lone particles coast.
    s.world.step(kFrame);
    for (size_t k = 0; k < 24; ++k) {
        CHECK(s.v(k).x == Approx(after[k].x).margin(1e-6));
        CHECK(s.v(k).y == Approx(after[k].y).margin(1e-6));
    }
}

TEST_CASE("explosion centred on a blob keeps its net momentum ~0", "[unit][forces]") {
    Scene s;
    BlobDef blob;
    blob.shape.type = ShapeType::Circle;
    blob.shape.radius = 0.08f;
    blob.material = s.water;
    const uint32_t n = s.world.spawnBlob(blob);
    REQUIRE(n > 50);
    auto& e = s.add(std::make_unique<ExplosionForce>(glm::vec2{0.0f, 0.0f}, 0.2f, 1.5f));
    s.world.step(kFrame); // settle one step first
    const glm::dvec2 p0 = momentum(s.world);
    e.fire();
    s.world.step(kFrame);
    double speedSum = 0.0;
    const auto vx = s.world.velocityX(), vy = s.world.velocityY();
    for (uint32_t i = 0; i < n; ++i) {
        speedSum += s.mass() * std::hypot(double(vx[i]), double(vy[i]));
    }
    const glm::dvec2 p1 = momentum(s.world);
    std::printf("[measure] explosion on a %u-particle blob: |P| %.2e -> %.2e kg m/s, sum m|v| "
                "%.3e (ratio %.2e)\n",
                n, length(p0), length(p1), speedSum, length(p1) / speedSum);
    CHECK(speedSum > 0.1 * n * s.mass()); // it did blow up
    CHECK(length(p1) < 1e-4 * speedSum);
    CHECK(allFinite(s.world));
}

// ---- damping zone ------------------------------------------------------------------------------

TEST_CASE("damping zone: exact exponential decay inside, nothing outside", "[unit][forces]") {
    DampingZoneForce d(2.0f, {0.0f, 0.0f}, {1.0f, 1.0f});
    const glm::vec2 v{1.0f, -3.0f};
    const float dt = 1.0f / 240.0f;
    const glm::dvec2 a = accelAt(d, {0.5f, 0.5f}, v, dt);
    CHECK(a.x == Approx(-lambdaOf(2.0, dt) * 1.0).epsilon(1e-5));
    CHECK(a.y == Approx(-lambdaOf(2.0, dt) * -3.0).epsilon(1e-5));
    CHECK(accelAt(d, {0.5f, 0.5f}, v).x == Approx(-2.0)); // dt = 0: -c v
    CHECK(accelAt(d, {1.5f, 0.5f}, v, dt) == glm::dvec2{0.0, 0.0});
    // Never reverses a velocity, however strong.
    d.setParam("rate", 1e4);
    const glm::dvec2 h = accelAt(d, {0.5f, 0.5f}, v, 1.0f / 60.0f);
    CHECK(v.x + h.x / 60.0 == Approx(0.0).margin(1e-6));
    CHECK(v.y + h.y / 60.0 == Approx(0.0).margin(1e-6));
}

TEST_CASE("damping zone: kinetic energy inside decays as exp(-2 c t)", "[unit][forces]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    Scene s(solver);
    s.add(std::make_unique<DampingZoneForce>(1.5f, glm::vec2{-2.0f, -2.0f}, glm::vec2{2.0f, 2.0f}));
    const std::array<glm::vec2, 4> v0{{{0.5f, 0.0f}, {-0.3f, 0.4f}, {0.0f, -0.6f}, {0.2f, 0.2f}}};
    double ke0 = 0.0;
    for (int k = 0; k < 4; ++k) {
        s.add({-1.0f + 0.6f * float(k), 0.0f}, v0[k]);
        ke0 += 0.5 * s.mass() * dot(glm::dvec2(v0[k]), glm::dvec2(v0[k]));
    }
    const ParticleHandle outside = s.add({3.0f, 0.0f}, {0.0f, 0.1f});
    s.frames(30);
    double ke = 0.0;
    for (size_t k = 0; k < 4; ++k) {
        ke += 0.5 * s.mass() * dot(s.v(k), s.v(k));
        // Direction kept.
        CHECK(std::fabs(cross(s.v(k), glm::dvec2(v0[k]))) < 1e-5);
    }
    const double expected = std::exp(-2.0 * 1.5 * 0.5);
    std::printf("[measure] damping (%s): KE ratio %.6f after 0.5 s (exp(-2 c t) = %.6f)\n",
                solverLabel(solver), ke / ke0, expected);
    CHECK(ke / ke0 == Approx(expected).epsilon(1e-3));
    CHECK(s.world.velocity(outside) == glm::vec2{0.0f, 0.1f}); // untouched
}

// ---- all of them -----------------------------------------------------------------------------

TEST_CASE("registry lists every built-in force with its parameters", "[unit][forces]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    struct Expected {
        std::string_view type;
        std::span<const ParamDecl> params;
    };
    const std::array<Expected, 7> expected{{
        {GravityForce::kType, GravityForce::kParams},
        {PointGravityForce::kType, PointGravityForce::kParams},
        {VortexForce::kType, VortexForce::kParams},
        {WindForce::kType, WindForce::kParams},
        {PointerForce::kType, PointerForce::kParams},
        {ExplosionForce::kType, ExplosionForce::kParams},
        {DampingZoneForce::kType, DampingZoneForce::kParams},
    }};
    const std::array<std::string_view, 7> names{
        "force.gravity", "force.point_gravity", "force.vortex", "force.wind",
        "force.pointer", "force.explosion",     "force.damping"};
    for (size_t k = 0; k < expected.size(); ++k) {
        CAPTURE(names[k]);
        CHECK(expected[k].type == names[k]);
        const PluginInfo* info = registry.find(names[k]);
        REQUIRE(info != nullptr);
        CHECK(info->kind == PluginKind::Force);
        CHECK_FALSE(info->description.empty());
        REQUIRE(info->params.size() == expected[k].params.size());
        std::unique_ptr<ForcePlugin> plugin = registry.createForce(names[k]);
        CHECK(plugin->type() == names[k]);
        for (size_t i = 0; i < info->params.size(); ++i) {
            const ParamDecl& d = info->params[i];
            CAPTURE(d.name);
            CHECK(d.name == expected[k].params[i].name);
            CHECK_FALSE(d.unit.empty());
            CHECK_FALSE(d.description.empty());
            CHECK(std::isfinite(d.minValue));
            CHECK(std::isfinite(d.maxValue));
            CHECK(d.minValue < d.maxValue);
            CHECK(plugin->param(d.name) == d.defaultValue);
        }
    }
    // Forces come first, in this order.
    for (size_t k = 0; k < names.size(); ++k) {
        CHECK(registry.types()[k].type == names[k]);
    }
    // Created by name with values, as a level file does.
    const std::vector<ParamValue> values{{"x", 1.0}, {"speed", -2.0}, {"pull", 3.0}};
    std::unique_ptr<ForcePlugin> vortex = registry.createForce("force.vortex", values);
    CHECK(vortex->param("x") == 1.0);
    CHECK(vortex->param("speed") == -2.0);
    CHECK(vortex->param("pull") == 3.0);
    CHECK(vortex->param("radius") == 0.2);
}

TEST_CASE("force parameters: exact errors for bad values", "[unit][forces]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    auto message = [&](std::string_view type, const char* key, double value) {
        std::unique_ptr<ForcePlugin> plugin = registry.createForce(type);
        try {
            plugin->setParam(key, value);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    CHECK(message("force.vortex", "radius", -1.0) ==
          "plugin 'force.vortex': parameter 'radius' = -1 is out of range [0.001, 10000] "
          "(unit: m)");
    CHECK(message("force.point_gravity", "falloff", 4.0) ==
          "plugin 'force.point_gravity': parameter 'falloff' = 4 is out of range [0, 3] "
          "(unit: 1)");
    CHECK(message("force.point_gravity", "softening", -0.5) ==
          "plugin 'force.point_gravity': parameter 'softening' = -0.5 is out of range [0, "
          "10000] (unit: m)");
    CHECK(message("force.wind", "rate", std::nan("")) ==
          "plugin 'force.wind': parameter 'rate' = nan is not finite; expected [0, 10000] "
          "(unit: 1/s)");
    CHECK(message("force.wind", "vx", INFINITY) ==
          "plugin 'force.wind': parameter 'vx' = inf is not finite; expected [-1000, 1000] "
          "(unit: m/s)");
    CHECK(message("force.pointer", "active", 2.0) ==
          "plugin 'force.pointer': parameter 'active' = 2 is out of range [0, 1] (unit: 1)");
    CHECK(message("force.pointer", "strength", -2e4) ==
          "plugin 'force.pointer': parameter 'strength' = -20000 is out of range [-10000, "
          "10000] (unit: m/s^2)");
    CHECK(message("force.explosion", "impulse", 5000.0) ==
          "plugin 'force.explosion': parameter 'impulse' = 5000 is out of range [-1000, 1000] "
          "(unit: m/s)");
    CHECK(message("force.explosion", "trigger", -1.0) ==
          "plugin 'force.explosion': parameter 'trigger' = -1 is out of range [0, 1] (unit: 1)");
    CHECK(message("force.damping", "rate", -0.1) ==
          "plugin 'force.damping': parameter 'rate' = -0.1 is out of range [0, 10000] "
          "(unit: 1/s)");
    CHECK(message("force.damping", "maxX", 2e6) ==
          "plugin 'force.damping': parameter 'maxX' = 2e+06 is out of range [-1e+06, 1e+06] "
          "(unit: m)");
    CHECK(message("force.vortex", "centre", 0.0) ==
          "plugin 'force.vortex': unknown parameter 'centre'; known: x y speed radius rate pull "
          "cutoff");
    // A rejected value leaves the old one.
    std::unique_ptr<ForcePlugin> v = registry.createForce("force.vortex");
    CHECK_THROWS_AS(v->setParam("radius", 0.0), Error);
    CHECK(v->param("radius") == 0.2);
}

namespace {
// Every built-in force (other than uniform gravity) created through the registry, made to act:
// the pointer active, the explosion armed for a step starting at `kStart`.
constexpr double kStart = 2.0;
const std::array<std::string_view, 6> kForceTypes{"force.point_gravity", "force.vortex",
                                                  "force.wind",          "force.pointer",
                                                  "force.explosion",     "force.damping"};
void makeActive(ForcePlugin& f) {
    if (f.type() == "force.pointer") {
        f.setParam("active", 1.0);
    }
    if (f.type() == "force.explosion") {
        f.setParam("trigger", 1.0);
        f.prepare(StepContext{1.0f / 60.0f, kStart, 0.01f, 0.032f});
    }
}
} // namespace

TEST_CASE("forces write only their range, and any split of it gives the same bits",
          "[unit][forces]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> pos(-0.3f, 0.3f), vel(-2.0f, 2.0f);
    Bench b;
    for (int k = 0; k < 50; ++k) {
        const glm::vec2 at{pos(rng), pos(rng)}; // braces: drawn left to right
        b.add(at, {vel(rng), vel(rng)});
    }
    const float dt = 1.0f / 240.0f;
    for (const std::string_view type : kForceTypes) {
        CAPTURE(type);
        std::unique_ptr<ForcePlugin> f = registry.createForce(type);
        makeActive(*f);
        b.run(*f, dt, kStart);
        const std::vector<float> wholeX = b.ax, wholeY = b.ay;
        int touched = 0;
        for (size_t i = 0; i < wholeX.size(); ++i) {
            touched += wholeX[i] != 0.0f || wholeY[i] != 0.0f;
        }
        CHECK(touched > 10); // the field acts on this cloud
        std::fill(b.ax.begin(), b.ax.end(), 0.0f);
        std::fill(b.ay.begin(), b.ay.end(), 0.0f);
        const ForceContext ctx = b.context(dt, kStart);
        f->apply(ctx, 17, 33);
        for (uint32_t i = 0; i < b.size(); ++i) {
            if (i < 17 || i >= 33) {
                CHECK(b.ax[i] == 0.0f);
                CHECK(b.ay[i] == 0.0f);
            }
        }
        f->apply(ctx, 0, 17);
        f->apply(ctx, 33, 50);
        CHECK(b.ax == wholeX);
        CHECK(b.ay == wholeY);
    }
}

TEST_CASE("forces stay finite for extreme parameters and positions", "[unit][forces]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    Bench b;
    // On centres, next to them, far away, with large velocities.
    for (const float x : {0.0f, 1e-38f, 1e-20f, 1e-7f, 1e-3f, 0.3f, 1e5f, -1e5f}) {
        for (const float y : {0.0f, 1e-30f, -0.3f, 1e5f}) {
            b.add({x, y}, {1e3f, -1e3f});
        }
    }
    std::mt19937 rng(11);
    int combos = 0;
    for (const std::string_view type : kForceTypes) {
        CAPTURE(type);
        std::unique_ptr<ForcePlugin> f = registry.createForce(type);
        const std::span<const ParamDecl> decls = f->params();
        for (int trial = 0; trial < 300; ++trial) {
            // Each parameter at its minimum, maximum, 0 (where allowed) or its default.
            for (const ParamDecl& d : decls) {
                double choice[4] = {d.minValue, d.maxValue, d.defaultValue, d.defaultValue};
                if (d.minValue <= 0.0 && 0.0 <= d.maxValue) {
                    choice[3] = 0.0;
                }
                f->setParam(d.name, choice[rng() % 4]);
            }
            makeActive(*f);
            for (const float dt : {0.0f, 1e-6f, 1.0f / 240.0f, 1.0f}) {
                b.run(*f, dt, kStart);
                bool finite = true;
                for (uint32_t i = 0; i < b.size(); ++i) {
                    finite = finite && std::isfinite(b.ax[i]) && std::isfinite(b.ay[i]);
                }
                if (!finite) {
                    std::ostringstream s;
                    for (const ParamDecl& d : decls) {
                        s << d.name << '=' << f->param(d.name) << ' ';
                    }
                    FAIL_CHECK("non-finite acceleration with " << s.str() << "dt=" << dt);
                }
                ++combos;
            }
        }
    }
    std::printf("[measure] finiteness: %d parameter/step combinations x %u particles, all "
                "finite\n",
                combos, b.size());
}

TEST_CASE("explosion state round-trips through saveState/restoreState", "[unit][forces]") {
    const StepContext step{1.0f / 60.0f, 4.25, 0.01f, 0.032f};
    ExplosionForce a({0.1f, 0.0f}, 0.4f, 1.0f);
    a.fire();
    a.prepare(step);
    StateWriter out;
    a.saveState(out);

    ExplosionForce b({0.1f, 0.0f}, 0.4f, 1.0f);
    b.setParam("trigger", 1.0); // parameters are restored by the world before the state
    StateReader in(out.bytes());
    b.restoreState(in);
    CHECK(in.remaining() == 0);
    CHECK(b.armed());
    Bench ba, bb;
    for (const glm::vec2 x : {glm::vec2{0.2f, 0.1f}, glm::vec2{-0.1f, 0.05f}}) {
        ba.add(x);
        bb.add(x);
    }
    const float dt = 1.0f / 240.0f;
    // Without prepare: the restored plugin fires in the same sub-step, with the same bits.
    ba.run(a, dt, 4.25);
    bb.run(b, dt, 4.25);
    CHECK(ba.ax == bb.ax);
    CHECK(ba.ay == bb.ay);
    CHECK(ba.ax[0] != 0.0f);
    ba.run(a, dt, 4.25 + dt);
    bb.run(b, dt, 4.25 + dt);
    CHECK(bb.ax[0] == 0.0f);
    b.finish(step);
    CHECK(b.param("trigger") == 0.0);

    // Bad state.
    std::vector<std::byte> bad(sizeof(uint8_t) + 2 * sizeof(double), std::byte{0});
    bad[0] = std::byte{7};
    StateReader badReader(bad);
    ExplosionForce c;
    CHECK_THROWS_WITH(c.restoreState(badReader),
                      "plugin 'force.explosion': bad snapshot state (armed = 7, step start = "
                      "0.000000 s, core = 0.000000 m; expected armed 0 or 1, a finite time and "
                      "a core in [0, 10000] m)");
    const std::vector<std::byte> shortState(3, std::byte{0});
    StateReader shortReader(shortState);
    CHECK_THROWS_AS(c.restoreState(shortReader), Error);
}

TEST_CASE("a world with every force continues bit-identically from a snapshot", "[unit][forces]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    Scene s;
    BlobDef blob;
    blob.shape.type = ShapeType::Circle;
    blob.shape.radius = 0.06f;
    blob.material = s.water;
    blob.shape.center = {0.05f, 0.02f};
    REQUIRE(s.world.spawnBlob(blob) > 20);
    const std::vector<ParamValue> gravity{{"x", 0.0}, {"y", -0.3}, {"strength", 3.0}};
    s.world.addForce(registry.createForce("force.point_gravity", gravity));
    s.world.addForce(registry.createForce("force.vortex"));
    const std::vector<ParamValue> wind{{"vx", 0.3}, {"rate", 0.5}, {"minY", 0.0}};
    s.world.addForce(registry.createForce("force.wind", wind));
    const std::vector<ParamValue> pointer{{"x", 0.1}, {"active", 1.0}};
    s.world.addForce(registry.createForce("force.pointer", pointer));
    const std::vector<ParamValue> boom{{"x", 0.0}, {"y", 0.05}, {"impulse", 0.5}};
    s.world.addForce(registry.createForce("force.explosion", boom));
    const std::vector<ParamValue> damping{{"rate", 0.2}, {"maxX", 0.0}};
    s.world.addForce(registry.createForce("force.damping", damping));
    s.frames(3);
    // Armed but not yet fired at the snapshot: the loaded world must fire it too.
    s.world.forces()[4]->setParam("trigger", 1.0);
    std::stringstream snapshot;
    s.world.save(snapshot);
    World loaded = World::load(snapshot, registry);
    REQUIRE(loaded.forces().size() == 6);
    CHECK(loaded.forces()[4]->param("trigger") == 1.0);
    for (int f = 0; f < 5; ++f) {
        s.world.step(kFrame);
        loaded.step(kFrame);
        CAPTURE(f);
        CHECK(stateHash(loaded) == stateHash(s.world));
    }
    CHECK(loaded.forces()[4]->param("trigger") == 0.0);
    CHECK(allFinite(loaded));
}

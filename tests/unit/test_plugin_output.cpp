// What the world does with plugin output that is not usable: boundary samples that are not
// finite (the step is refused, the world unchanged, the plugin named), a `project` that writes
// a non-finite position or velocity (that particle keeps what it had before the plugin, the
// plugin is counted and named), and a force plugin's finite but huge acceleration (the particle
// moves at the speed cap along it). docs/plugins.md, "Output that is not finite".
#include "test_support.h"

#include <catch2/catch.hpp>

#include <limits>

using namespace fluid;
using namespace fluid::test;

namespace {

// A disc-shaped solid at the tank's centre whose output a test breaks in one way.
enum class Fault {
    None,           // the same samples, project moves nothing
    SampleX,        // one sample at x = NaN
    SampleVelocity, // one sample with a NaN velocity
    SampleInf,      // one sample at y = infinity
    ProjectOneX,    // project writes NaN into one particle's x
    ProjectOneV,    // project writes NaN into one particle's velocity
    ProjectAll,     // project writes NaN into every particle of its range
    ProjectInf,     // project writes infinity into every particle's position
};

class FaultyBoundary final : public BoundaryPlugin {
public:
    static constexpr std::array<ParamDecl, 0> kParams{};
    explicit FaultyBoundary(Fault fault)
        : BoundaryPlugin("boundary.test-faulty", kParams), m_fault(fault) {}
    void prepare(const StepContext& ctx) override {
        m_samples.clear();
        const float s = ctx.sampleSpacing;
        for (int k = 0; k < 8; ++k) {
            m_samples.add(-0.2f + float(k) * s, 0.3f);
        }
        switch (m_fault) {
        case Fault::SampleX:
            m_samples.px[3] = kNaN;
            break;
        case Fault::SampleVelocity:
            m_samples.vy[5] = kNaN;
            break;
        case Fault::SampleInf:
            m_samples.py[0] = kInf;
            break;
        default:
            break;
        }
    }
    void project(const ProjectContext& ctx, uint32_t begin, uint32_t end) override {
        for (uint32_t i = begin; i < end; ++i) {
            switch (m_fault) {
            case Fault::ProjectOneX:
                if (i == 7) {
                    ctx.px[i] = kNaN; // a normal divided by zero
                }
                break;
            case Fault::ProjectOneV:
                if (i == 11) {
                    ctx.vx[i] = kNaN;
                    ctx.vy[i] = kNaN;
                }
                break;
            case Fault::ProjectAll:
                ctx.px[i] = ctx.py[i] = ctx.vx[i] = ctx.vy[i] = kNaN;
                break;
            case Fault::ProjectInf:
                ctx.px[i] = kInf;
                ctx.py[i] = -kInf;
                break;
            default:
                break;
            }
        }
    }

private:
    Fault m_fault;
};

struct State {
    std::vector<float> px, py, vx, vy;
    double time = 0.0;
    explicit State(const World& w)
        : px(w.positionX().begin(), w.positionX().end()),
          py(w.positionY().begin(), w.positionY().end()),
          vx(w.velocityX().begin(), w.velocityX().end()),
          vy(w.velocityY().begin(), w.velocityY().end()), time(w.time()) {}
    bool operator==(const State&) const = default;
};

// Water in a 0.6 m tank with gravity, the faulty boundary added after the tank.
World faultyTank(Solver solver, uint32_t workers, Fault fault) {
    WorldDef def;
    def.solver = solver;
    def.workerCount = workers;
    World world(def);
    const MaterialId w = world.addMaterial(water());
    world.addForce(std::make_unique<GravityForce>());
    world.addBoundary(std::make_unique<BoxContainer>(-0.3f, 0.0f, 0.3f, 0.6f));
    world.spawnBlob(latticeBlock(world, w, -0.3f, 0.0f, 40, 12));
    world.step(kFrame);
    world.addBoundary(std::make_unique<FaultyBoundary>(fault));
    return world;
}

// A uniform acceleration along x (a user's force plugin with a runaway value).
class ConstantForce final : public ForcePlugin {
public:
    static constexpr std::array<ParamDecl, 0> kParams{};
    explicit ConstantForce(float ax) : ForcePlugin("force.test-constant", kParams), m_ax(ax) {}
    void apply(const ForceContext& ctx, uint32_t begin, uint32_t end) override {
        for (uint32_t i = begin; i < end; ++i) {
            ctx.ax[i] += m_ax;
        }
    }

private:
    float m_ax;
};

float meanParticleX(const World& world) { // unit: m
    double sum = 0.0;
    for (const float x : world.positionX()) {
        sum += x;
    }
    return float(sum / double(world.particleCount()));
}

} // namespace

TEST_CASE("a boundary plugin's non-finite sample refuses the step and names the plugin",
          "[unit][bad-input][plugins]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    const uint32_t workers = GENERATE(1u, 2u);
    CAPTURE(solverLabel(solver), workers);
    Fault fault = Fault::SampleX;
    std::string message;
    SECTION("a sample at x = NaN") {
        fault = Fault::SampleX;
        message = "World::step: boundary plugin 1 ('boundary.test-faulty'): sample 3 at (nan, "
                  "0.3) with velocity (0, 0) is not finite; a boundary plugin's prepare must lay "
                  "finite samples";
    }
    SECTION("a sample with a NaN velocity") {
        fault = Fault::SampleVelocity;
        message = "World::step: boundary plugin 1 ('boundary.test-faulty'): sample 5 at (";
    }
    SECTION("a sample at y = infinity") {
        fault = Fault::SampleInf;
        message = "World::step: boundary plugin 1 ('boundary.test-faulty'): sample 0 at (-0.2, "
                  "inf) with velocity (0, 0) is not finite; a boundary plugin's prepare must "
                  "lay finite samples";
    }
    World world = faultyTank(solver, workers, fault);
    const State before(world);
    for (int attempt = 0; attempt < 2; ++attempt) {
        try {
            world.step(kFrame);
            FAIL("the step went through");
        } catch (const Error& e) {
            const std::string text = e.what();
            if (fault == Fault::SampleVelocity) {
                CHECK(text.rfind(message, 0) == 0);
                CHECK_THAT(text, Catch::Contains("with velocity (0, nan) is not finite"));
            } else {
                CHECK(text == message);
            }
        }
        CHECK(State(world) == before); // refused whole: nothing moved, the clock did not run
    }
}

TEST_CASE("a boundary plugin's project writing NaN or infinity keeps the particle as it was",
          "[unit][bad-input][plugins]") {
    // Two workers: the ranges the undo works on are split (one worker is the same code on one
    // range).
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    const uint32_t workers = 2;
    const Fault fault =
        GENERATE(Fault::ProjectOneX, Fault::ProjectOneV, Fault::ProjectAll, Fault::ProjectInf);
    CAPTURE(solverLabel(solver), workers, int(fault));
    World world = faultyTank(solver, workers, fault);
    const uint32_t count = world.particleCount();
    uint32_t dropped = 0;
    for (int frame = 0; frame < 5; ++frame) {
        CAPTURE(frame);
        REQUIRE_NOTHROW(world.step(kFrame));
        REQUIRE(allFinite(world));
        REQUIRE(world.particleCount() == count);
        REQUIRE(countOutside(world, -0.3f, 0.0f, 0.3f, 0.6f) == 0);
        dropped += world.profile().boundaryDropped;
        REQUIRE(world.profile().boundaryDroppedPlugin == 1); // the faulty one, not the tank (0)
    }
    if (fault == Fault::ProjectOneX || fault == Fault::ProjectOneV) {
        // One particle per call: two calls per position-based sub-step, one per explicit one.
        CHECK(dropped >= 5);
        CHECK(dropped <= 5 * 2 * 64);
    } else {
        CHECK(dropped >= 5 * count);
    }
    // Every move of a plugin that writes NaN or infinity everywhere is undone: the world is
    // bit for bit the one whose plugin lays the same samples and moves nothing.
    if (fault == Fault::ProjectAll || fault == Fault::ProjectInf) {
        World clean = faultyTank(solver, workers, Fault::None);
        for (int frame = 0; frame < 5; ++frame) {
            clean.step(kFrame);
        }
        CHECK(State(world) == State(clean));
        CHECK(clean.profile().boundaryDropped == 0);
    }
}

TEST_CASE("a force plugin's huge finite acceleration moves the particle at the speed cap",
          "[unit][bad-input][plugins]") {
    // 1e30 m/s^2 along x with gravity: the velocity's square overflowed a float, so the cap
    // scaled it to zero and the liquid froze in mid-air. The particles now move at the speed
    // cap along the sum of the accelerations (gravity is too small beside 1e30 to turn it) and
    // the tank's wall stops them.
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    const float huge = GENERATE(1e30f, -1e30f, std::numeric_limits<float>::max());
    CAPTURE(solverLabel(solver), huge);
    WorldDef def;
    def.solver = solver;
    World world(def);
    const MaterialId w = world.addMaterial(water());
    world.addForce(std::make_unique<GravityForce>());
    world.addForce(std::make_unique<ConstantForce>(huge));
    world.addBoundary(std::make_unique<BoxContainer>(-0.5f, 0.0f, 0.5f, 1.0f));
    world.spawnBlob(latticeBlock(world, w, -0.1f, 0.4f, 10, 10));
    std::vector<ParticleHandle> handles;
    std::vector<float> startX;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        handles.push_back(world.handleAt(i));
        startX.push_back(world.positionX()[i]);
    }
    world.step(kFrame);
    REQUIRE(allFinite(world));
    CHECK(world.profile().forceDropped == 0); // finite: used, not dropped
    CHECK(world.profile().boundaryDropped == 0);
    CHECK(world.profile().boundaryDroppedPlugin == -1);
    CHECK(world.profile().speedClamped > 0);
    // Every particle moved along the force by over a centimetre in the frame (the explicit
    // solver's many sub-steps take them to the wall already): none froze.
    uint32_t along = 0;
    for (size_t k = 0; k < handles.size(); ++k) {
        const float moved = world.position(handles[k]).x - startX[k];
        along += (huge > 0 ? moved > 0.01f : moved < -0.01f) ? 1u : 0u;
    }
    CHECK(along == world.particleCount());
    // Soon the liquid lies against the wall the force points to, inside the tank (the explicit
    // solver takes its 512 sub-steps a frame at this acceleration: it is there after one).
    const int frames = solver == Solver::Explicit ? 2 : 30;
    for (int frame = 0; frame < frames; ++frame) {
        world.step(kFrame);
    }
    REQUIRE(allFinite(world));
    CHECK(countOutside(world, -0.5f, 0.0f, 0.5f, 1.0f) == 0);
    CHECK((huge > 0 ? meanParticleX(world) > 0.4f : meanParticleX(world) < -0.4f));
}

// Plugins: hook order (a logging force plugin and a logging boundary plugin), registry
// creation with parameters, parameter declarations.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <string>

using namespace fluid;
using namespace fluid::test;

namespace {

struct Event {
    enum Kind { ForcePrepare, BoundaryPrepare, Apply, Project } kind;
    double time = 0.0;   // apply: ForceContext::time; prepare: StepContext::time
    float dt = 0.0f;     // apply / project: the sub-step; prepare: frameDt
    float inStep = 0.0f; // project: ProjectContext::timeInStep
    uint32_t begin = 0, end = 0;
};

// Serial worlds only: the log is not synchronised (apply and project run on the stepping
// thread when the world has one worker).
struct Log {
    std::vector<Event> events;
};

class LoggingForce final : public ForcePlugin {
public:
    static constexpr std::array<ParamDecl, 0> kParams{};
    explicit LoggingForce(Log& log) : ForcePlugin("force.test-log", kParams), m_log(log) {}
    void prepare(const StepContext& c) override {
        m_log.events.push_back({Event::ForcePrepare, c.time, c.frameDt, 0.0f, 0, 0});
    }
    void apply(const ForceContext& c, uint32_t begin, uint32_t end) override {
        m_log.events.push_back({Event::Apply, c.time, c.dt, 0.0f, begin, end});
        for (uint32_t i = begin; i < end; ++i) {
            c.ay[i] -= 9.81f;
        }
    }

private:
    Log& m_log;
};

class LoggingBoundary final : public BoundaryPlugin {
public:
    static constexpr std::array<ParamDecl, 0> kParams{};
    explicit LoggingBoundary(Log& log) : BoundaryPlugin("boundary.test-log", kParams), m_log(log) {}
    void prepare(const StepContext& c) override {
        m_log.events.push_back({Event::BoundaryPrepare, c.time, c.frameDt, 0.0f, 0, 0});
        // A floor of samples under y = 0, three layers deep.
        m_samples.clear();
        for (int l = 0; l < 3; ++l) {
            for (int k = -40; k <= 40; ++k) {
                m_samples.add(float(k) * c.sampleSpacing, -(float(l) + 0.5f) * c.sampleSpacing);
            }
        }
    }
    void project(const ProjectContext& c, uint32_t begin, uint32_t end) override {
        m_log.events.push_back({Event::Project, 0.0, c.dt, c.timeInStep, begin, end});
        for (uint32_t i = begin; i < end; ++i) {
            if (c.py[i] < 0.0f) {
                c.py[i] = 0.0f;
                c.vy[i] = std::max(c.vy[i], 0.0f);
            }
        }
    }

private:
    Log& m_log;
};

// Checks one step's events: both prepares first (once each), then per sub-step one apply over
// all particles followed by `projects` projects (the explicit solver projects once, after its
// move; the position-based one after predicting and at the end), with the sub-step's time and
// length. Sub-steps tile the frame exactly and are equal, except that a world deriving its
// sound speed opens its first step with one shorter probe sub-step (`probeFirst`).
void checkStep(const std::vector<Event>& ev, double t0, float frameDt, uint32_t substeps,
               uint32_t particles, bool probeFirst, uint32_t projects) {
    REQUIRE(substeps >= 1);
    CAPTURE(t0, substeps, ev.size(), probeFirst);
    size_t count[4] = {0, 0, 0, 0};
    for (const Event& e : ev) {
        ++count[e.kind];
    }
    CHECK(count[Event::ForcePrepare] == 1);
    CHECK(count[Event::BoundaryPrepare] == 1);
    CHECK(count[Event::Apply] == substeps);
    CHECK(count[Event::Project] == projects * substeps);
    const size_t perSubstep = 1 + projects;
    REQUIRE(ev.size() == 2 + perSubstep * size_t(substeps));
    CHECK(ev[0].kind == Event::ForcePrepare);
    CHECK(ev[1].kind == Event::BoundaryPrepare);
    for (int k = 0; k < 2; ++k) {
        CHECK(ev[k].time == Approx(t0));
        CHECK(ev[k].dt == frameDt);
    }
    const uint32_t equalFrom = probeFirst ? 1 : 0;
    REQUIRE(substeps > equalFrom);
    const double first = probeFirst ? double(ev[2].dt) : 0.0;
    if (probeFirst) {
        CHECK(ev[2].dt < frameDt / float(substeps)); // the probe is the shortest sub-step
    }
    const float h = float((double(frameDt) - first) / double(substeps - equalFrom));
    double elapsed = 0.0;
    for (uint32_t s = 0; s < substeps; ++s) {
        const Event& a = ev[2 + perSubstep * s];
        CAPTURE(s);
        REQUIRE(a.kind == Event::Apply);
        if (s >= equalFrom) {
            CHECK(a.dt == Approx(h));
        }
        CHECK(a.time == Approx(t0 + elapsed).margin(1e-9));
        CHECK(a.begin == 0);
        CHECK(a.end == particles);
        elapsed += double(a.dt);
        for (uint32_t k = 0; k < projects; ++k) {
            const Event& p = ev[3 + perSubstep * s + k];
            REQUIRE(p.kind == Event::Project);
            CHECK(p.dt == a.dt);
            CHECK(p.inStep == Approx(elapsed).margin(1e-7));
            CHECK(p.begin == 0);
            CHECK(p.end == particles);
        }
    }
    CHECK(elapsed == Approx(frameDt).margin(1e-7));
}

void runHookOrder(const WorldDef& def, bool probeFirst) {
    Log log;
    World world(def);
    const MaterialId w = world.addMaterial(water());
    world.addForce(std::make_unique<LoggingForce>(log));
    world.addBoundary(std::make_unique<LoggingBoundary>(log));
    world.spawnBlob(latticeBlock(world, w, -0.1f, 0.0f, 20, 10));
    const uint32_t n = world.particleCount();
    for (int step = 0; step < 3; ++step) {
        log.events.clear();
        const double t0 = world.time();
        world.step(kFrame);
        checkStep(log.events, t0, kFrame, world.lastSubsteps(), n, probeFirst && step == 0,
                  def.solver == Solver::PositionBased ? 2 : 1);
    }
    CHECK(allFinite(world));
}

} // namespace

TEST_CASE("hook order: prepare once per step, then apply and project per sub-step",
          "[unit][plugins]") {
    SECTION("position-based (the default): the set number of sub-steps") {
        WorldDef def;
        def.positionBased.substeps = 3;
        runHookOrder(def, false);
    }
    WorldDef def;
    def.solver = Solver::Explicit;
    SECTION("explicit, fixed sound speed") {
        def.soundSpeed = 15.0f;
        runHookOrder(def, false);
    }
    SECTION("explicit, sound speed derived from the scene") {
        runHookOrder(def, true);
    }
    SECTION("explicit, linear equation of state") {
        def.equationOfState = EquationOfState::Linear;
        runHookOrder(def, false);
    }
}

TEST_CASE("registry creates built-ins with parameters", "[unit][plugins]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    // Forces first, then boundaries, each in the order documented in builtin.h.
    std::vector<std::string> types;
    for (const PluginInfo& info : registry.types()) {
        types.push_back(info.type);
    }
    CHECK(types == std::vector<std::string>{"force.gravity", "force.point_gravity", "force.vortex",
                                            "force.wind", "force.pointer", "force.explosion",
                                            "force.damping", "boundary.box", "boundary.polygon",
                                            "boundary.chain", "boundary.circle"});
    REQUIRE(registry.find("force.gravity") != nullptr);
    CHECK(registry.find("force.gravity")->kind == PluginKind::Force);
    CHECK(registry.find("boundary.box")->kind == PluginKind::Boundary);
    CHECK(registry.find("boundary.nope") == nullptr);

    const std::vector<ParamValue> gravity{{"gx", 1.5}, {"gy", -3.0}};
    std::unique_ptr<ForcePlugin> g = registry.createForce("force.gravity", gravity);
    REQUIRE(g != nullptr);
    CHECK(g->type() == "force.gravity");
    CHECK(g->kind() == PluginKind::Force);
    CHECK(g->param("gx") == 1.5);
    CHECK(g->param("gy") == -3.0);

    const std::vector<ParamValue> box{
        {"minX", -0.5}, {"maxX", 0.25}, {"maxY", 0.75}, {"friction", 0.5}};
    std::unique_ptr<BoundaryPlugin> b = registry.createBoundary("boundary.box", box);
    REQUIRE(b != nullptr);
    CHECK(b->type() == "boundary.box");
    CHECK(b->param("minX") == -0.5);
    CHECK(b->param("minY") == 0.0); // default kept
    CHECK(b->param("maxX") == 0.25);
    CHECK(b->param("maxY") == 0.75);
    CHECK(b->friction() == 0.5f);

    // The created plugins work in a world: a particle falls with gx, gy and stays in the box.
    World world;
    const MaterialId w = world.addMaterial(water());
    world.addForce(std::move(g));
    world.addBoundary(std::move(b));
    const ParticleHandle p = world.addParticle({0.0f, 0.5f}, {0.0f, 0.0f}, w);
    world.step(0.1f);
    const glm::vec2 v = world.velocity(p);
    CHECK(v.x == Approx(0.15f).epsilon(1e-3));
    CHECK(v.y == Approx(-0.3f).epsilon(1e-3));
    for (int i = 0; i < 20; ++i) {
        world.step(0.1f);
    }
    const glm::vec2 x = world.position(p);
    CHECK(x.x <= 0.25f);
    CHECK(x.y >= 0.0f);
    // Resting in the lower right corner (the wall pressure holds it up to a spacing away).
    CHECK(x.x >= 0.25f - world.spacing(w));
    CHECK(x.y <= world.spacing(w));
}

TEST_CASE("parameter declarations describe themselves", "[unit][plugins]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    for (const PluginInfo& info : registry.types()) {
        CAPTURE(info.type);
        CHECK_FALSE(info.description.empty());
        const std::string prefix = info.kind == PluginKind::Force ? "force." : "boundary.";
        CHECK(info.type.rfind(prefix, 0) == 0);
        std::unique_ptr<Plugin> plugin = info.create();
        CHECK(plugin->type() == info.type);
        CHECK(plugin->kind() == info.kind);
        REQUIRE(plugin->params().size() == info.params.size());
        CHECK_FALSE(info.params.empty());
        for (const ParamDecl& d : info.params) {
            CAPTURE(d.name);
            CHECK_FALSE(d.name.empty());
            CHECK_FALSE(d.unit.empty());
            CHECK_FALSE(d.description.empty());
            if (d.type == ParamType::Points) {
                // A point list: its range is the vertex count; a new plugin has no points.
                CHECK(d.minValue >= 1.0);
                CHECK(d.minValue <= d.maxValue);
                CHECK(plugin->points(d.name).empty());
                continue;
            }
            CHECK(d.minValue <= d.defaultValue);
            CHECK(d.defaultValue <= d.maxValue);
            CHECK(d.minValue < d.maxValue);
            CHECK(plugin->param(d.name) == d.defaultValue); // starts at its default
        }
    }
}

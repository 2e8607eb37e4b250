// Shape boundaries (polygon, chain, circle): parameters and their errors, the kinematic pose,
// samples, and `project` on synthetic particles (crossing a thin wall, concave polygons, swept
// particles, wall velocity), plus a small world that stays deterministic across thread counts.
#include "test_support.h"

#include "plugins/boundaries/shape_geometry.h"

#include <fluid/plugins/boundaries.h>
#include <fluid/plugins/builtin.h>

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

constexpr float kSpacing = 0.01f;
constexpr float kSupport = 0.032f;
constexpr float kDt = 1.0f / 240.0f;

StepContext stepContext(float frameDt = kFrame) {
    return StepContext{frameDt, 0.0, kSpacing, kSupport};
}

// Synthetic particles for `project`: where they were (q) and where they are now (p).
struct Moves {
    std::vector<float> px, py, qx, qy, vx, vy;
    std::vector<uint16_t> material;
    void add(glm::vec2 from, glm::vec2 to, glm::vec2 velocity) {
        qx.push_back(from.x);
        qy.push_back(from.y);
        px.push_back(to.x);
        py.push_back(to.y);
        vx.push_back(velocity.x);
        vy.push_back(velocity.y);
        material.push_back(0);
    }
    glm::vec2 at(size_t i) const { return {px[i], py[i]}; }
    glm::vec2 velocity(size_t i) const { return {vx[i], vy[i]}; }
    // Runs the plugin's project over all particles, the path from q (at prevT) to p (at t).
    void project(BoundaryPlugin& plugin, float prevT = 0.0f, float t = kDt) {
        const ProjectContext c{px, py, qx, qy, vx, vy, material, kDt, t, prevT, kSpacing, {}};
        plugin.project(c, 0, static_cast<uint32_t>(px.size()));
    }
};

// Signed side of p against the line a -> b (> 0 left).
double side(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
    return double(b.x - a.x) * double(p.y - a.y) - double(b.y - a.y) * double(p.x - a.x);
}

} // namespace

TEST_CASE("shape boundaries: registry types and parameters", "[boundaries]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    for (const char* type : {"boundary.polygon", "boundary.chain", "boundary.circle"}) {
        CAPTURE(type);
        const PluginInfo* info = registry.find(type);
        REQUIRE(info != nullptr);
        CHECK(info->kind == PluginKind::Boundary);
        // Pose, velocities and friction come first, in this order, for every shape.
        const char* common[] = {"x", "y", "angle", "vx", "vy", "omega", "friction"};
        REQUIRE(info->params.size() > 7);
        for (size_t k = 0; k < 7; ++k) {
            CHECK(info->params[k].name == common[k]);
        }
    }
    const std::array<ParamValue, 4> values{
        {{"x", 0.5}, {"radius", 0.25}, {"omega", -3.0}, {"friction", 10.0}}};
    auto circle = registry.createBoundary("boundary.circle", values);
    CHECK(circle->param("radius") == 0.25);
    CHECK(circle->param("omega") == -3.0);
    CHECK(circle->friction() == 10.0f);
    CHECK_THROWS_WITH(
        circle->setParam("friction", 11.0),
        "plugin 'boundary.circle': parameter 'friction' = 11 is out of range [0, 10] (unit: 1)");
    CHECK_THROWS_WITH(circle->setParam("radius", 0.0),
                      "plugin 'boundary.circle': parameter 'radius' = 0 is out of range [0.0001, "
                      "10000] (unit: m)");
}

TEST_CASE("shape boundaries: point parameters and shape errors", "[boundaries]") {
    const std::vector<glm::vec2> two{{0.0f, 0.0f}, {1.0f, 0.0f}};
    PolygonBoundary polygon;
    CHECK_THROWS_WITH(polygon.setPoints("vertices", two),
                      "plugin 'boundary.polygon': parameter 'vertices' has 2 points; expected 3 "
                      "to 4096");
    CHECK_THROWS_WITH(polygon.setParam("vertices", 1.0),
                      "plugin 'boundary.polygon': parameter 'vertices' is a point list, not a "
                      "number");
    // No vertices yet: the first step says what is missing.
    CHECK_THROWS_WITH(polygon.prepare(stepContext()),
                      "plugin 'boundary.polygon': parameter 'vertices' has 0 points; set 3 to "
                      "4096 vertices with setPoints before the first step");
    // A bad shape is refused by setPoints itself, with the message the first step gave before
    // (so a level file's loader can point at the line). The rejected list is not kept
    // (Plugin::setPoints reverts it): a polygon that never had vertices still has none.
    const std::vector<glm::vec2> bowtie{{0, 0}, {1, 1}, {1, 0}, {0, 1}};
    const char* notSimple = "plugin 'boundary.polygon': parameter 'vertices' is not simple: edge "
                            "0 (vertex 0 to 1) meets edge 2 (vertex 2 to 3)";
    CHECK_THROWS_WITH(polygon.setPoints("vertices", bowtie), notSimple);
    CHECK(polygon.points("vertices").empty());
    CHECK_THROWS_WITH(polygon.prepare(stepContext()),
                      "plugin 'boundary.polygon': parameter 'vertices' has 0 points; set 3 to "
                      "4096 vertices with setPoints before the first step");
    // Once a shape was accepted, a rejected edit leaves it as it was.
    const std::vector<glm::vec2> tri{{0, 0}, {1, 0}, {0, 1}};
    polygon.setPoints("vertices", tri);
    const std::vector<glm::vec2> flat{{0, 0}, {1, 0}, {2, 0}};
    CHECK_THROWS_WITH(polygon.setPoints("vertices", flat),
                      "plugin 'boundary.polygon': parameter 'vertices' folds back at vertex 0: "
                      "edges 0 and 2 overlap");
    const std::vector<glm::vec2> repeated{{0, 0}, {1, 0}, {1, 0}, {0, 1}};
    CHECK_THROWS_WITH(polygon.setPoints("vertices", repeated),
                      "plugin 'boundary.polygon': parameter 'vertices' repeats vertex 1 = (1, 0) "
                      "as vertex 2; expected distinct consecutive vertices (unit: m)");
    const std::vector<glm::vec2> sliver{{0, 0}, {1e5f, 0}, {0, 1e-8f}};
    CHECK_THROWS_WITH(polygon.setPoints("vertices", sliver),
                      "plugin 'boundary.polygon': parameter 'vertices' encloses no area "
                      "(collinear vertices)");
    CHECK_THROWS_WITH(polygon.setPoints("vertices", bowtie), notSimple);
    REQUIRE(polygon.points("vertices").size() == 3);
    CHECK(polygon.points("vertices")[2] == tri[2]);
    CHECK_NOTHROW(polygon.prepare(stepContext()));
    CHECK(polygon.containsLocal({0.2, 0.2}));
    const std::vector<glm::vec2> nan{{0, 0}, {1, 0}, {0, NAN}};
    CHECK_THROWS_WITH(polygon.setPoints("vertices", nan),
                      "plugin 'boundary.polygon': parameter 'vertices' point 2 = (0, nan) is not "
                      "finite");

    ChainBoundary chain;
    const std::vector<glm::vec2> one{{0.0f, 0.0f}};
    CHECK_THROWS_WITH(chain.setPoints("points", one),
                      "plugin 'boundary.chain': parameter 'points' has 1 points; expected 2 to "
                      "4096");
    const char* closedTwo = "plugin 'boundary.chain': parameter 'points' has 2 points; set 3 to "
                            "4096 with setPoints before the first step (a closed chain needs 3)";
    chain.setPoints("points", two);
    // `closed` last: refused at once, and left open.
    CHECK_THROWS_WITH(chain.setParam("closed", 1.0), closedTwo);
    CHECK(chain.param("closed") == 0.0);
    CHECK_NOTHROW(chain.prepare(stepContext()));
    CHECK(chain.points("points").size() == 2);
    CHECK(chain.segments().size() == 1);
}

TEST_CASE("chain: closed and points are checked whichever is set last", "[boundaries]") {
    const std::vector<glm::vec2> two{{0.0f, 0.0f}, {1.0f, 0.0f}};
    const std::vector<glm::vec2> three{{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
    const char* closedTwo = "plugin 'boundary.chain': parameter 'points' has 2 points; set 3 to "
                            "4096 with setPoints before the first step (a closed chain needs 3)";
    // `closed` first, before any points: allowed (a default chain has none yet).
    ChainBoundary chain;
    CHECK_NOTHROW(chain.setParam("closed", 1.0));
    // The points last: 2 are refused for a closed chain, 3 accepted.
    CHECK_THROWS_WITH(chain.setPoints("points", two), closedTwo);
    chain.setPoints("points", three);
    // A rejected edit keeps the accepted loop.
    CHECK_THROWS_WITH(chain.setPoints("points", two), closedTwo);
    CHECK(chain.points("points").size() == 3);
    chain.prepare(stepContext());
    CHECK(chain.segments().size() == 3);
    // Opening it makes 2 points fine again.
    chain.setParam("closed", 0.0);
    chain.setPoints("points", two);
    chain.prepare(stepContext());
    CHECK(chain.segments().size() == 1);
    // Consecutive repeats: refused at once; a closed chain also joins the last to the first.
    const std::vector<glm::vec2> repeat{{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 0.0f}};
    CHECK_THROWS_WITH(chain.setPoints("points", repeat),
                      "plugin 'boundary.chain': parameter 'points' repeats point 1 = (1, 0) as "
                      "point 2; expected distinct consecutive points (unit: m)");
    const std::vector<glm::vec2> loopBack{{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}, {0.0f, 0.0f}};
    chain.setPoints("points", loopBack); // open: the last point may equal the first
    CHECK_THROWS_WITH(chain.setParam("closed", 1.0),
                      "plugin 'boundary.chain': parameter 'points' repeats point 3 = (0, 0) as "
                      "point 0; expected distinct consecutive points (unit: m)");
    CHECK(chain.param("closed") == 0.0);
    // The constructor's points and flag go through the same checks.
    CHECK_THROWS_WITH(ChainBoundary(two, true), closedTwo);
    // Through the registry (what a level file uses): closed before the points.
    Registry registry;
    registerBuiltinPlugins(registry);
    const std::array<ParamValue, 1> closed{{{"closed", 1.0}}};
    auto made = registry.createBoundary("boundary.chain", closed);
    CHECK_THROWS_WITH(made->setPoints("points", two), closedTwo);
    CHECK_NOTHROW(made->setPoints("points", three));
}

TEST_CASE("shape boundaries: coordinates beyond 1e5 m are refused when set", "[boundaries]") {
    std::vector<glm::vec2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    square[3] = {1e30f, 0.0f};
    PolygonBoundary polygon;
    CHECK_THROWS_WITH(polygon.setPoints("vertices", square),
                      "plugin 'boundary.polygon': parameter 'vertices' point 3 = (1e+30, 0) is "
                      "outside [-100000, 100000] (unit: m)");
    // Checked before the geometry (this one would also be refused as not simple).
    const std::vector<glm::vec2> far{{0, 0}, {1, 1}, {1, 0}, {0, -100001.0f}};
    CHECK_THROWS_WITH(polygon.setPoints("vertices", far),
                      "plugin 'boundary.polygon': parameter 'vertices' point 3 = (0, -100001) is "
                      "outside [-100000, 100000] (unit: m)");
    // The bound itself is fine.
    const std::vector<glm::vec2> edge{{-1e5f, -1e5f}, {1e5f, -1e5f}, {0.0f, 1e5f}};
    CHECK_NOTHROW(polygon.setPoints("vertices", edge));

    ChainBoundary chain;
    const std::vector<glm::vec2> wall{{0.0f, 0.0f}, {-2e5f, 3.0f}};
    CHECK_THROWS_WITH(chain.setPoints("points", wall),
                      "plugin 'boundary.chain': parameter 'points' point 1 = (-200000, 3) is "
                      "outside [-100000, 100000] (unit: m)");
    // The rejected list is not kept: the chain still has no points.
    CHECK(chain.points("points").empty());
    CHECK_THROWS_WITH(chain.prepare(stepContext()),
                      "plugin 'boundary.chain': parameter 'points' has 0 points; set 2 to 4096 "
                      "with setPoints before the first step");

    // The circle's radius has its declared range (tighter than the coordinates').
    CircleBoundary circle;
    CHECK_THROWS_WITH(circle.setParam("radius", 1e5),
                      "plugin 'boundary.circle': parameter 'radius' = 100000 is out of range "
                      "[0.0001, 10000] (unit: m)");
}

TEST_CASE("shape boundaries: too many samples are refused before any is laid", "[boundaries]") {
    // Water spacing 0.01 m and support 0.032 m: 4 layers, some 400 samples per metre of outline.
    CircleBoundary circle({0.0f, 0.0f}, 1e4f);
    CHECK_THROWS_WITH(circle.prepare(stepContext()),
                      "plugin 'boundary.circle': radius 10000 m needs about 25000000 boundary "
                      "samples at spacing 0.01 m; at most 2000000");
    CHECK(circle.samples().size() == 0);
    CHECK(circle.localSamples().empty());

    const std::vector<glm::vec2> huge{{-1e5f, -1e5f}, {1e5f, -1e5f}, {1e5f, 1e5f}, {-1e5f, 1e5f}};
    PolygonBoundary polygon(huge);
    CHECK_THROWS_WITH(polygon.prepare(stepContext()),
                      "plugin 'boundary.polygon': perimeter 800000 m needs about 320000000 "
                      "boundary samples at spacing 0.01 m; at most 2000000");
    CHECK(polygon.samples().size() == 0);
    // A rejected shape is not half-built: project leaves particles alone.
    Moves moves;
    moves.add({0.0f, -2e5f}, {0.0f, 0.0f}, {0.0f, 1.0f});
    moves.project(polygon);
    CHECK(moves.at(0) == glm::vec2(0.0f, 0.0f));

    ChainBoundary chain(std::vector<glm::vec2>{{-1e4f, 0.0f}, {1e4f, 0.0f}, {1e4f, 1e4f}});
    CHECK_THROWS_WITH(chain.prepare(stepContext()),
                      "plugin 'boundary.chain': length 30000 m needs about 3000000 boundary "
                      "samples at spacing 0.01 m; at most 2000000");

    // A spacing far below the support (many layers) is caught the same way, without an
    // integer overflow, and a tiny disc there still gets its one centre sample.
    const StepContext deep{kFrame, 0.0, 1e-6f, 10.0f};
    CircleBoundary post({0.0f, 0.0f}, 1.0f);
    CHECK_THROWS_WITH(post.prepare(deep),
                      "plugin 'boundary.circle': radius 1 m needs about 3100000000000 boundary "
                      "samples at spacing 1e-06 m; at most 2000000");
    const StepContext wide{kFrame, 0.0, 0.01f, 1e7f};
    CircleBoundary speck({0.0f, 0.0f}, 2e-4f);
    speck.prepare(wide);
    CHECK(speck.localSamples().size() == 1);

    // Below the cap: laid (a 400 m outline, some 160,000 samples).
    const std::vector<glm::vec2> big{
        {0.0f, 0.0f}, {100.0f, 0.0f}, {100.0f, 100.0f}, {0.0f, 100.0f}};
    PolygonBoundary field(big);
    const auto t0 = std::chrono::steady_clock::now();
    field.prepare(stepContext());
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[measure] 100 m square polygon: %zu samples laid in %.3f s\n",
                field.samples().size(), seconds);
    CHECK(field.samples().size() > 150000);
    CHECK(field.samples().size() <= 160000);
}

TEST_CASE("shape boundaries: a shape moving past 1e5 m stops there and its world reloads",
          "[boundaries]") {
    CircleBoundary circle({99990.0f, 0.0f}, 0.1f);
    circle.setVelocity({1000.0f, -3.0f}, 0.0f);
    circle.finish(stepContext(1.0f / 60.0f)); // 99990 + 16.7 m: past the edge
    CHECK(circle.param("x") == 1e5);
    CHECK(circle.param("vx") == 0.0); // stopped: no sweeping past the edge in later steps
    CHECK(circle.param("vy") == -3.0);
    CHECK(circle.param("y") == Approx(-3.0 / 60.0));
    circle.finish(stepContext(1.0f / 60.0f));
    CHECK(circle.param("x") == 1e5);
    // The other way, and y too.
    circle.setPose({-99999.0f, -99999.0f}, 0.0f);
    circle.setVelocity({-1000.0f, -1000.0f}, 0.0f);
    circle.finish(stepContext(1.0f / 60.0f));
    CHECK(circle.param("x") == -1e5);
    CHECK(circle.param("y") == -1e5);
    CHECK(circle.param("vx") == 0.0);
    CHECK(circle.param("vy") == 0.0);

    // In a world: the snapshot taken after the shape reached the edge loads.
    Registry registry;
    registerBuiltinPlugins(registry);
    World world;
    const MaterialId water = world.addMaterial(fluid::water());
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 0.2f, 0.2f));
    auto paddle = std::make_unique<PolygonBoundary>(
        std::vector<glm::vec2>{{-0.05f, -0.01f}, {0.05f, -0.01f}, {0.05f, 0.01f}});
    paddle->setPose({99995.0f, 0.5f}, 0.0f);
    paddle->setVelocity({900.0f, 0.0f}, 1.0f);
    world.addBoundary(std::move(paddle));
    world.spawnBlob(latticeBlock(world, water, 0.0f, 0.0f, 8, 8));
    for (int f = 0; f < 3; ++f) {
        world.step(kFrame);
    }
    CHECK(world.boundaries()[1]->param("x") == 1e5);
    std::stringstream bytes;
    world.save(bytes);
    World copy = World::load(bytes, registry);
    CHECK(copy.boundaries()[1]->param("x") == 1e5);
    CHECK(copy.boundaries()[1]->param("angle") == world.boundaries()[1]->param("angle"));
}

TEST_CASE("shape boundaries: far and non-finite positions give edge cells, not overflow",
          "[boundaries]") {
    // The segment grid and the sample hash clamp cell indices before casting: a position far
    // beyond the shape (or NaN, from a blown-up host) lands in an edge cell, never in an
    // out-of-range float-to-int conversion or a signed overflow (undefined behaviour, which a
    // sanitizer build of this test reports).
    geometry::SegmentSet set;
    set.build({geometry::makeSegment({0, 0}, {1, 0}), geometry::makeSegment({1, 0}, {1, 1}),
               geometry::makeSegment({1, 1}, {0, 1}), geometry::makeSegment({0, 1}, {0, 0})},
              0.1);
    double t = 0.0;
    CHECK(set.firstCrossing({1e30, 0.5}, {-1e30, 0.5}, 0, t) == 1); // the right edge first
    CHECK(t == Approx(0.5));
    CHECK(set.firstCrossing({0.5, -1e300}, {0.5, 1e300}, 0, t) == 0);
    glm::dvec2 closest{0.0, 0.0};
    double distance = 0.0;
    CHECK(set.nearest({1e30, -1e30}, 1.0, closest, distance) == -1);
    CHECK(set.nearest({NAN, 0.5}, 1.0, closest, distance) == -1);
    CHECK(set.inside({0.5, 0.5}));
    CHECK_FALSE(set.inside({-1e30, 0.5}));
    CHECK_FALSE(set.inside({0.5, 1e30}));
    CHECK_FALSE(set.inside({0.5, NAN}));

    geometry::SpacedPoints kept(0.0055);
    CHECK(kept.add({1e30, 0.0}));
    CHECK_FALSE(kept.add({1e30, 0.0})); // found again in its (clamped) cell
    CHECK(kept.add({9e29, 0.0}));       // the same clamped cell, far apart: kept
    CHECK(kept.add({-1e30, -1e30}));
    CHECK(kept.add({-1e5, 1e5}));
    CHECK_FALSE(kept.add({-1e5 + 0.005, 1e5}));
    CHECK(kept.points().size() == 4);

    // Through the plugins: far particles are left where they are, NaN ones too, and a path
    // from far away through the shape ends somewhere finite.
    const std::vector<glm::vec2> square{{0, 0}, {0.1f, 0}, {0.1f, 0.1f}, {0, 0.1f}};
    PolygonBoundary polygon(square);
    ChainBoundary chain(std::vector<glm::vec2>{{0.0f, 0.0f}, {0.1f, 0.1f}, {0.2f, 0.0f}});
    CircleBoundary circle({0.05f, 0.05f}, 0.03f);
    for (BoundaryPlugin* plugin :
         std::initializer_list<BoundaryPlugin*>{&polygon, &chain, &circle}) {
        CAPTURE(plugin->type());
        plugin->prepare(stepContext());
        Moves moves;
        moves.add({1e30f, 0.05f}, {-1e30f, 0.05f}, {0.0f, 0.0f});
        moves.add({3e38f, 3e38f}, {3e38f, -3e38f}, {0.0f, 0.0f});
        moves.add({0.05f, -1e30f}, {0.05f, -1e30f}, {0.0f, 0.0f});
        moves.add({NAN, 0.05f}, {NAN, 0.05f}, {0.0f, 0.0f});
        moves.project(*plugin);
        CHECK(std::isfinite(moves.at(0).x));
        CHECK(std::isfinite(moves.at(0).y));
        CHECK(moves.at(1) == glm::vec2(3e38f, -3e38f));
        CHECK(moves.at(2) == glm::vec2(0.05f, -1e30f));
        CHECK(std::isnan(moves.at(3).x));
    }
}

TEST_CASE("shape boundaries: kinematic pose at time t and after finish", "[boundaries]") {
    CircleBoundary circle({0.0f, 0.0f}, 0.1f);
    circle.setPose({1.0f, 2.0f}, 0.5f);
    circle.setVelocity({3.0f, -4.0f}, 2.0f);
    const KinematicShape::Pose p = circle.pose(0.25);
    CHECK(p.origin.x == Approx(1.75));
    CHECK(p.origin.y == Approx(1.0));
    CHECK(p.cosA == Approx(std::cos(1.0)));
    CHECK(p.sinA == Approx(std::sin(1.0)));
    // Local (1, 0) turned by 1 rad; its velocity is v + omega x r.
    const glm::dvec2 w = p.toWorld({1.0, 0.0});
    CHECK(w.x == Approx(1.75 + std::cos(1.0)));
    CHECK(w.y == Approx(1.0 + std::sin(1.0)));
    const glm::dvec2 back = p.toLocal(w);
    CHECK(back.x == Approx(1.0));
    CHECK(back.y == Approx(0.0).margin(1e-12));
    const glm::dvec2 v = p.velocityAt(w);
    CHECK(v.x == Approx(3.0 - 2.0 * std::sin(1.0)));
    CHECK(v.y == Approx(-4.0 + 2.0 * std::cos(1.0)));

    // The samples carry the solid's velocity at their place.
    circle.prepare(stepContext(0.5f));
    const BoundarySamples& s = circle.samples();
    REQUIRE(s.size() > 10);
    for (size_t k = 0; k < s.size(); k += 7) {
        const double rx = s.px[k] - 1.0, ry = s.py[k] - 2.0;
        CHECK(s.vx[k] == Approx(3.0 - 2.0 * ry).margin(1e-5));
        CHECK(s.vy[k] == Approx(-4.0 + 2.0 * rx).margin(1e-5));
    }

    // finish: the pose advances by the frame; the velocities stay.
    circle.finish(stepContext(0.5f));
    CHECK(circle.param("x") == Approx(2.5));
    CHECK(circle.param("y") == Approx(0.0).margin(1e-12));
    CHECK(circle.param("angle") == Approx(1.5));
    CHECK(circle.param("vx") == 3.0);
    CHECK(circle.param("omega") == 2.0);
    // Many turns later the angle is still in [-pi, pi] and the same rotation.
    for (int k = 0; k < 10; ++k) {
        circle.finish(stepContext(0.5f));
    }
    const double expected = std::remainder(1.5 + 10.0, 2.0 * std::numbers::pi);
    CHECK(circle.param("angle") == Approx(expected));
    CHECK(std::fabs(circle.param("angle")) <= std::numbers::pi);

    // A static shape's pose is untouched by finish, bit for bit.
    PolygonBoundary still;
    still.setPose({0.1f, 0.2f}, 0.3f);
    const std::vector<glm::vec2> tri{{0, 0}, {1, 0}, {0, 1}};
    still.setPoints("vertices", tri);
    still.finish(stepContext());
    CHECK(still.param("x") == double(0.1f));
    CHECK(still.param("angle") == double(0.3f));
}

TEST_CASE("chain: a particle jumping 0.1 m across a segment goes back to its side",
          "[boundaries]") {
    // A splitter with a slanted middle part.
    const std::vector<glm::vec2> pts{{0.0f, -0.5f}, {0.0f, 0.0f}, {0.1f, 0.2f}, {0.1f, 0.6f}};
    ChainBoundary chain(pts);
    chain.prepare(stepContext());
    Moves m;
    m.add({-0.02f, -0.2f}, {0.08f, -0.2f}, {24.0f, 0.0f});  // through the vertical part
    m.add({0.03f, 0.15f}, {0.09f, 0.05f}, {14.0f, -24.0f}); // the slanted part, from its left
    m.add({0.15f, 0.1f}, {0.0f, 0.1f}, {-36.0f, 0.0f});     // from the right
    m.add({-0.03f, 0.0f}, {0.07f, 0.0f}, {24.0f, 0.0f});    // exactly through a vertex
    m.add({0.5f, 0.5f}, {0.52f, 0.5f}, {1.0f, 0.0f});       // far away: untouched
    m.add({0.0957f, 0.3f}, {0.0957f, 0.3f}, {0.0f, 0.0f});  // too close to the wall
    const Moves before = m;
    m.project(chain);
    auto sideOf = [&](glm::vec2 p) {
        // Side against the chain as a function of y (it is monotone in y).
        double s = 0.0;
        for (size_t k = 0; k + 1 < pts.size(); ++k) {
            if (p.y >= pts[k].y && p.y <= pts[k + 1].y) {
                s = side(p, pts[k], pts[k + 1]);
            }
        }
        return s;
    };
    for (size_t i = 0; i < 4; ++i) {
        CAPTURE(i, m.at(i).x, m.at(i).y);
        const glm::vec2 from{before.qx[i], before.qy[i]};
        CHECK(sideOf(m.at(i)) * sideOf(from) > 0.0); // the side it came from
        double d = INFINITY;
        for (size_t k = 0; k + 1 < pts.size(); ++k) {
            d = std::min(d, segmentDistance(m.at(i), pts[k], pts[k + 1]));
        }
        CHECK(d >= 0.5 * kSpacing * 0.999); // keeps half a spacing of clearance
        CHECK(d <= 0.05);                   // stopped at the wall, not thrown away
    }
    // Velocity into the wall is gone: the first particle moved +x into a vertical wall.
    CHECK(m.velocity(0).x == Approx(0.0).margin(1e-6));
    CHECK(m.velocity(3).x == Approx(0.0).margin(1e-6));
    const glm::vec2 n{-0.2f / std::sqrt(0.05f), 0.1f / std::sqrt(0.05f)}; // slanted part's normal
    CHECK(glm::dot(m.velocity(2), n) == Approx(0.0).margin(1e-5));
    // Motion along the wall is kept: the slanted hit keeps its tangential part.
    const glm::vec2 t = glm::normalize(pts[2] - pts[1]);
    CHECK(glm::dot(m.velocity(1), t) == Approx(glm::dot(before.velocity(1), t)).epsilon(1e-5));
    CHECK(m.at(4) == before.at(4));
    CHECK(m.velocity(4) == before.velocity(4));
    // Pushed out to the clearance on its own side.
    CHECK(m.at(5).x == Approx(0.095f).margin(1e-6));
    CHECK(m.at(5).y == Approx(0.3f));
}

TEST_CASE("chain: open ends, closed loops and a moving wall", "[boundaries]") {
    const std::vector<glm::vec2> square{{0, 0}, {0.2f, 0}, {0.2f, 0.2f}, {0, 0.2f}};
    ChainBoundary loop(square, true);
    loop.prepare(stepContext());
    // Samples: one row along the walls, about a spacing apart.
    CHECK(loop.samples().size() == 80);
    Moves m;
    m.add({0.1f, 0.1f}, {0.1f, 0.3f}, {0.0f, 48.0f});    // inside, out through the closing top
    m.add({0.1f, -0.05f}, {0.1f, 0.05f}, {0.0f, 24.0f}); // outside, in through the bottom
    m.project(loop);
    CHECK(m.at(0).y == Approx(0.2f - 0.005f).margin(1e-6));
    CHECK(m.at(1).y == Approx(-0.005f).margin(1e-6));

    // Round the open end of a chain: allowed, with clearance from the end point.
    const std::vector<glm::vec2> stub{{0, 0}, {0, 0.1f}};
    ChainBoundary open(stub);
    open.prepare(stepContext());
    Moves e;
    e.add({-0.01f, 0.12f}, {0.003f, 0.101f}, {4.0f, 0.0f});
    e.project(open);
    CHECK(e.at(0).x > 0.0f); // went round the end
    CHECK(glm::length(e.at(0) - glm::vec2(0, 0.1f)) == Approx(0.005f).margin(1e-6));

    // A wall moving at 2 m/s sweeps a particle at rest: it stays on its side and moves with
    // the wall.
    ChainBoundary wall(stub);
    wall.setVelocity({2.0f, 0.0f}, 0.0f);
    wall.prepare(stepContext());
    Moves w;
    w.add({0.006f, 0.05f}, {0.006f, 0.05f}, {0.0f, 0.0f});
    w.project(wall, 0.0f, 0.01f); // the wall moved 2 cm in 10 ms
    CHECK(w.at(0).x == Approx(0.02f + 0.005f).margin(1e-6));
    CHECK(w.velocity(0).x == Approx(2.0f));
}

TEST_CASE("polygon: concave inside test, samples, crossings and swept particles", "[boundaries]") {
    // A U (clockwise, to check that either winding works): a notch from the top.
    const std::vector<glm::vec2> u{{0.0f, 0.0f}, {0.0f, 0.3f}, {0.1f, 0.3f}, {0.1f, 0.1f},
                                   {0.2f, 0.1f}, {0.2f, 0.3f}, {0.3f, 0.3f}, {0.3f, 0.0f}};
    PolygonBoundary polygon(u);
    polygon.prepare(stepContext());
    CHECK(polygon.containsLocal({0.05, 0.2}));        // left arm
    CHECK(polygon.containsLocal({0.25, 0.2}));        // right arm
    CHECK(polygon.containsLocal({0.15, 0.05}));       // base
    CHECK_FALSE(polygon.containsLocal({0.15, 0.2}));  // the notch
    CHECK_FALSE(polygon.containsLocal({0.15, 0.35})); // above
    CHECK_FALSE(polygon.containsLocal({-0.01, 0.1})); // left of it

    // Samples: all inside, at least half a spacing deep, none closer than 0.55 spacing to
    // another, and every point of the solid within a support radius of the surface has one
    // within a spacing.
    const auto local = polygon.localSamples();
    REQUIRE(local.size() > 100);
    auto depth = [&](glm::dvec2 p) {
        double d = INFINITY;
        for (size_t k = 0; k < u.size(); ++k) {
            d = std::min(d, segmentDistance(p, u[k], u[(k + 1) % u.size()]));
        }
        return d;
    };
    double closestPair = INFINITY, shallowest = INFINITY;
    for (size_t a = 0; a < local.size(); ++a) {
        CHECK(polygon.containsLocal(local[a]));
        shallowest = std::min(shallowest, depth(local[a]));
        for (size_t b = a + 1; b < local.size(); ++b) {
            closestPair = std::min(closestPair, glm::length(local[a] - local[b]));
        }
    }
    CHECK(shallowest >= 0.499 * kSpacing);
    CHECK(closestPair >= 0.55 * kSpacing);
    double worstHole = 0.0;
    for (double x = 0.001; x < 0.3; x += 0.002) {
        for (double y = 0.001; y < 0.3; y += 0.002) {
            if (!polygon.containsLocal({x, y}) || depth({x, y}) > kSupport) {
                continue;
            }
            double nearest = INFINITY;
            for (const glm::dvec2 s : local) {
                nearest = std::min(nearest, glm::length(s - glm::dvec2(x, y)));
            }
            worstHole = std::max(worstHole, nearest);
        }
    }
    std::printf("[measure] U polygon: %zu samples, closest pair %.3f s, worst hole %.3f s\n",
                local.size(), closestPair / kSpacing, worstHole / kSpacing);
    CHECK(worstHole < 0.85 * kSpacing);

    Moves m;
    m.add({0.15f, 0.25f}, {0.15f, 0.05f}, {0.0f, -48.0f}); // down the notch into the base
    m.add({0.15f, 0.2f}, {0.25f, 0.18f}, {24.0f, -4.8f});  // sideways into the right arm
    m.add({0.13f, 0.11f}, {0.19f, 0.09f}, {14.4f, -4.8f}); // sliding along the notch floor
    m.add({-0.05f, 0.15f}, {0.05f, 0.15f}, {24.0f, 0.0f}); // from outside into the left arm
    m.add({0.12f, 0.2f}, {0.16f, 0.2f}, {9.6f, 0.0f});     // in the notch: untouched
    m.project(polygon);
    for (size_t i = 0; i < 4; ++i) {
        CAPTURE(i, m.at(i).x, m.at(i).y);
        CHECK_FALSE(polygon.containsLocal(m.at(i)));
        CHECK(depth(m.at(i)) < 1e-4); // on the surface
    }
    CHECK(m.at(0).y == Approx(0.1f).margin(1e-4));
    CHECK(m.velocity(0).y == Approx(0.0f).margin(1e-6));
    CHECK(m.at(1).x == Approx(0.2f).margin(1e-4));
    CHECK(m.at(1).y == Approx(0.18f).margin(1e-4)); // kept its motion along the wall
    CHECK(m.at(2).x == Approx(0.19f).margin(1e-4)); // slides on along the notch floor
    CHECK(m.at(2).y == Approx(0.1f).margin(1e-4));
    CHECK(m.velocity(2).x == 14.4f);
    CHECK(m.at(3).x == Approx(0.0f).margin(1e-4));
    CHECK(m.at(4) == glm::vec2(0.16f, 0.2f));

    // Swept over: a particle at rest found inside goes to the nearest surface point.
    PolygonBoundary paddle(
        std::vector<glm::vec2>{{-0.2f, -0.025f}, {0.2f, -0.025f}, {0.2f, 0.025f}, {-0.2f, 0.025f}});
    paddle.setVelocity({0.0f, 0.0f}, 5.0f);
    paddle.prepare(stepContext());
    Moves s;
    // At t = 0 the paddle is flat; by t = 0.01 s it turned 0.05 rad: the tip rose 1 cm.
    s.add({0.19f, 0.03f}, {0.19f, 0.03f}, {0.0f, 0.0f});
    s.project(paddle, 0.0f, 0.01f);
    const KinematicShape::Pose now = paddle.pose(0.01);
    const glm::dvec2 l = now.toLocal(glm::dvec2(s.at(0)));
    CAPTURE(l.x, l.y);
    CHECK_FALSE(paddle.containsLocal(l));
    CHECK(l.y == Approx(0.025).margin(1e-4)); // on the top face, the side it was on
    // It moves with the paddle's surface: at least the wall's normal speed omega * r.
    const double wallNormal = 5.0 * 0.19;
    CHECK(glm::dot(glm::dvec2(s.velocity(0)), now.rotate({0.0, 1.0})) >= wallNormal * 0.99);
}

TEST_CASE("polygon: a thin paddle is not tunnelled through", "[boundaries]") {
    // 2 cm thick, a particle jumping 5 cm straight through it.
    PolygonBoundary thin(
        std::vector<glm::vec2>{{-0.1f, 0.0f}, {0.1f, 0.0f}, {0.1f, 0.02f}, {-0.1f, 0.02f}});
    thin.prepare(stepContext());
    CHECK(thin.samples().size() > 0);
    Moves m;
    m.add({0.0f, 0.03f}, {0.0f, -0.02f}, {0.0f, -12.0f});
    m.add({0.05f, -0.02f}, {0.07f, 0.03f}, {4.8f, 12.0f});
    m.project(thin);
    CHECK(m.at(0).y == Approx(0.02f).margin(1e-4));
    CHECK(m.at(0).y >= 0.02f);
    CHECK(m.at(1).y == Approx(0.0f).margin(1e-4));
    CHECK(m.at(1).y <= 0.0f);
    CHECK(m.velocity(1).y == Approx(0.0f).margin(1e-6));
}

TEST_CASE("circle: crossing, sliding round the rim and sweeping", "[boundaries]") {
    CircleBoundary circle({0.0f, 0.0f}, 0.05f);
    circle.prepare(stepContext());
    // Rings: each about a spacing apart, the first half a spacing inside the rim.
    double outer = 0.0;
    for (size_t k = 0; k < circle.samples().size(); ++k) {
        outer = std::max(
            outer, std::hypot(double(circle.samples().px[k]), double(circle.samples().py[k])));
    }
    CHECK(outer == Approx(0.045).epsilon(1e-5));
    Moves m;
    m.add({-0.08f, 0.0f}, {-0.03f, 0.0f}, {12.0f, 0.0f});  // head on
    m.add({-0.06f, 0.01f}, {0.06f, 0.01f}, {28.8f, 0.0f}); // straight through
    m.add({0.0f, 0.051f}, {0.01f, 0.048f}, {2.4f, -0.7f}); // grazing the top
    m.project(circle);
    CHECK(m.at(0).x == Approx(-0.05f).margin(1e-4));
    CHECK(m.at(0).y == Approx(0.0f).margin(1e-6));
    CHECK(m.velocity(0).x == Approx(0.0f).margin(1e-5));
    CHECK(m.at(1).x < -0.045f); // back at its entry, not out at the far side
    CHECK(glm::length(m.at(2)) == Approx(0.05f).margin(1e-4));
    CHECK(m.at(2).x > 0.009f); // kept sliding round

    // A disc moving at 1 m/s hits a particle at rest.
    CircleBoundary moving({0.0f, 0.0f}, 0.05f);
    moving.setVelocity({1.0f, 0.0f}, 0.0f);
    moving.prepare(stepContext());
    Moves s;
    s.add({0.052f, 0.0f}, {0.052f, 0.0f}, {0.0f, 0.0f});
    s.project(moving, 0.0f, 0.01f);
    CHECK(s.at(0).x == Approx(0.06f).margin(1e-4));
    CHECK(s.velocity(0).x == Approx(1.0f));
}

TEST_CASE("shape boundaries: a world with a paddle is the same for 1 and 3 workers",
          "[boundaries]") {
    auto run = [](uint32_t workers) {
        WorldDef def;
        def.workerCount = workers;
        World world(def);
        const MaterialId water = world.addMaterial(fluid::water());
        world.addForce(std::make_unique<GravityForce>());
        world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 0.3f, 0.3f));
        auto paddle = std::make_unique<PolygonBoundary>(std::vector<glm::vec2>{
            {-0.08f, -0.01f}, {0.08f, -0.01f}, {0.08f, 0.01f}, {-0.08f, 0.01f}});
        paddle->setPose({0.15f, 0.1f}, 0.0f);
        paddle->setVelocity({0.0f, 0.0f}, 6.0f);
        world.addBoundary(std::move(paddle));
        world.addBoundary(
            std::make_unique<ChainBoundary>(std::vector<glm::vec2>{{0.02f, 0.12f}, {0.1f, 0.05f}}));
        world.addBoundary(std::make_unique<CircleBoundary>(glm::vec2{0.25f, 0.05f}, 0.02f));
        world.spawnBlob(latticeBlock(world, water, 0.0f, 0.15f, 28, 10));
        for (int f = 0; f < 20; ++f) {
            world.step(kFrame);
        }
        return stateHash(world);
    };
    CHECK(run(1) == run(3));
}

TEST_CASE("shape boundaries: a snapshot mid-motion continues bit-identically", "[boundaries]") {
    // The shapes keep no state beyond their parameters (the advanced pose is stored in them),
    // so the world's snapshot of parameters and points is all a restored world needs.
    Registry registry;
    registerBuiltinPlugins(registry);
    World world;
    const MaterialId water = world.addMaterial(fluid::water());
    world.addForce(std::make_unique<GravityForce>());
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 0.3f, 0.3f));
    auto paddle = std::make_unique<PolygonBoundary>(
        std::vector<glm::vec2>{{-0.08f, -0.01f}, {0.08f, -0.01f}, {0.08f, 0.01f}, {-0.08f, 0.01f}});
    paddle->setPose({0.15f, 0.1f}, 0.0f);
    paddle->setVelocity({0.0f, 0.0f}, 6.0f);
    world.addBoundary(std::move(paddle));
    auto chain = std::make_unique<ChainBoundary>(
        std::vector<glm::vec2>{{-0.04f, 0.0f}, {0.04f, 0.0f}, {0.0f, 0.03f}}, true);
    chain->setPose({0.22f, 0.05f}, 0.0f);
    chain->setVelocity({0.0f, 0.02f}, -1.0f);
    world.addBoundary(std::move(chain));
    world.addBoundary(std::make_unique<CircleBoundary>(glm::vec2{0.06f, 0.05f}, 0.02f));
    world.spawnBlob(latticeBlock(world, water, 0.0f, 0.15f, 28, 10));
    for (int f = 0; f < 10; ++f) {
        world.step(kFrame);
    }
    std::stringstream bytes;
    world.save(bytes);
    World copy = World::load(bytes, registry);
    CHECK(copy.boundaries()[1]->param("angle") == world.boundaries()[1]->param("angle"));
    CHECK(world.boundaries()[1]->param("angle") == Approx(10.0 * 6.0 / 60.0));
    CHECK(world.boundaries()[2]->param("y") == Approx(0.05 + 10.0 * 0.02 / 60.0));
    for (int f = 0; f < 10; ++f) {
        world.step(kFrame);
        copy.step(kFrame);
    }
    CHECK(stateHash(copy) == stateHash(world));
}

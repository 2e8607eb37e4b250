// Region queries (fluid/query.h): exactly the particles a brute-force scan finds, in increasing
// array index, the same for any number of workers and after a save and load; the callback stops
// early, the buffer form truncates and counts; bad regions and queries during a step refused.
#include "test_support.h"

#include <fluid/query.h>

#include <catch2/catch.hpp>

#include <random>
#include <sstream>
#include <thread>

using namespace fluid;
using namespace fluid::test;

namespace {

// The indices a scan of every particle finds in `region`, in increasing order.
std::vector<uint32_t> bruteForce(const World& world, const Shape& region) {
    std::vector<uint32_t> out;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (contains(region, {world.positionX()[i], world.positionY()[i]})) {
            out.push_back(i);
        }
    }
    return out;
}

std::vector<uint32_t> queried(const World& world, const Shape& region) {
    std::vector<uint32_t> out;
    queryParticles(world, region, [&](const QueryHit& hit) {
        CHECK(world.handleAt(hit.index) == hit.handle);
        CHECK(hit.material.index == world.materialIndex()[hit.index]);
        out.push_back(hit.index);
        return true;
    });
    return out;
}

// Water and yoghurt dropped into a tank and stepped, so that the particles are out of lattice
// order and some have left the grid's last sort.
World mixedTank(Solver solver, uint32_t workers) {
    WorldDef def;
    def.solver = solver;
    def.workerCount = workers;
    World world(def);
    const MaterialId w = world.addMaterial(water());
    world.addForce(std::make_unique<GravityForce>());
    world.addBoundary(std::make_unique<BoxContainer>(-0.4f, 0.0f, 0.4f, 0.8f));
    world.spawnBlob(latticeBlock(world, w, -0.4f, 0.0f, 30, 20));
    if (solver == Solver::PositionBased) {
        const MaterialId y = world.addMaterial(yoghurt());
        world.spawnBlob(latticeBlock(world, y, 0.05f, 0.3f, 12, 12));
    } else {
        world.spawnBlob(latticeBlock(world, w, 0.05f, 0.3f, 12, 12));
    }
    for (int frame = 0; frame < 12; ++frame) {
        world.step(kFrame);
    }
    return world;
}

Shape randomShape(std::mt19937& rng) {
    std::uniform_real_distribution<float> x(-0.5f, 0.5f), y(-0.1f, 0.6f), size(0.005f, 0.3f);
    switch (rng() % 3) {
    case 0: {
        // Each draw its own statement (a call's arguments are evaluated in an order the
        // compiler picks).
        const glm::vec2 a{x(rng), y(rng)};
        const float w = size(rng);
        const float h = size(rng);
        return Shape::box(a, a + glm::vec2(w, h));
    }
    case 1: {
        const glm::vec2 c{x(rng), y(rng)};
        return Shape::circle(c, size(rng));
    }
    default: {
        // A star-shaped polygon round a centre: simple, often concave.
        const glm::vec2 c{x(rng), y(rng)};
        const int n = 3 + int(rng() % 8);
        std::vector<glm::vec2> v;
        for (int k = 0; k < n; ++k) {
            const float a = 6.2831853f * float(k) / float(n);
            const float r = size(rng);
            v.push_back(c + r * glm::vec2(std::cos(a), std::sin(a)));
        }
        return Shape::polygon(v);
    }
    }
}

// A force plugin whose prepare queries the world that runs it.
class Hook final : public ForcePlugin {
public:
    static constexpr std::array<ParamDecl, 0> kParams{};
    explicit Hook(const World& w) : ForcePlugin("force.test-query", kParams), m_world(w) {}
    void prepare(const StepContext&) override {
        try {
            countParticles(m_world, Shape::circle({0.0f, 0.1f}, 0.1f));
            message = "no error";
        } catch (const Error& e) {
            code = e.code();
            message = e.what();
        }
    }
    void apply(const ForceContext&, uint32_t, uint32_t) override {}
    std::string message;
    ErrorCode code = ErrorCode::BadArgument;

private:
    const World& m_world;
};

} // namespace

TEST_CASE("queries: the particles in a shape are exactly those a scan finds, in index order",
          "[unit][queries]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    const World world = mixedTank(solver, 1);
    std::mt19937 rng(7);
    uint32_t nonEmpty = 0;
    for (int k = 0; k < 120; ++k) {
        const Shape region = randomShape(rng);
        CAPTURE(k, int(region.type));
        const std::vector<uint32_t> expected = bruteForce(world, region);
        nonEmpty += expected.empty() ? 0u : 1u;
        REQUIRE(queried(world, region) == expected);
        // The buffer form: the same handles, truncated to the buffer, the whole count returned.
        std::vector<ParticleHandle> handles(expected.size() / 2);
        CHECK(queryParticles(world, region, handles) == expected.size());
        for (std::size_t j = 0; j < handles.size(); ++j) {
            CHECK(handles[j] == world.handleAt(expected[j]));
        }
        // By material.
        std::vector<uint32_t> perMaterial(world.materialCount(), 99);
        CHECK(countParticles(world, region, perMaterial) == expected.size());
        uint32_t sum = 0;
        for (uint32_t m = 0; m < world.materialCount(); ++m) {
            uint32_t n = 0;
            for (const uint32_t i : expected) {
                n += world.materialIndex()[i] == m ? 1u : 0u;
            }
            CHECK(perMaterial[m] == n);
            sum += perMaterial[m];
        }
        CHECK(sum == expected.size());
    }
    CHECK(nonEmpty > 40);
    // A region larger than the world holds every particle (the scan path).
    CHECK(queried(world, Shape::box({-1e4f, -1e4f}, {1e4f, 1e4f})).size() == world.particleCount());
}

TEST_CASE("queries: boxes, early stops, far and empty regions", "[unit][queries]") {
    World world = mixedTank(Solver::PositionBased, 1);
    // queryBox: edges included, a zero-width box allowed.
    const glm::vec2 p{world.positionX()[5], world.positionY()[5]};
    std::vector<uint32_t> atPoint;
    queryBox(world, p, p, [&](const QueryHit& hit) {
        atPoint.push_back(hit.index);
        return true;
    });
    CHECK(std::find(atPoint.begin(), atPoint.end(), 5u) != atPoint.end());
    const Shape all = Shape::box({-0.4f, 0.0f}, {0.4f, 0.8f});
    const std::vector<uint32_t> everything = bruteForce(world, all);
    REQUIRE(everything.size() > 100);
    std::vector<uint32_t> boxed;
    CHECK(queryBox(world, {-0.4f, 0.0f}, {0.4f, 0.8f}, [&](const QueryHit& hit) {
              boxed.push_back(hit.index);
              return true;
          }) == everything.size());
    CHECK(boxed == everything);
    // The visitor stops the query: it saw the first ten, in order.
    std::vector<uint32_t> first;
    CHECK(queryParticles(world, all, [&](const QueryHit& hit) {
              first.push_back(hit.index);
              return first.size() < 10;
          }) == 10);
    CHECK(first == std::vector<uint32_t>(everything.begin(), everything.begin() + 10));
    // Far from the liquid (a hashed cell range far out) and in an empty world: nothing.
    CHECK(queried(world, Shape::circle({5e4f, -5e4f}, 1.0f)).empty());
    World empty;
    empty.addMaterial(water());
    CHECK(countParticles(empty, all) == 0);
    // A change to the world rebuilds the grid: a particle added is found at once, one removed
    // is gone.
    const ParticleHandle added = world.addParticle({0.3f, 0.7f}, {0.0f, 0.0f}, MaterialId{0});
    const Shape corner = Shape::circle({0.3f, 0.7f}, 0.001f);
    std::vector<ParticleHandle> found(4);
    REQUIRE(queryParticles(world, corner, found) == 1);
    CHECK(found[0] == added);
    world.removeParticle(added);
    CHECK(queryParticles(world, corner, found) == 0);
}

TEST_CASE("queries: the same particles in the same order for 1, 2 and 4 workers and after a "
          "save and load",
          "[unit][queries]") {
    std::vector<std::vector<uint32_t>> results;
    std::mt19937 rng(11);
    std::vector<Shape> regions;
    for (int k = 0; k < 40; ++k) {
        regions.push_back(randomShape(rng));
    }
    for (const uint32_t workers : {1u, 2u, 4u}) {
        const World world = mixedTank(Solver::PositionBased, workers);
        std::vector<uint32_t> all;
        for (const Shape& r : regions) {
            queryParticles(world, r, [&](const QueryHit& hit) {
                all.push_back(hit.index);
                all.push_back(hit.handle.slot);
                return true;
            });
        }
        results.push_back(all);
        if (workers == 2) {
            std::stringstream bytes;
            world.save(bytes);
            Registry registry;
            registerBuiltinPlugins(registry);
            const World loaded = World::load(bytes, registry, 1);
            std::vector<uint32_t> again;
            for (const Shape& r : regions) {
                queryParticles(loaded, r, [&](const QueryHit& hit) {
                    again.push_back(hit.index);
                    again.push_back(hit.handle.slot);
                    return true;
                });
            }
            CHECK(again == all);
        }
    }
    CHECK(results[1] == results[0]);
    CHECK(results[2] == results[0]);
}

TEST_CASE("queries: from several threads at once between steps", "[unit][queries]") {
    World world = mixedTank(Solver::PositionBased, 1);
    world.step(kFrame); // the grid is stale: the threads race to build it
    std::mt19937 rng(3);
    std::vector<Shape> regions;
    std::vector<std::vector<uint32_t>> expected;
    for (int k = 0; k < 64; ++k) {
        regions.push_back(randomShape(rng));
        expected.push_back(bruteForce(world, regions.back()));
    }
    std::vector<uint32_t> wrong(4, 0);
    std::vector<std::thread> threads;
    for (uint32_t t = 0; t < 4; ++t) {
        threads.emplace_back([&, t] {
            for (std::size_t k = 0; k < regions.size(); ++k) {
                std::vector<uint32_t> got;
                queryParticles(world, regions[(k + t * 16) % regions.size()],
                               [&](const QueryHit& hit) {
                                   got.push_back(hit.index);
                                   return true;
                               });
                wrong[t] += got == expected[(k + t * 16) % regions.size()] ? 0u : 1u;
            }
        });
    }
    for (std::thread& t : threads) {
        t.join();
    }
    CHECK(wrong == std::vector<uint32_t>(4, 0));
}

TEST_CASE("queries: bad regions and queries during a step are refused", "[unit][queries]") {
    World world = mixedTank(Solver::PositionBased, 1);
    const auto none = [](const QueryHit&) { return true; };
    CHECK_THROWS_WITH(queryParticles(world, Shape::circle({std::nanf(""), 0.0f}, 0.1f), none),
                      Catch::StartsWith("queryParticles: ") && Catch::Contains("not finite"));
    CHECK_THROWS_WITH(queryParticles(world, Shape::circle({0.0f, 0.0f}, -1.0f), none),
                      Catch::StartsWith("queryParticles: "));
    CHECK_THROWS_WITH(
        queryBox(world, {0.0f, 0.0f}, {-1.0f, 1.0f}, none),
        "queryBox: the box [0, -1] x [0, 1] is not finite or inverted; expected finite lo <= hi "
        "on both axes (unit: m)");
    CHECK_THROWS_WITH(queryBox(world, {0.0f, 0.0f}, {INFINITY, 1.0f}, none),
                      Catch::StartsWith("queryBox: the box [0, inf]"));
    CHECK_THROWS_WITH(queryParticles(world, Shape::circle({0.0f, 0.0f}, 0.1f), QueryVisitor{}),
                      "queryParticles: the visitor is empty");
    // From a plugin's hook during the step: refused, not a race with the step.
    auto& hook = static_cast<Hook&>(world.addForce(std::make_unique<Hook>(world)));
    world.step(kFrame);
    CHECK(hook.code == ErrorCode::WrongState);
    CHECK(hook.message == "countParticles: called during the world's own step (from a plugin's "
                          "hook or a task); query the world between its steps");
}

// hello_fluid: the copy-paste starter for fluid. A tank 0.6 m wide and 0.8 m tall, a block of
// water standing in its left part and a ball of yoghurt dropped from above; two seconds of
// simulation printed as a table. Units are SI everywhere (m, s, kg, kg/m^3); y points up and the
// tank floor is at y = 0.
#include <fluid/fluid.h> // the umbrella header: World, materials, registry, built-in plugins

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>

int main() {
    // Every WorldDef field has a usable default: the position-based solver's game preset (4
    // sub-steps per frame, each one constraint sweep and the coarse pressure correction), one
    // thread (set workerCount for more; the result is bit-identical whatever the count).
    // WorldDef::solver = fluid::Solver::Explicit selects the seed's explicit SPH loop instead.
    fluid::World world{fluid::WorldDef{}};

    // Materials are plain values (tweak any field before adding); the world answers with an id.
    // The first material also sets the spacing of the walls' boundary samples.
    const fluid::MaterialId water = world.addMaterial(fluid::water());
    const fluid::MaterialId yoghurt = world.addMaterial(fluid::yoghurt());

    // Forces and boundaries are plugins, created by string type as a level file names them.
    fluid::Registry registry;
    fluid::registerBuiltinPlugins(registry); // "force.gravity" and "boundary.box"
    // Gravity's parameters default to (gx, gy) = (0, -9.81) m/s^2.
    world.addForce(registry.createForce("force.gravity"));
    // The tank: inner rectangle [0, 0.6] x [0, 0.8] m. Values are checked against the ranges the
    // plugin declares (a bad one throws fluid::Error naming key, value, range and unit).
    const std::array<fluid::ParamValue, 4> tank{
        {{"minX", 0.0}, {"minY", 0.0}, {"maxX", 0.6}, {"maxY", 0.8}}};
    world.addBoundary(registry.createBoundary("boundary.box", tank));

    // A water block 0.1 m wide and 0.2 m tall against the left wall. Blobs are filled on a
    // square lattice at the material's spacing (about 0.01 m, one particle per ~1 cm^2). Cost
    // grows with the particle count: this block is kept small so the demo runs in seconds.
    fluid::BlobDef block;
    block.shape = fluid::Shape::box({0.0f, 0.0f}, {0.1f, 0.2f}); // m: lower-left, upper-right
    block.material = water;
    const uint32_t waterCount = world.spawnBlob(block);

    // A yoghurt ball of radius 5 cm, centred 0.45 m up on the right, falling from rest.
    fluid::BlobDef ball;
    ball.shape = fluid::Shape::circle({0.4f, 0.45f}, 0.05f); // m: centre, radius
    ball.material = yoghurt;
    const uint32_t yoghurtCount = world.spawnBlob(ball);

    // Slots move every sub-step (particles are sorted by grid cell); a handle keeps naming one
    // particle. The last one spawned is the top of the yoghurt ball.
    const fluid::ParticleHandle top = world.handleAt(world.particleCount() - 1);
    const glm::vec2 start = world.position(top);

    std::printf("hello_fluid: a 0.6 m x 0.8 m tank with a water block (%u particles) on the left\n"
                "and a yoghurt ball (%u particles) dropped from y = %.2f m; 2 s in 120 frames of "
                "1/60 s\n\n",
                waterCount, yoghurtCount, ball.shape.center.y);
    // Columns: simulated time, particle count, sub-steps of the last frame, fastest particle,
    // lowest and highest particle, mean density per material, wall time of the last step.
    std::printf("%5s %9s %9s %10s %8s %8s %13s %13s %8s\n", "t [s]", "particles", "sub-steps",
                "vmax [m/s]", "ymin [m]", "ymax [m]", "water [kg/m3]", "yogh. [kg/m3]", "step ms");

    const float frameDt = 1.0f / 60.0f; // s: one game frame
    const auto wallStart = std::chrono::steady_clock::now();
    uint64_t totalSubsteps = 0;
    for (int frame = 1; frame <= 120; ++frame) {
        // One frame, split into PositionBasedDef::substeps sub-steps (4); profile() says how
        // many sub-steps and constraint iterations it took and how compressed the water is.
        world.step(frameDt);
        totalSubsteps += world.lastSubsteps();
        if (frame % 10 != 0) {
            continue;
        }
        // Reads are spans over the particle arrays, valid until the next step/add/remove.
        const auto py = world.positionY(); // y per slot (m)
        const auto vx = world.velocityX(), vy = world.velocityY();
        const auto rho = world.density();
        const auto mat = world.materialIndex();
        float vmax = 0.0f, ymin = 1e9f, ymax = -1e9f;
        double rhoSum[2] = {0.0, 0.0};
        uint32_t rhoCount[2] = {0, 0};
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            vmax = std::max(vmax, std::hypot(vx[i], vy[i]));
            ymin = std::min(ymin, py[i]);
            ymax = std::max(ymax, py[i]);
            rhoSum[mat[i]] += rho[i]; // material index: 0 water, 1 yoghurt (order added)
            ++rhoCount[mat[i]];
        }
        // profile() holds the last step's timings (ms) and counters.
        const fluid::Profile& prof = world.profile();
        std::printf("%5.2f %9u %9u %10.3f %8.3f %8.3f %13.1f %13.1f %8.1f\n", world.time(),
                    prof.particles, prof.substeps, vmax, ymin, ymax, rhoSum[0] / rhoCount[0],
                    rhoSum[1] / rhoCount[1], prof.step);
    }
    const double wallSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();

    std::printf("\nsummary: %.2f s simulated in %.2f s of wall time (%.0f ms per frame), %.1f "
                "sub-steps per frame\n",
                world.time(), wallSeconds, wallSeconds * 1000.0 / 120.0,
                double(totalSubsteps) / 120.0);

    // The handle still names the same particle although its slot changed many times.
    const glm::vec2 end = world.position(top);
    std::printf("handle:  top of the yoghurt ball moved from (%.3f, %.3f) to (%.3f, %.3f) m\n",
                start.x, start.y, end.x, end.y);
    // Removing the particle makes every copy of the handle stale: isValid says false.
    world.removeParticle(top);
    std::printf("handle:  removed it; isValid = %s, %u particles left\n",
                world.isValid(top) ? "true" : "false", world.particleCount());

    // Bad input throws fluid::Error (one exception type) and leaves the world unchanged.
    try {
        world.step(-1.0f);
    } catch (const fluid::Error& error) {
        std::printf("error:   world.step(-1) threw fluid::Error: %s\n", error.what());
    }
    return 0;
}

// Smallest game-like use of fluid: build a world from its definition, give it a material, a
// blob, gravity and a tank, and step it once. Built with the optional components too, it also
// calls into each (FLUID_CONSUMER_WITH_BOX2D, _LEVEL, _GL, _C, set by CMakeLists.txt), so that the
// link proves their targets carry what they need.
// Compiled by tests/install/check_install.cmake against the installed package and against
// the source tree added with add_subdirectory().
#include <fluid/fluid.h>

#if defined(FLUID_CONSUMER_WITH_BOX2D)
#include <box2d/box2d.h>
#include <fluid/box2d/coupling.h>
#endif
#if defined(FLUID_CONSUMER_WITH_LEVEL)
#include <fluid/level.h>
#endif
#if defined(FLUID_CONSUMER_WITH_C)
#include <fluid/c.h>
#endif
#if defined(FLUID_CONSUMER_WITH_GL)
#include <fluid/gl/camera.h>
#include <fluid/gl/renderer.h>
#endif

#include <cmath>
#include <cstdio>
#include <memory>

namespace {

// The core: a block of water in a tank, one step. False if it went wrong.
bool runCore() {
    fluid::World world{fluid::WorldDef{}};
    const fluid::MaterialId water = world.addMaterial(fluid::water());
    world.addForce(std::make_unique<fluid::GravityForce>());
    world.addBoundary(std::make_unique<fluid::BoxContainer>(-0.2f, 0.0f, 0.2f, 0.4f));
    fluid::BlobDef blob;
    blob.shape.halfExtents = {0.05f, 0.05f};
    blob.shape.center = {0.0f, 0.06f};
    blob.material = water;
    const unsigned count = world.spawnBlob(blob);
    world.step(1.0f / 60.0f);
    const float y = world.positionY()[0];
    std::printf("fluid consumer: %u particles, %u sub-steps\n", count, world.lastSubsteps());
    return count > 0 && std::isfinite(y);
}

#if defined(FLUID_CONSUMER_WITH_BOX2D)
// fluid::box2d: a ball dropped into water, coupled both ways, one frame.
bool runBox2d() {
    fluid::World world{fluid::WorldDef{}};
    const fluid::MaterialId water = world.addMaterial(fluid::water());
    world.addForce(std::make_unique<fluid::GravityForce>());
    world.addBoundary(std::make_unique<fluid::BoxContainer>(-0.2f, 0.0f, 0.2f, 0.4f));
    fluid::BlobDef blob;
    blob.shape.halfExtents = {0.1f, 0.05f};
    blob.shape.center = {0.0f, 0.06f};
    blob.material = water;
    world.spawnBlob(blob);
    b2World physics(b2Vec2(0.0f, -9.81f));
    b2BodyDef bodyDef;
    bodyDef.type = b2_dynamicBody;
    bodyDef.position.Set(0.0f, 0.15f);
    b2Body* ball = physics.CreateBody(&bodyDef);
    b2CircleShape circle;
    circle.m_radius = 0.03f;
    ball->CreateFixture(&circle, 500.0f);
    fluid::box2d::Coupling coupling(world, physics);
    coupling.step(world, 1.0f / 60.0f);
    const float y = ball->GetPosition().y;
    std::printf("fluid consumer: box2d ball at y = %.4f m\n", static_cast<double>(y));
    return std::isfinite(y);
}
#endif

#if defined(FLUID_CONSUMER_WITH_LEVEL)
// fluid::level: a level with water and a ball read from text, one frame.
bool runLevel() {
    fluid::Registry registry;
    fluid::registerBuiltinPlugins(registry);
    fluid::Level level = fluid::parseLevel(
        R"({"version": 1, "world": {"gravity": [0, -9.81]}, "materials": [{"name": "water"}],
  "plugins": [{"type": "boundary.box", "params": {"minX": 0, "minY": 0, "maxX": 0.3, "maxY": 0.5}}],
  "blobs": [{"material": "water", "shape": "box", "min": [0, 0], "max": [0.3, 0.1]}],
  "bodies": [{"name": "ball", "position": [0.15, 0.13], "fixtures": [{"shape": "circle", "radius": 0.04, "densityRatio": 0.5}]}]})",
        "consumer.json", registry);
    level.step();
    std::printf("fluid consumer: level with %zu bodies, %u particles\n", level.bodies.size(),
                level.world.particleCount());
    return level.physics != nullptr && level.bodies.size() == 1 && level.world.particleCount() > 0;
}
#endif

#if defined(FLUID_CONSUMER_WITH_GL)
// fluid::gl: no context here, so only the pure-math camera runs; loadFunctions is linked.
bool runGl() {
    void (*load)() = &fluid::gl::loadFunctions;
    const fluid::gl::Camera camera =
        fluid::gl::Camera::fit({0.0f, 0.0f}, {1.0f, 1.0f}, {640, 360}, 0.0f);
    const glm::vec2 pixel = camera.worldToPixel({0.5f, 0.5f});
    std::printf("fluid consumer: gl camera maps the centre to (%.1f, %.1f) px\n",
                static_cast<double>(pixel.x), static_cast<double>(pixel.y));
    return load != nullptr && std::fabs(pixel.x - 320.0f) < 0.5f && std::fabs(pixel.y - 180.0f) < 0.5f;
}
#endif

#if defined(FLUID_CONSUMER_WITH_C)
// fluid::c: a world through the C API, water by preset, gravity by name, one step.
bool runC() {
    fluid_world_def def = fluid_default_world_def();
    fluid_world* world = nullptr;
    fluid_material_def water{};
    fluid_material_id id{};
    fluid_plugin_id plugin{};
    fluid_blob_def blob = fluid_default_blob_def();
    uint32_t count = 0;
    blob.shape = fluid_box_shape({0.0f, 0.0f}, {0.1f, 0.1f});
    const bool ok = fluid_version() / 100 == FLUID_C_VERSION_MAJOR &&
                    fluid_world_create(&def, &world) == FLUID_OK &&
                    fluid_material_preset("water", &water) == FLUID_OK &&
                    fluid_world_add_material(world, &water, &id) == FLUID_OK &&
                    fluid_world_add_plugin(world, "force.gravity", nullptr, 0, &plugin) ==
                        FLUID_OK &&
                    (blob.material = id, fluid_world_spawn_blob(world, &blob, &count)) ==
                        FLUID_OK &&
                    fluid_world_step(world, 1.0f / 60.0f) == FLUID_OK;
    std::printf("fluid consumer: C API %u, %u particles%s%s\n", fluid_version(), count,
                ok ? "" : ": ", ok ? "" : fluid_last_error());
    fluid_world_destroy(world);
    return ok && count > 0;
}
#endif

} // namespace

int main() {
    bool ok = runCore();
#if defined(FLUID_CONSUMER_WITH_BOX2D)
    ok = runBox2d() && ok;
#endif
#if defined(FLUID_CONSUMER_WITH_LEVEL)
    ok = runLevel() && ok;
#endif
#if defined(FLUID_CONSUMER_WITH_GL)
    ok = runGl() && ok;
#endif
#if defined(FLUID_CONSUMER_WITH_C)
    ok = runC() && ok;
#endif
    return ok ? 0 : 1;
}

// A core-only game: a world, a material, a blob, a few steps, and the particle count checked.
// Built by tests/install/check_install.cmake against the installed package, configured as on a
// machine without Box2D, nlohmann_json, OpenGL or GLEW.
#include <fluid/fluid.h>

#include <cmath>
#include <cstdio>
#include <memory>

int main() {
    fluid::World world{fluid::WorldDef{}};
    const fluid::MaterialId water = world.addMaterial(fluid::water());
    world.addForce(std::make_unique<fluid::GravityForce>());
    world.addBoundary(std::make_unique<fluid::BoxContainer>(-0.2f, 0.0f, 0.2f, 0.4f));
    fluid::BlobDef blob;
    blob.shape.halfExtents = {0.05f, 0.05f};
    blob.shape.center = {0.0f, 0.06f};
    blob.material = water;
    const unsigned spawned = world.spawnBlob(blob);
    for (int frame = 0; frame < 3; ++frame) {
        world.step(1.0f / 60.0f);
    }
    const unsigned count = world.particleCount();
    const float y = world.positionY()[0];
    std::printf("fluid core consumer: %u particles spawned, %u after 3 steps\n", spawned, count);
    return spawned > 0 && count == spawned && std::isfinite(y) ? 0 : 1;
}

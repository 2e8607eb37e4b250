// Smallest game-like use of fluid: build a world from its definition, give it a material, a
// blob, gravity and a tank, and step it once.
// Compiled by tests/install/check_install.cmake against the installed package and against
// the source tree added with add_subdirectory().
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
    const unsigned count = world.spawnBlob(blob);
    world.step(1.0f / 60.0f);
    const float y = world.positionY()[0];
    std::printf("fluid consumer: %u particles, %u sub-steps\n", count, world.lastSubsteps());
    return count > 0 && std::isfinite(y) ? 0 : 1;
}

// Smallest game-like use of fluid: build a world from its definition and step it once.
// Compiled by tests/install/check_install.cmake against the installed package and against
// the source tree added with add_subdirectory().
#include <fluid/fluid.h>

int main() {
    fluid::World world{fluid::WorldDef{}};
    world.step(1.0f / 60.0f);
    return 0;
}

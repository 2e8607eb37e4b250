// fluid — registration of the built-in plugins.
#include <fluid/plugins/box_container.h>
#include <fluid/plugins/builtin.h>
#include <fluid/plugins/gravity.h>

namespace fluid {

void registerBuiltinPlugins(Registry& registry) {
    registry.add<GravityForce>("Uniform gravity; (0, 0) for zero-g.");
    registry.add<BoxContainer>("Axis-aligned box container (a tank) with sampled walls.");
}

} // namespace fluid

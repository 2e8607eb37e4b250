// fluid — registration of the built-in boundary plugins.
#include <fluid/plugins/boundaries.h>
#include <fluid/plugins/builtin.h>

namespace fluid {

void registerBuiltinBoundaries(Registry& registry) {
    registry.add<BoxContainer>("Axis-aligned box container (a tank) with sampled walls.");
    registry.add<PolygonBoundary>(
        "Solid polygon (convex or concave) the fluid stays outside of; static or kinematic.");
    registry.add<ChainBoundary>(
        "Chain of thin wall segments (open or closed) neither side can cross; static or "
        "kinematic.");
    registry.add<CircleBoundary>("Solid disc the fluid stays outside of; static or kinematic.");
}

} // namespace fluid

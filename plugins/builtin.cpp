// fluid — registration of the built-in plugins: the forces and the boundaries, each with its
// one line for humans (`PluginInfo::description`).
#include <fluid/plugins/boundaries.h>
#include <fluid/plugins/builtin.h>
#include <fluid/plugins/forces.h>

namespace fluid {

void registerBuiltinForces(Registry& registry) {
    registry.add<GravityForce>("Uniform gravity; (0, 0) for zero-g.");
    registry.add<PointGravityForce>(
        "Pull towards a point, softened, falling off as 1/r^n (planetoids, zero-g levels).");
    registry.add<VortexForce>(
        "Whirlpool: drives the swirl towards a Rankine vortex (CCW for positive speed).");
    registry.add<WindForce>("Drag towards a wind velocity, in a region or everywhere.");
    registry.add<PointerForce>(
        "Push (strength > 0) or pull around a point the host moves each frame (the mouse).");
    registry.add<ExplosionForce>(
        "One-shot radial impulse, fired at the next step after trigger = 1.");
    registry.add<DampingZoneForce>("Slows particles inside a rectangle: speed ~ exp(-rate t).");
}

void registerBuiltinBoundaries(Registry& registry) {
    registry.add<BoxContainer>("Axis-aligned box container (a tank) with sampled walls.");
    registry.add<PolygonBoundary>(
        "Solid polygon (convex or concave) the fluid stays outside of; static or kinematic.");
    registry.add<ChainBoundary>(
        "Chain of thin wall segments (open or closed) neither side can cross; static or "
        "kinematic.");
    registry.add<CircleBoundary>("Solid disc the fluid stays outside of; static or kinematic.");
}

void registerBuiltinPlugins(Registry& registry) {
    registerBuiltinForces(registry);
    registerBuiltinBoundaries(registry);
}

} // namespace fluid

// fluid — registration of the built-in force plugins.
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

} // namespace fluid

// custom_force: a user-written force plugin, a whirlpool, registered like the built-in plugins.
// Compile with -DFLUID_EXAMPLE_NO_MAIN to reuse the plugin (e.g. in a test) without main().
#include "custom_force.h"

#include <fluid/fluid.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

// [docs/plugins.md: A force] (docs/plugins.md quotes the lines up to the end marker; a test
// checks that they match.)
/// "force.whirlpool": a counter-clockwise swirl around (cx, cy). The tangential acceleration
/// rises linearly from 0 at the centre to `strength` at `radius`, then eases smoothly to 0 at
/// twice the radius; `pull` adds the same profile pointing inward. Thread rule: see ForcePlugin.
class WhirlpoolForce : public fluid::ForcePlugin {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "force.whirlpool";
    /// Parameters, in the order `apply` reads them.
    static constexpr std::array<fluid::ParamDecl, 5> kParams{{
        {"cx", "m", 0.0, -1e5, 1e5, "Centre x."},
        {"cy", "m", 0.0, -1e5, 1e5, "Centre y."},
        {"strength", "m/s^2", 1.0, -1e3, 1e3, "Tangential acceleration at the radius (CCW > 0)."},
        {"radius", "m", 0.2, 1e-3, 1e3, "Where the swirl peaks; it is 0 beyond twice this."},
        {"pull", "m/s^2", 0.0, -1e3, 1e3, "Inward acceleration at the radius (optional)."},
    }};
// [end]
    /// A whirlpool with the default parameters.
    WhirlpoolForce() : fluid::ForcePlugin(kType, kParams) {}
    /// Adds the swirl to particles [begin, end), writing only their own slots.
    void apply(const fluid::ForceContext& ctx, uint32_t begin, uint32_t end) override {
        const auto cx = float(value(0)), cy = float(value(1)), strength = float(value(2));
        const auto radius = float(value(3)), pull = float(value(4));
        for (uint32_t i = begin; i < end; ++i) {
            const float dx = ctx.particles.px[i] - cx, dy = ctx.particles.py[i] - cy;
            const float r = std::sqrt(dx * dx + dy * dy);
            // Profile f: r/R inside, then a smoothstep from 1 at R down to 0 at 2R and beyond.
            const float t = std::clamp(r / radius - 1.0f, 0.0f, 1.0f);
            const float f = r < radius ? r / radius : 1.0f - t * t * (3.0f - 2.0f * t);
            // (-dy, dx)/r turns counter-clockwise, -(dx, dy)/r points in; the centre gets 0.
            const float s = r > 1e-6f ? f / r : 0.0f;
            ctx.ax[i] += s * (-strength * dy - pull * dx);
            ctx.ay[i] += s * (strength * dx - pull * dy);
        }
    }
};

void registerWhirlpool(fluid::Registry& registry) {
    registry.add<WhirlpoolForce>("Counter-clockwise whirlpool with an optional inward pull.");
}

#ifndef FLUID_EXAMPLE_NO_MAIN
int main() {
    fluid::World world; // no gravity plugin is added: zero gravity
    const fluid::MaterialId water = world.addMaterial(fluid::water());
    fluid::Registry registry;
    registerWhirlpool(registry); // add fluid::registerBuiltinPlugins(registry) for the others
    // Parameters by name (m/s^2, m, m/s^2); cx and cy keep their defaults (0, 0).
    const fluid::ParamValue swirl[] = {{"strength", 1.0}, {"radius", 0.3}, {"pull", 2.0}};
    world.addForce(registry.createForce("force.whirlpool", swirl));
    fluid::BlobDef blob; // a round blob of water, radius 0.15 m, centred on the whirlpool
    blob.shape = fluid::Shape::circle({0.0f, 0.0f}, 0.15f), blob.material = water;
    std::printf("custom_force: %u water particles in zero gravity, whirlpool at (0, 0), 2 s\n"
                "t [s]  Lz [kg m^2/s] (angular momentum about the centre)\n",
                world.spawnBlob(blob));
    for (int line = 1; line <= 10; ++line) {
        for (int frame = 0; frame < 12; ++frame) {
            world.step(1.0f / 60.0f); // 12 frames of 1/60 s: a line every 0.2 s
        }
        // Lz = sum m (x vy - y vx); it grows sub-linearly: viscosity brakes a rigid spin too.
        const auto px = world.positionX(), py = world.positionY();
        const auto vx = world.velocityX(), vy = world.velocityY();
        double lz = 0.0, mass = world.material(water).mass; // mass: kg per particle
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            lz += mass * (double(px[i]) * vy[i] - double(py[i]) * vx[i]);
        }
        std::printf("%5.2f  %.5f\n", world.time(), lz);
    }
}
#endif

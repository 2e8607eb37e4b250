// fluid-float: one Box2D body floating in a tank of resting water (or yoghurt), coupled by
// fluid::box2d::Coupling; prints how deep it floats against Archimedes and how still it holds.
//
//   fluid-float [--shape box|circle] [--ratio R] [--size N] [--depth D] [--width W]
//               [--quality game|precise] [--seconds T] [--threads K] [--drop]
//               [--substeps S] [--iterations I] [--coarse C] [--hold MM] [--trace]
//               [--material water|yoghurt] [--yield-stress Y] [--surface-tension G]
//               [--shear-constraint 0|1] [--guided] [--no-body] [--doubled]
//
// The tank: W m wide (default 0.6), water D m deep (default 0.2), gravity (0, -9.81) m/s^2. The
// body: a box N water spacings wide and 2N/3 tall, or a circle N spacings across (default 12),
// R times water's areal density (default 0.5). It starts at its exact Archimedes draft with the
// water it displaces left out of the tank (so the surface stays at D), or with --drop with its
// bottom on the surface. After T seconds (default 10) of 60 Hz frames, over the last second:
// the waterline is read from the particles left and right of the body, one support radius from
// it and from the walls, and the body's area below it exactly from its shape and pose. The
// last line is machine-readable:
//   shape=S ratio=R size=N depth=D quality=Q submerged=F error=E high_mm=H speed=V spin=W
//   reported=F2 gap=G particles=P ms_per_frame=M ... water_mean=VM water_max=VX
// water_mean and water_max: the particles' mean and largest speed over the last two seconds
// (m/s; the mean over particles and frames). --no-body leaves the body out (a resting tank);
// --doubled couples the Box2D tank's static walls too, so the floor and walls are there twice
// (the fluid's box and Box2D's), as a user gets who does not filter Box2D's walls out.
// error: submerged fraction over R, minus 1 (negative: floats too high); high_mm: how far above
// its Archimedes draft the body's centre rides (mm; its bottom when upright); speed and spin: the
// largest over the last second (m/s, rad/s); reported: the coupling's submerged fraction (mean
// over the last second); gap: the body's bottom minus the highest particle centre under its
// middle half at the end (spacings). --hold MM holds the body MM above its draft (Box2D's
// gravity off, its pose reset every frame) and prints the fluid's force on it first; --trace
// prints its pose and velocity every frame of the last second.
//
// In yoghurt (--material yoghurt: the preset, with --yield-stress and --surface-tension if
// given) a box also reads the paste's bearing: carried = (R H - d) rho g / ((2 + pi) tau_y), H
// its height and d its draft: what the paste carries under its base beyond its buoyancy, over
// Prandtl's strip footing (1: Prandtl's; 0: a liquid's). --guided keeps the body from turning
// (a footing in a load test: a narrow box that tips reads nothing).
#include "command_line.h"

#include <fluid/box2d/coupling.h>
#include <fluid/fluid.h>

#include <box2d/box2d.h>

#include <CLI/CLI.hpp>

#include "box2d_support.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using namespace fluid;
using namespace fluid::test;

struct Options {
    std::string shape = "box";
    float ratio = 0.5f;
    float size = 12.0f;
    float depth = 0.2f;
    float width = 0.6f;
    std::string quality{fluid::qualityName(fluid::Quality::Game)};
    float seconds = 10.0f;
    uint32_t threads = 1;
    bool drop = false;
    uint32_t substeps = 0, iterations = 0;
    float coarse = -1.0f;
    float hold = NAN; // mm above the draft to hold the body at; NaN: free
    bool trace = false;
    std::string material = "water";
    float yieldStress = -1.0f;    // Pa; < 0: the preset's
    float surfaceTension = -1.0f; // < 0: the preset's
    uint32_t shearConstraint = fluid::PositionBasedDef{}.shearConstraint;
    bool guided = false;
    bool noBody = false;
    bool doubled = false;
};

// Height of the box's or circle's draft below its top... the draft d of a body of `ratio`:
// box: ratio times its height; circle: the chord depth whose segment area is ratio pi r^2.
double archimedesDraft(bool circle, double ratio, double hh, double r) {
    if (!circle) {
        return ratio * 2.0 * hh;
    }
    double lo = 0.0, hi = 2.0 * r;
    for (int k = 0; k < 100; ++k) {
        const double d = 0.5 * (lo + hi);
        const double below = circleAreaBelow(0.0, r, d - r); // circle at 0, level d - r
        (below < ratio * std::numbers::pi * r * r ? lo : hi) = d;
    }
    return 0.5 * (lo + hi);
}

int run(const Options& opt) {
    WorldDef def;
    def.workerCount = opt.threads;
    def.positionBased = positionBasedPreset(qualityFromName(opt.quality).value_or(Quality::Game));
    if (opt.substeps > 0) {
        def.positionBased.substeps = opt.substeps;
    }
    if (opt.iterations > 0) {
        def.positionBased.iterations = opt.iterations;
    }
    if (opt.coarse >= 0.0f) {
        def.positionBased.coarseCorrection = opt.coarse;
    }
    def.positionBased.shearConstraint = opt.shearConstraint;
    World world(def);
    Material liquid = opt.material == "yoghurt" ? fluid::yoghurt() : fluid::water();
    if (opt.yieldStress >= 0.0f) {
        liquid.yieldStress = opt.yieldStress;
    }
    if (opt.surfaceTension >= 0.0f) {
        liquid.surfaceTension = opt.surfaceTension;
    }
    const MaterialId water = world.addMaterial(liquid);
    const float s = world.spacing(water);
    const float h = world.material(water).smoothingDistance;
    const auto cols = uint32_t(std::floor(opt.width / s));
    const auto rows = uint32_t(std::lround(opt.depth / s));
    const float width = float(cols) * s, surface = float(rows) * s, top = surface + 0.5f;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, width, top));
    b2World physics(b2Vec2(0.0f, -kG));
    addTankWalls(physics, 0.0f, 0.0f, width, top);

    const bool circle = opt.shape == "circle";
    const float hw = 0.5f * opt.size * s, hh = circle ? hw : hw * 2.0f / 3.0f;
    const double draft = archimedesDraft(circle, opt.ratio, hh, hw);
    const float rho = box2d::arealDensity(world, water);
    const bool held = std::isfinite(opt.hold);
    const float bottom = opt.drop ? surface
                         : held   ? surface - float(draft) + 0.001f * opt.hold
                                  : surface - float(draft);
    const glm::vec2 centre{0.5f * width, bottom + hh};
    b2Body* body = circle ? addCircle(physics, b2_dynamicBody, centre, hw, opt.ratio * rho)
                          : addBox(physics, b2_dynamicBody, centre, hw, hh, opt.ratio * rho);
    body->GetFixtureList()->SetFriction(0.0f);
    body->SetFixedRotation(opt.guided);
    if (opt.noBody) {
        physics.DestroyBody(body);
        body = nullptr;
    }
    box2d::CouplingDef cdef;
    cdef.categoryMask = opt.doubled ? uint16_t(0xFFFF) : kFluidMask;
    box2d::Coupling coupling(world, physics, cdef);
    // After the coupling: the blob leaves out the lattice points inside the body.
    world.spawnBlob(latticeBlock(world, water, 0.0f, 0.0f, cols, rows));

    const int frames = int(std::lround(opt.seconds * 60.0f)), window = 60;
    double submerged = 0.0, level = 0.0, lowest = 0.0, speed = 0.0, spin = 0.0, reported = 0.0;
    double seconds = 0.0, support = 0.0;
    const b2Vec2 pose = body != nullptr ? body->GetPosition() : b2Vec2(0.0f, 0.0f);
    const int waterWindow = std::min(frames, 120);
    double waterMean = 0.0, waterMax = 0.0;
    if (held && body != nullptr) {
        body->SetGravityScale(0.0f); // still during the fluid's step: the fluid's static force
    }
    for (int f = 0; f < frames; ++f) {
        const auto t0 = std::chrono::steady_clock::now();
        coupling.step(world, kFrame);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (f >= frames - waterWindow) {
            waterMean += meanSpeed(world) / waterWindow;
            waterMax = std::max(waterMax, double(maxSpeed(world)));
        }
        if (body == nullptr) {
            continue;
        }
        if (held) {
            if (f >= frames - window) {
                support += double(coupling.report(body)->force.y) / (double(body->GetMass()) * kG) /
                           window;
            }
            body->SetTransform(pose, 0.0f);
            body->SetLinearVelocity(b2Vec2(0.0f, 0.0f));
            body->SetAngularVelocity(0.0f);
        }
        if (f < frames - window) {
            continue;
        }
        const Immersion in = immersion(world, *body, s, width, h);
        submerged += in.submerged / window;
        reported += double(coupling.report(body)->submergedFraction) / window;
        level += in.level / window;
        lowest += (double(body->GetPosition().y) - hh) / window; // the bottom, upright
        speed = std::max(speed, length(toD(body->GetLinearVelocity())));
        if (opt.trace) {
            std::printf("frame %d: x %.4f y %.4f angle %+.4f vx %+.4f vy %+.4f omega %+.4f\n",
                        f + 1, double(body->GetPosition().x), double(body->GetPosition().y),
                        double(body->GetAngle()), double(body->GetLinearVelocity().x),
                        double(body->GetLinearVelocity().y), double(body->GetAngularVelocity()));
        }
        spin = std::max(spin, double(std::fabs(body->GetAngularVelocity())));
    }
    if (body == nullptr) {
        std::printf("depth=%.2f width=%.2f quality=%s doubled=%d particles=%u ms_per_frame=%.3f "
                    "water_mean=%.5f water_max=%.5f\n",
                    double(opt.depth), double(opt.width), opt.quality.c_str(), int(opt.doubled),
                    world.particleCount(), 1000.0 * seconds / frames, waterMean, waterMax);
        return allFinite(world) ? 0 : 1;
    }
    if (held) {
        std::printf("held %+.1f mm: the fluid's force %.4f of the weight; waterline %.4f m, "
                    "submerged %.4f (Archimedes' force: %.4f of the weight)\n",
                    double(opt.hold), support, level, submerged, submerged / double(opt.ratio));
    }
    // The gap under the body at the end: its bottom (upright) minus the highest particle centre
    // under its middle half.
    double gap = NAN;
    {
        const double xc = body->GetPosition().x, bottomY = body->GetPosition().y - hh;
        double highest = -1e9;
        const auto px = world.positionX(), py = world.positionY();
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            if (std::fabs(px[i] - xc) < 0.5 * hw && py[i] < bottomY + 0.5 * s) {
                highest = std::max(highest, double(py[i]));
            }
        }
        gap = (bottomY - highest) / s;
    }
    const double error = submerged / double(opt.ratio) - 1.0;
    const double high = lowest - (level - draft);
    // The paste's bearing beyond buoyancy over Prandtl's, as heads of the fluid (m).
    const Material& used = world.material(water);
    const double prandtl = (2.0 + std::numbers::pi) * double(used.yieldStress) /
                           (double(used.restDensity) * double(kG));
    const double carried =
        !circle && prandtl > 0.0 ? (double(opt.ratio) - submerged) * 2.0 * hh / prandtl : NAN;
    std::printf("shape=%s ratio=%.2f size=%.0f depth=%.2f quality=%s submerged=%.4f error=%+.4f "
                "high_mm=%+.2f speed=%.4f spin=%.4f reported=%.4f gap=%.2f particles=%u "
                "ms_per_frame=%.3f material=%s yield=%.1f carried=%.3f water_mean=%.5f "
                "water_max=%.5f\n",
                opt.shape.c_str(), double(opt.ratio), double(opt.size), double(opt.depth),
                opt.quality.c_str(), submerged, error, 1000.0 * high, speed, spin, reported, gap,
                world.particleCount(), 1000.0 * seconds / frames, opt.material.c_str(),
                double(used.yieldStress), carried, waterMean, waterMax);
    return allFinite(world) ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) {
    Options opt;
    CLI::App app{"fluid-float: one Box2D body floating in a tank of resting water or yoghurt"};
    app.add_option("--shape", opt.shape, "box or circle")->check(CLI::IsMember({"box", "circle"}));
    app.add_option("--ratio", opt.ratio, "body density over the fluid's (1)")
        ->check(CLI::Range(0.05, 4.0));
    app.add_option("--size", opt.size, "body width in the fluid's spacings (count)")
        ->check(CLI::Range(2.0, 200.0));
    app.add_option("--depth", opt.depth, "fluid depth (m)")->check(CLI::Range(0.05, 3.0));
    app.add_option("--width", opt.width, "tank width (m)")->check(CLI::Range(0.1, 10.0));
    app.add_option("--quality", opt.quality, "game or precise")
        ->check(CLI::IsMember(fluid::tools::namesOf(kQualityNames)));
    app.add_option("--seconds", opt.seconds, "simulated time (s)")->check(CLI::Range(1.5, 600.0));
    app.add_option("--threads", opt.threads, "worker threads")->check(CLI::Range(1, 64));
    app.add_flag("--drop", opt.drop, "start with the body's bottom on the surface");
    app.add_flag("--trace", opt.trace, "print the body's pose and velocity every measured frame");
    app.add_option("--hold", opt.hold,
                   "hold the body this far above its draft (mm) and print the fluid's force")
        ->check(CLI::Range(-500.0, 500.0));
    app.add_option("--substeps", opt.substeps, "override the preset's sub-steps")
        ->check(CLI::Range(1, 64));
    app.add_option("--iterations", opt.iterations, "override the preset's sweeps")
        ->check(CLI::Range(1, 64));
    app.add_option("--coarse", opt.coarse, "override the coarse correction's share (0 = off)")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--material", opt.material, "water or yoghurt (the presets)")
        ->check(CLI::IsMember({"water", "yoghurt"}));
    app.add_option("--yield-stress", opt.yieldStress, "override the material's yield stress (Pa)")
        ->check(CLI::Range(0.0, 1e5));
    app.add_option("--surface-tension", opt.surfaceTension,
                   "override the material's surface tension (m^3/(kg s^2))")
        ->check(CLI::Range(0.0, 0.5));
    app.add_option("--shear-constraint", opt.shearConstraint,
                   "1 (the default): yielding materials step with the shear constraint; 0: "
                   "with the stress pass")
        ->check(CLI::Range(0, 1));
    app.add_flag("--guided", opt.guided, "keep the body from turning");
    app.add_flag("--no-body", opt.noBody, "no body: the resting tank alone");
    app.add_flag("--doubled", opt.doubled,
                 "couple Box2D's static tank walls too: the floor and walls twice");
    if (const int status = fluid::tools::parseCommandLine(app, argc, argv); status >= 0) {
        return status;
    }
    return run(opt);
}

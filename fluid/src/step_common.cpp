// fluid — the parts of a step both solvers share: plugins, boundary samples, the grid sort,
// material constants, the safety-net projection and the density error.
#include "step_common.h"

#include "kernels.h"
#include "lanes.h"
#include "parallel.h"

#include <fluid/error.h>
#include <fluid/internal/checks.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace fluid::detail {

namespace {

// The largest mass a RigidBody may declare (kg).
constexpr float kMaxBodyMass = 1e9f;
// separateStacked: how far a particle found exactly on another is moved (unit: cell sizes, the
// largest support).
constexpr float kStackedNudge = 1.0f / 64.0f;
// The direction a particle stacked on another moves off in, picked by its slot: slots in a row
// spread over the circle (the golden ratio's steps, 4096 of them). A unit vector from +, -, *
// and / only (the circle's rational parametrisation), so the same bits on every platform: no
// C library's cos and sin, which round differently.
glm::vec2 stackedDirection(uint32_t slot) {
    const float step = float(slot % 4096u) * 0.618033988f;
    const float u = step - std::floor(step); // [0, 1)
    const bool left = u >= 0.5f;
    const float t = left ? 4.0f * u - 3.0f : 4.0f * u - 1.0f; // [-1, 1): a half circle each
    const float w = 1.0f / (1.0f + t * t);
    const glm::vec2 d{(1.0f - t * t) * w, 2.0f * t * w};
    return left ? -d : d;
}

// Cells per task of separateStacked (most hold one particle or none).
constexpr uint32_t kStackedGrain = 8192;

} // namespace

void refreshConstants(WorldState& s) {
    const size_t m = s.materials.size();
    s.constants.resize(m);
    s.yielding = false;
    for (size_t i = 0; i < m; ++i) {
        const Material& mat = s.materials[i];
        MaterialConstants& c = s.constants[i];
        c.yielding = hasYield(mat);
        c.yieldStress = mat.yieldStress;
        c.consistency = mat.consistency;
        c.flowIndex = mat.flowIndex;
        c.shearModulus = mat.shearModulus;
        s.yielding = s.yielding || c.yielding;
        c.mass = mat.mass;
        c.massPerDepth = mat.mass / s.def.depth;
        c.restDensity = mat.restDensity;
        c.viscosity = mat.viscosity;
        c.stiffness = mat.stiffness;
        c.taitB = 0.0f;
        c.backgroundPressure = 0.0f;
        c.support = mat.smoothingDistance;
        c.gamma = mat.surfaceTension;
        // The kernel sum V sum_j W_ij of a particle inside the material's square lattice.
        const double spacing = particleSpacing(mat, s.def.depth);
        const double h = mat.smoothingDistance;
        const int reach = static_cast<int>(std::ceil(h / spacing));
        double sum = 0.0, gradients = 0.0;
        c.neighbours = 0.0f;
        for (int a = -reach; a <= reach; ++a) {
            for (int b = -reach; b <= reach; ++b) {
                const double r = spacing * std::sqrt(double(a * a + b * b));
                if ((a != 0 || b != 0) && r < h) {
                    c.neighbours += 1.0f;
                    // |grad W|^2 = (kG / h^4 (1 - q)^3 r)^2, as pbfConstraint sums it.
                    const double t = 1.0 - r / h;
                    const double g = double(kG) * t * t * t * r / (h * h * h * h);
                    gradients += g * g;
                }
                sum += double(kernel::wendland(float(r), float(h)));
            }
        }
        c.lattice = float(sum * spacing * spacing);
        const double volume = spacing * spacing / double(c.lattice);
        c.diagonal = float(volume * volume * gradients / double(mat.mass));
    }
}

namespace {

// A boundary plugin's samples as its prepare left them: four arrays of one length, every value
// finite. Anything else refuses the step (before any particle moved: World::step puts the
// emitters back), naming the plugin and the first bad sample.
void checkSamples(const BoundaryPlugin& plugin, size_t index) {
    const BoundarySamples& b = plugin.samples();
    const std::string who = "World::step: boundary plugin " + std::to_string(index) + " (" +
                            internal::quoted(plugin.type()) + "): ";
    const size_t n = b.px.size();
    if (b.py.size() != n || b.vx.size() != n || b.vy.size() != n) {
        throw Error(who + "its samples' arrays have different lengths (px " + std::to_string(n) +
                        ", py " + std::to_string(b.py.size()) + ", vx " +
                        std::to_string(b.vx.size()) + ", vy " + std::to_string(b.vy.size()) +
                        "); lay samples with BoundarySamples::add",
                    ErrorCode::WrongState);
    }
    for (size_t i = 0; i < n; ++i) {
        if (std::isfinite(b.px[i]) && std::isfinite(b.py[i]) && std::isfinite(b.vx[i]) &&
            std::isfinite(b.vy[i])) {
            continue;
        }
        std::ostringstream text;
        text << who << "sample " << i << " at (" << b.px[i] << ", " << b.py[i]
             << ") with velocity (" << b.vx[i] << ", " << b.vy[i]
             << ") is not finite; a boundary plugin's prepare must lay finite samples";
        throw Error(text.str(), ErrorCode::WrongState);
    }
}

} // namespace

void gatherSamples(WorldState& s, const StepContext& context) {
    Samples& out = s.samples;
    out.pluginBegin.clear();
    size_t total = 0;
    for (size_t k = 0; k < s.boundaries.size(); ++k) {
        const auto& plugin = s.boundaries[k];
        plugin->prepare(context);
        checkSamples(*plugin, k);
        out.pluginBegin.push_back(static_cast<uint32_t>(total));
        total += plugin->samples().size();
    }
    out.pluginBegin.push_back(static_cast<uint32_t>(total));
    out.fx.assign(total, 0.0f);
    out.fy.assign(total, 0.0f);
    out.drag.assign(total, 0.0f);
    // The rigid bodies with a mass: unknowns of the position-based coarse solve.
    s.bodies.clear();
    out.bodyOf.assign(total, -1);
    for (size_t p = 0; p < s.boundaries.size(); ++p) {
        const std::span<const RigidBody> bodies = s.boundaries[p]->rigidBodies();
        const size_t count = s.boundaries[p]->samples().size();
        for (size_t b = 0; b < bodies.size(); ++b) {
            const RigidBody& rb = bodies[b];
            const auto fail = [&](const std::string& what) {
                throw Error(std::string(s.boundaries[p]->type()) + ": rigid body " +
                                std::to_string(b) + ": " + what,
                            ErrorCode::WrongState);
            };
            if (!(rb.mass >= 0.0f && rb.mass <= kMaxBodyMass)) {
                std::ostringstream text;
                text << "mass = " << rb.mass << " is out of range [0, 1e9] (unit: kg)";
                fail(text.str());
            }
            if (rb.sampleBegin > rb.sampleEnd || rb.sampleEnd > count) {
                fail("samples [" + std::to_string(rb.sampleBegin) + ", " +
                     std::to_string(rb.sampleEnd) + ") are not within the plugin's " +
                     std::to_string(count) + " samples");
            }
            if (rb.mass == 0.0f || rb.sampleBegin == rb.sampleEnd) {
                continue; // moved by the host only
            }
            BodyState body;
            body.plugin = uint32_t(p);
            body.index = uint32_t(b);
            body.sampleBegin = out.pluginBegin[p] + rb.sampleBegin;
            body.sampleEnd = out.pluginBegin[p] + rb.sampleEnd;
            body.mass = rb.mass;
            const auto index = int32_t(s.bodies.size());
            for (uint32_t k = body.sampleBegin; k < body.sampleEnd; ++k) {
                if (out.bodyOf[k] < 0) { // a sample listed twice stays with its first body
                    out.bodyOf[k] = index;
                }
            }
            s.bodies.push_back(body);
        }
    }
    gatherContactBodies(s, context);
}

void deliverBodyImpulses(WorldState& s, float frameDt) {
    std::vector<RigidBodyImpulse> impulses;
    for (size_t p = 0; p < s.boundaries.size(); ++p) {
        const size_t count = s.boundaries[p]->rigidBodies().size();
        if (count == 0) {
            continue;
        }
        impulses.assign(count, RigidBodyImpulse{});
        for (const BodyState& body : s.bodies) {
            if (body.plugin != p) {
                continue;
            }
            RigidBodyImpulse& out = impulses[body.index];
            out.impulse = glm::vec2(float(body.impulseX), float(body.impulseY));
            out.displacement =
                glm::vec2(body.dvx * frameDt + body.ox, body.dvy * frameDt + body.oy);
        }
        s.boundaries[p]->receiveBodyImpulses(impulses);
    }
}

// Positions of all samples at `t` seconds into the step, sorted by cell (rebuilt each sub-step
// only when some sample moves).
void placeSamples(WorldState& s, float t, float cellSize, bool rebuild) {
    Samples& out = s.samples;
    const uint32_t total = out.pluginBegin.empty() ? 0 : out.pluginBegin.back();
    if (!rebuild && out.size() == total) {
        return;
    }
    // Unsorted positions at time t, in concatenation order.
    std::vector<float> x(total), y(total), vx(total), vy(total), friction(total);
    for (size_t p = 0; p < s.boundaries.size(); ++p) {
        const BoundarySamples& bs = s.boundaries[p]->samples();
        const float f = s.boundaries[p]->friction();
        for (size_t k = 0; k < bs.size(); ++k) {
            const size_t i = out.pluginBegin[p] + k;
            x[i] = bs.px[k] + bs.vx[k] * t;
            y[i] = bs.py[k] + bs.vy[k] * t;
            vx[i] = bs.vx[k];
            vy[i] = bs.vy[k];
            friction[i] = f;
        }
    }
    // The coarse solve's corrections of the rigid bodies so far: an offset growing with the
    // velocity change.
    for (const BodyState& b : s.bodies) {
        if (b.dvx == 0.0f && b.dvy == 0.0f && b.ox == 0.0f && b.oy == 0.0f) {
            continue;
        }
        const float offX = b.dvx * t + b.ox, offY = b.dvy * t + b.oy;
        for (uint32_t i = b.sampleBegin; i < b.sampleEnd; ++i) {
            x[i] += offX;
            y[i] += offY;
            vx[i] += b.dvx;
            vy[i] += b.dvy;
        }
    }
    // Samples line the level's walls: cells of R (3x3 per query; clipping gains little along a
    // thin wall), and dense up to 2 cells per particle, because a hashed grid would slow every
    // particle's query (16k dam: 30% per frame).
    out.grid.build(x, y, cellSize, s.tasks, GridLayout{1, 1, 2 * size_t(s.particles.size())});
    const std::span<const uint32_t> order = out.grid.order();
    out.px.resize(total);
    out.py.resize(total);
    out.vx.resize(total);
    out.vy.resize(total);
    out.friction.resize(total);
    out.pressure.assign(total, 0.0f);
    out.source.assign(order.begin(), order.end());
    std::vector<uint8_t> wants(total, 0);
    for (size_t p = 0; p < s.boundaries.size(); ++p) {
        if (s.boundaries[p]->wantsForces()) {
            std::fill(wants.begin() + out.pluginBegin[p], wants.begin() + out.pluginBegin[p + 1],
                      uint8_t(1));
        }
    }
    // The samples of bodies that ask for contact events report their forces too (the events'
    // impulse), and the contact pass visits them.
    const std::vector<int32_t>& contactOf = s.contacts.bodyOf;
    s.contacts.samples.clear();
    if (!contactOf.empty()) {
        for (uint32_t i = 0; i < total; ++i) {
            wants[i] = contactOf[i] >= 0 ? uint8_t(1) : wants[i];
        }
    }
    out.reporting.clear();
    out.body.resize(total);
    for (uint32_t k = 0; k < total; ++k) {
        const uint32_t i = order[k];
        out.body[k] = out.bodyOf[i];
        out.px[k] = x[i];
        out.py[k] = y[i];
        out.vx[k] = vx[i];
        out.vy[k] = vy[i];
        out.friction[k] = friction[i];
        if (wants[i] != 0) {
            out.reporting.push_back(k);
        }
    }
    for (uint32_t k = 0; k < total && !contactOf.empty(); ++k) {
        if (contactOf[order[k]] >= 0) {
            s.contacts.samples.push_back(k);
        }
    }
}

bool samplesMove(const WorldState& s) {
    for (const auto& plugin : s.boundaries) {
        const BoundarySamples& bs = plugin->samples();
        for (size_t k = 0; k < bs.size(); ++k) {
            if (bs.vx[k] != 0.0f || bs.vy[k] != 0.0f) {
                return true;
            }
        }
    }
    return false;
}

ParticleView particleView(const WorldState& s) {
    const Particles& p = s.particles;
    return ParticleView{p.px, p.py, p.vx, p.vy, p.material, s.materials, p.size()};
}

void externalForces(WorldState& s, float dt, double time, std::vector<float>& ax,
                    std::vector<float>& ay) {
    Particles& p = s.particles;
    ax.resize(p.size());
    ay.resize(p.size());
    const ForceContext context{particleView(s), ax, ay, dt, time};
    const size_t plugins = s.forces.size();
    // Per plugin: the particles whose acceleration it made non-finite.
    std::vector<std::atomic<uint32_t>> dropped(plugins);
    parallelFor(s.tasks, p.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        std::fill(ax.begin() + b, ax.begin() + e, 0.0f);
        std::fill(ay.begin() + b, ay.begin() + e, 0.0f);
        std::vector<float> keepX, keepY; // the sums before the plugin (none before the first)
        for (size_t k = 0; k < plugins; ++k) {
            if (k > 0) {
                keepX.assign(ax.begin() + b, ax.begin() + e);
                keepY.assign(ay.begin() + b, ay.begin() + e);
            }
            s.forces[k]->apply(context, b, e);
            // A non-finite result drops this plugin's contribution to the particle only.
            uint32_t bad = 0;
            for (uint32_t i = b; i < e; ++i) {
                if (std::isfinite(ax[i]) && std::isfinite(ay[i])) {
                    continue;
                }
                ax[i] = k > 0 ? keepX[i - b] : 0.0f;
                ay[i] = k > 0 ? keepY[i - b] : 0.0f;
                ++bad;
            }
            if (bad > 0) {
                dropped[k].fetch_add(bad, std::memory_order_relaxed);
            }
        }
    });
    Profile& prof = s.profile;
    for (size_t k = 0; k < plugins; ++k) {
        const uint32_t count = dropped[k].load(std::memory_order_relaxed);
        if (count == 0) {
            continue;
        }
        prof.forceDropped += count;
        if (prof.forceDroppedPlugin < 0) {
            prof.forceDroppedPlugin = int32_t(k);
        }
    }
}

void sortParticles(WorldState& s, float cellSize,
                   std::initializer_list<std::vector<float>*> extra, const TaskHook& tasks) {
    Particles& p = s.particles;
    ++s.sorts;
    s.grid.build(p.px, p.py, cellSize, tasks);
    const std::span<const uint32_t> order = s.grid.order();
    for (auto* channel : {&p.px, &p.py, &p.vx, &p.vy}) {
        permute(*channel, order, s.sortScratch, tasks);
    }
    // In a step without yielding particles the stress channels are all zero: nothing to
    // permute (WorldState::yielding). The pending kicks are zero at every sort.
    if (s.yielding) {
        for (auto* channel : {&p.sxx, &p.sxy, &p.structure}) {
            permute(*channel, order, s.sortScratch, tasks);
        }
    }
    // Most worlds have no lifetimes: an all-infinite channel needs no permutation (and no
    // scratch of 8 bytes per particle).
    if (!std::all_of(p.expiry.begin(), p.expiry.end(), [](double t) { return std::isinf(t); })) {
        permute(p.expiry, order, s.sortScratchD, tasks);
    }
    for (auto* channel : extra) {
        permute(*channel, order, s.sortScratch, tasks);
    }
    // The optional channels: colours whenever a world has them; the previous positions
    // only in the sort of a step's last sub-step, which captured them (permuteLast).
    if (!p.colour.empty()) {
        permute(p.colour, order, s.sortScratch, tasks);
    }
    if (s.permuteLast) {
        permute(p.lastX, order, s.sortScratch, tasks);
        permute(p.lastY, order, s.sortScratch, tasks);
    }
    // Slots and materials pass through the float scratch too: no scratch array of their own.
    permute(p.slot, order, s.sortScratch, tasks);
    permute(p.material, order, s.sortScratch, tasks);
    parallelFor(tasks, p.size(), kPermuteGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t k = b; k < e; ++k) {
            s.slotIndex[p.slot[k]] = k; // slots are distinct: one write each
        }
    });
}

uint32_t separateStacked(WorldState& s, float cellSize, std::vector<float>* alsoX,
                         std::vector<float>* alsoY, const TaskHook& tasks) {
    Particles& p = s.particles;
    const GridView& g = s.grid.view();
    if (p.size() < 2 || g.count != p.size()) {
        return 0; // nothing to stack (and a grid of no points keeps no cells)
    }
    const size_t ranges = g.hashed ? size_t(g.mask) + 1 : size_t(g.nx) * size_t(g.ny);
    const float reach = kStackedNudge * cellSize;
    // Cell by cell (bucket by bucket in a hashed grid): only cells of two or more can stack.
    // Each cell's particles are its own, so the cells split over the workers freely.
    std::atomic<uint32_t> moved{0};
    parallelFor(tasks, uint32_t(ranges), kStackedGrain, [&](uint32_t c0, uint32_t c1, uint32_t) {
        uint32_t count = 0;
        for (size_t c = c0; c < c1; ++c) {
            const uint32_t b = g.start[c], e = g.start[c + 1];
            if (e - b < 2) {
                continue;
            }
            for (uint32_t i = b; i + 1 < e; ++i) {
                for (uint32_t j = i + 1; j < e; ++j) {
                    if (p.px[j] != p.px[i] || p.py[j] != p.py[i]) {
                        continue;
                    }
                    // j sits exactly on i: the pair terms have no direction to part them. Move
                    // it a little, the way its slot picks, with the channels that hold where
                    // it stands (the velocity does not change).
                    const glm::vec2 d = reach * stackedDirection(p.slot[j]);
                    const float dx = d.x, dy = d.y;
                    p.px[j] += dx;
                    p.py[j] += dy;
                    if (alsoX != nullptr && alsoY != nullptr) {
                        (*alsoX)[j] += dx;
                        (*alsoY)[j] += dy;
                    }
                    ++count;
                }
            }
        }
        moved += count;
    });
    return moved.load();
}

void projectBoundaries(WorldState& s, float dt, float prevTimeInStep, float timeInStep,
                       float spacing, const std::vector<float>& prevX,
                       const std::vector<float>& prevY) {
    Particles& p = s.particles;
    // Each plugin's bodies as the coarse solve has shifted them so far in the step (the
    // samples stand there already): its projection moves their shapes with them.
    s.bodyShifts.resize(s.boundaries.size());
    for (std::vector<BodyShift>& shifts : s.bodyShifts) {
        shifts.clear();
    }
    for (const BodyState& body : s.bodies) {
        if (body.dvx == 0.0f && body.dvy == 0.0f && body.ox == 0.0f && body.oy == 0.0f) {
            continue;
        }
        const size_t count = s.boundaries[body.plugin]->rigidBodies().size();
        if (body.index >= count) {
            continue;
        }
        std::vector<BodyShift>& shifts = s.bodyShifts[body.plugin];
        shifts.resize(count);
        shifts[body.index] = BodyShift{{body.dvx, body.dvy}, {body.ox, body.oy}};
    }
    ProjectContext context{p.px,       p.py, prevX,      prevY,          p.vx,    p.vy,
                           p.material, dt,   timeInStep, prevTimeInStep, spacing, {}};
    // Solids, then walls, then containers (BoundaryPlugin::role), each in the order added.
    for (const BoundaryRole role :
         {BoundaryRole::Solid, BoundaryRole::Wall, BoundaryRole::Container}) {
        for (size_t index = 0; index < s.boundaries.size(); ++index) {
            BoundaryPlugin* const plugin = s.boundaries[index].get();
            if (plugin->role() != role) {
                continue;
            }
            context.bodyShifts = s.bodyShifts[index];
            // A position or velocity the plugin left non-finite is undone: that particle keeps
            // what it had before this plugin's call (docs/plugins.md, "Output that is not
            // finite"). Each range keeps its own copy, so the check costs one pass over it.
            std::atomic<uint32_t> undone{0};
            parallelFor(s.tasks, p.size(), 1024, [&](uint32_t b, uint32_t e, uint32_t) {
                thread_local std::vector<float> keep;
                keep.resize(4 * size_t(e - b));
                float* const k = keep.data();
                for (uint32_t i = b; i < e; ++i) {
                    float* const q = k + 4 * size_t(i - b);
                    q[0] = p.px[i];
                    q[1] = p.py[i];
                    q[2] = p.vx[i];
                    q[3] = p.vy[i];
                }
                plugin->project(context, b, e);
                uint32_t bad = 0;
                for (uint32_t i = b; i < e; ++i) {
                    if (std::isfinite(p.px[i]) && std::isfinite(p.py[i]) &&
                        std::isfinite(p.vx[i]) && std::isfinite(p.vy[i])) {
                        continue;
                    }
                    const float* const q = k + 4 * size_t(i - b);
                    p.px[i] = q[0];
                    p.py[i] = q[1];
                    p.vx[i] = q[2];
                    p.vy[i] = q[3];
                    ++bad;
                }
                if (bad > 0) {
                    undone.fetch_add(bad, std::memory_order_relaxed);
                }
            });
            const uint32_t count = undone.load(std::memory_order_relaxed);
            if (count > 0) {
                s.profile.boundaryDropped += count;
                if (s.profile.boundaryDroppedPlugin < 0) {
                    s.profile.boundaryDroppedPlugin = int32_t(index);
                }
            }
        }
    }
}

void finishPlugins(WorldState& s, const StepContext& context) {
    for (const auto& plugin : s.forces) {
        plugin->finish(context);
    }
    for (const auto& plugin : s.boundaries) {
        plugin->finish(context);
    }
}

void densityError(WorldState& s) {
    const Particles& p = s.particles;
    struct Err {
        double sum = 0;
        float max = 0;
    };
    const Err err = blockReduce<Err>(
        s.tasks, p.size(), Err{},
        [&](uint32_t b, uint32_t e) {
            Err r;
            for (uint32_t i = b; i < e; ++i) {
                const float c =
                    std::max(0.0f, p.density[i] / s.constants[p.material[i]].restDensity - 1.0f);
                r.sum += c;
                r.max = std::max(r.max, c);
            }
            return r;
        },
        [](Err a, const Err& b) {
            return Err{a.sum + b.sum, std::max(a.max, b.max)};
        });
    s.profile.densityErrorMax = err.max;
    s.profile.densityErrorAvg = p.size() > 0 ? float(err.sum / p.size()) : 0.0f;
}

IntegrateStats integrate(WorldState& s, const std::vector<float>& ax, const std::vector<float>& ay,
                         float dt, float speedCap, std::vector<float>& prevX,
                         std::vector<float>& prevY) {
    Particles& p = s.particles;
    prevX.resize(p.size());
    prevY.resize(p.size());
    return blockReduce<IntegrateStats>(
        s.tasks, p.size(), IntegrateStats{},
        [&](uint32_t b, uint32_t e) {
            IntegrateStats st;
            for (uint32_t i = b; i < e; ++i) {
                float axi = ax[i], ayi = ay[i];
                if (!std::isfinite(axi) || !std::isfinite(ayi)) {
                    axi = ayi = 0.0f;
                    ++st.repaired;
                }
                st.maxAccel2 = std::max(st.maxAccel2, axi * axi + ayi * ayi);
                float vx = p.vx[i] + dt * axi;
                float vy = p.vy[i] + dt * ayi;
                const float v2 = vx * vx + vy * vy;
                if (v2 > speedCap * speedCap) {
                    if (std::isfinite(v2)) {
                        const float scale = speedCap / std::sqrt(v2);
                        vx *= scale;
                        vy *= scale;
                    } else {
                        // A huge finite acceleration (a force plugin's 1e30 m/s^2) made v2
                        // overflow a float: a scale of cap / inf = 0 would stop the particle
                        // dead. In double, it is capped along its direction.
                        const double w2 = double(vx) * double(vx) + double(vy) * double(vy);
                        const double scale = double(speedCap) / std::sqrt(w2);
                        vx = float(double(vx) * scale);
                        vy = float(double(vy) * scale);
                    }
                    ++st.clamped;
                }
                p.vx[i] = vx;
                p.vy[i] = vy;
                prevX[i] = p.px[i];
                prevY[i] = p.py[i];
                p.px[i] += dt * vx;
                p.py[i] += dt * vy;
            }
            return st;
        },
        [](IntegrateStats a, const IntegrateStats& b) {
            return IntegrateStats{a.clamped + b.clamped, a.repaired + b.repaired,
                                  std::max(a.maxAccel2, b.maxAccel2)};
        });
}

std::vector<uint8_t> presentMaterials(const WorldState& s) {
    const size_t count = s.materials.size();
    const Particles& p = s.particles;
    std::vector<uint8_t> present(count, p.size() == 0 ? 1 : 0);
    if (p.size() == 0) {
        return present;
    }
    if (count <= 64) {
        // One bit per material, or-ed over fixed blocks (any order gives the same mask).
        const uint64_t mask = blockReduce<uint64_t>(
            s.tasks, p.size(), 0,
            [&](uint32_t b, uint32_t e) {
                uint64_t bits = 0;
                for (uint32_t i = b; i < e; ++i) {
                    bits |= uint64_t(1) << p.material[i];
                }
                return bits;
            },
            [](uint64_t a, uint64_t b) { return a | b; });
        for (size_t m = 0; m < count; ++m) {
            present[m] = (mask >> m) & 1u;
        }
        return present;
    }
    for (const uint16_t m : p.material) {
        present[m] = 1;
    }
    return present;
}

SceneFacts sceneFacts(const WorldState& s) {
    SceneFacts f;
    f.minSupport = std::numeric_limits<float>::max();
    f.minSpacing = std::numeric_limits<float>::max();
    // Only the materials some particle has: a material registered for later (a level's
    // yoghurt before its first blob) changes nothing of a step.
    size_t first = s.materials.size();
    for (size_t i = 0; i < s.materials.size(); ++i) {
        if (!s.isPresent(i)) {
            continue;
        }
        first = std::min(first, i);
        const Material& m = s.materials[i];
        f.minSupport = std::min(f.minSupport, m.smoothingDistance);
        f.maxSupport = std::max(f.maxSupport, m.smoothingDistance);
        f.minSpacing = std::min(f.minSpacing, particleSpacing(m, s.def.depth));
        f.maxNu = std::max(f.maxNu, m.viscosity / m.restDensity);
        f.maxK = std::max(f.maxK, m.stiffness);
        f.surfaceTension = f.surfaceTension || m.surfaceTension > 0.0f;
    }
    // Boundary samples on the lattice of the first material present.
    f.sampleSpacing = particleSpacing(s.materials[first], s.def.depth);
    for (const auto& plugin : s.boundaries) {
        f.maxFriction = std::max(f.maxFriction, plugin->friction());
        f.wantsForces = f.wantsForces || plugin->wantsForces();
    }
    return f;
}

void deliverSampleForces(WorldState& s) {
    for (size_t k = 0; k < s.boundaries.size(); ++k) {
        const size_t b = s.samples.pluginBegin[k], e = s.samples.pluginBegin[k + 1];
        if (s.boundaries[k]->wantsForces()) {
            s.boundaries[k]->receiveForces(
                std::span<const float>(s.samples.fx).subspan(b, e - b),
                std::span<const float>(s.samples.fy).subspan(b, e - b),
                std::span<const float>(s.samples.drag).subspan(b, e - b));
        }
    }
}

} // namespace fluid::detail

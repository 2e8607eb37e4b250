// fluid — the parts of a step both solvers share (step_common.cpp).
#pragma once

#include "parallel.h"
#include "world_state.h"

#include <chrono>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <span>
#include <type_traits>
#include <vector>

namespace fluid::detail {

using Clock = std::chrono::steady_clock;

/// Runs f and adds its wall-clock time to `total` (unit: ms).
template <class F> void timed(float& total, F&& f) {
    const Clock::time_point t0 = Clock::now();
    f();
    total += std::chrono::duration<float, std::milli>(Clock::now() - t0).count();
}

/// Per material: 1 when some particle has it (every material when there are no particles).
std::vector<uint8_t> presentMaterials(const WorldState& s);

/// What a step needs to know about the materials its particles have and the boundaries,
/// gathered once per step.
struct SceneFacts {
    float minSupport = 0, maxSupport = 0; // smallest and largest h (m)
    float minSpacing = 0;                 // smallest lattice spacing (m)
    float sampleSpacing = 0;              // spacing of boundary samples: the first present
                                          // material's (m)
    float maxNu = 0;                      // largest kinematic viscosity mu/rho0 (m^2/s)
    float maxK = 0;                       // largest stiffness (m^2/s^2)
    float maxFriction = 0;                // largest boundary friction (1)
    bool surfaceTension = false;          // some material has gamma > 0
    bool wantsForces = false;             // some boundary asks for the fluid's forces
};
SceneFacts sceneFacts(const WorldState& s);

/// Particles per task of a permutation (each slot is written once, so any split gives the same
/// channel).
inline constexpr uint32_t kPermuteGrain = 4096;

/// channel[k] = channel[order[k]], through `tmp`, split over the workers.
template <class T>
void permute(std::vector<T>& channel, std::span<const uint32_t> order, std::vector<T>& tmp,
             const TaskHook& tasks) {
    tmp.resize(channel.size());
    parallelFor(tasks, uint32_t(order.size()), kPermuteGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t k = b; k < e; ++k) {
            tmp[k] = channel[order[k]];
        }
    });
    channel.swap(tmp);
}

/// The same for an integer channel of at most 32 bits, through a float scratch that carries
/// each value as a raw 32-bit pattern (memcpy, so none is ever read as a float): the sort needs
/// no scratch array of the channel's own type.
template <class T>
void permute(std::vector<T>& channel, std::span<const uint32_t> order, std::vector<float>& tmp,
             const TaskHook& tasks) requires(std::is_integral_v<T> &&
                                             sizeof(T) <= sizeof(uint32_t)) {
    tmp.resize(channel.size());
    parallelFor(tasks, uint32_t(order.size()), kPermuteGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t k = b; k < e; ++k) {
            const auto value = static_cast<uint32_t>(channel[order[k]]);
            std::memcpy(&tmp[k], &value, sizeof(uint32_t));
        }
    });
    // Element-wise (an empty channel's data() is null), after every read of the old order.
    parallelFor(tasks, uint32_t(order.size()), kPermuteGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t k = b; k < e; ++k) {
            uint32_t value = 0;
            std::memcpy(&value, &tmp[k], sizeof(uint32_t));
            channel[k] = static_cast<T>(value);
        }
    });
}

/// Per-material constants from the material table (equation-of-state fields left 0).
void refreshConstants(WorldState& s);

/// Boundary plugins' prepare hooks; sizes the per-sample force sums; collects the plugins'
/// rigid bodies with a mass into `WorldState::bodies` (throws `fluid::Error` naming the plugin
/// and body for a mass, inertia or sample range out of range, or a non-finite pose).
void gatherSamples(WorldState& s, const StepContext& context);

/// After the step: each boundary plugin with rigid bodies gets what the coarse solve did to them
/// (`BoundaryPlugin::receiveBodyImpulses`).
void deliverBodyImpulses(WorldState& s, float frameDt);

/// Positions of all samples at `t` seconds into the step, sorted by cell (rebuilt only when
/// `rebuild` or the sample count changed).
void placeSamples(WorldState& s, float t, float cellSize, bool rebuild);

/// True when some boundary sample has a non-zero velocity.
bool samplesMove(const WorldState& s);

/// The particles as plugins see them.
ParticleView particleView(const WorldState& s);

/// Force plugins' accelerations into (ax, ay) (resized to the particles and zeroed first), one
/// apply per plugin. The explicit solver passes (ex, ey); the position-based one its (ax, ay)
/// scratch, free at that point of its sub-step.
void externalForces(WorldState& s, float dt, double time, std::vector<float>& ax,
                    std::vector<float>& ay);

/// Counting sort by grid cell (cell size `cellSize`); positions, velocities, material, slot and
/// the `extra` channels follow; handles are remapped. Its loops run on `tasks` (the world's, or
/// a hook with no enqueue to run them all on the calling thread).
void sortParticles(WorldState& s, float cellSize,
                   std::initializer_list<std::vector<float>*> extra, const TaskHook& tasks);
inline void sortParticles(WorldState& s, float cellSize,
                          std::initializer_list<std::vector<float>*> extra = {}) {
    sortParticles(s, cellSize, extra, s.tasks);
}

/// After `sortParticles`: every particle at exactly the position of another one of its cell is
/// moved 1/64 of `cellSize` the way its slot picks (a golden-angle step per slot), together
/// with (alsoX, alsoY) when given (the position-based solver's admissible prediction, so that
/// the velocity does not change). Such stacks come from projections onto a wall's corner; the
/// pair terms have no direction to part them. Cells are independent, so the result does not
/// depend on the workers. Returns how many particles it moved.
/// Its loops run on `tasks`.
uint32_t separateStacked(WorldState& s, float cellSize, std::vector<float>* alsoX,
                         std::vector<float>* alsoY, const TaskHook& tasks);
inline uint32_t separateStacked(WorldState& s, float cellSize, std::vector<float>* alsoX = nullptr,
                                std::vector<float>* alsoY = nullptr) {
    return separateStacked(s, cellSize, alsoX, alsoY, s.tasks);
}

/// Counters of one `integrate` call.
struct IntegrateStats {
    uint32_t clamped = 0;   // particles whose speed hit the cap
    uint32_t repaired = 0;  // particles whose acceleration was non-finite and zeroed
    float maxAccel2 = 0.0f; // largest squared (finite) acceleration (m^2/s^4)
};

/// Symplectic Euler, seed eqs. 2.8 and 2.9: v += dt a, x += dt v, with two safety nets: a
/// non-finite acceleration (a broken plugin) is zeroed instead of spreading NaN, and the speed
/// is capped at `speedCap` (m/s) so that no particle can jump through a wall's sample layers.
/// The explicit solver passes its total acceleration; the position-based one predicts with the
/// plugins'. The positions before the move are kept in (prevX, prevY) (resized) for the
/// boundaries: (qx, qy) for the explicit solver, the free correction scratch for the other.
IntegrateStats integrate(WorldState& s, const std::vector<float>& ax, const std::vector<float>& ay,
                         float dt, float speedCap, std::vector<float>& prevX,
                         std::vector<float>& prevY);

/// Boundary plugins' projection over all particles (px, py, vx, vy as they are now); `prevX`,
/// `prevY` are where the particles stood at `prevTimeInStep` (see `ProjectContext`).
void projectBoundaries(WorldState& s, float dt, float prevTimeInStep, float timeInStep,
                       float spacing, const std::vector<float>& prevX,
                       const std::vector<float>& prevY);

/// Every plugin's `finish` hook, in the order added (forces, then boundaries).
void finishPlugins(WorldState& s, const StepContext& context);

/// Profile's densityErrorMax and densityErrorAvg from p.density.
void densityError(WorldState& s);

/// Hands each boundary that wants them the summed forces on its samples.
void deliverSampleForces(WorldState& s);

// Contact events (contacts.cpp, fluid/contacts.h): the bodies that ask for them (end of
// gatherSamples), the particles touching them after each sub-step (runFrame), the events at the
// end of the step (runFrame's closing); clearContacts (world_state.h) for a step that simulated
// nothing.
void gatherContactBodies(WorldState& s, const StepContext& context);
void contactPass(WorldState& s);
void finishContacts(WorldState& s, float frameDt);

} // namespace fluid::detail

// fluid — a world's internal state, shared by the API (world.cpp) and the solvers.
#pragma once

#include "coarse_multigrid.h"
#include "grid.h"

#include <fluid/contacts.h>
#include <fluid/world.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

namespace fluid::detail {

/// Structure of arrays of the particles. The persistent channels (position, velocity, material,
/// slot) are permuted together when the grid sorts; the derived ones are recomputed every
/// sub-step, except density and pressure, which are kept in slot order for readers.
struct Particles {
    std::vector<float> px, py, vx, vy;
    std::vector<uint16_t> material;
    std::vector<uint32_t> slot;
    std::vector<float> density, pressure;
    // The deviatoric stress of a Herschel-Bulkley material (Pa), kept between steps: sxx
    // (= -syy) and sxy of the symmetric traceless 2D tensor. 0 for Newtonian particles, and not
    // permuted by the sort in a step without yielding particles (all zeros then).
    std::vector<float> sxx, sxy;
    // The structure of a yielding material with the shear constraint, in [0, 1]: broken by
    // plastic flow, rebuilt at rest; it raises the yield stress at rest (pbf_shear.cpp). 0 for
    // Newtonian particles, permuted as the stress.
    std::vector<float> structure;
    // Yielding worlds, position-based: the velocity change of the last surface and stress
    // passes (m/s), applied before the next prediction instead of at once, so that the density
    // solve meets the cohesion and stress forces in the same sub-step as gravity: a resting
    // particle then reads a velocity of 0, not the dt * force the next solve takes back. 0
    // elsewhere.
    std::vector<float> kx, ky;
    // Simulated time (s) at which the particle is removed; +infinity for those that live
    // forever. Absolute and double, so that a long lifetime neither stalls nor drifts.
    std::vector<double> expiry;
    // Derived every sub-step, in sorted order, for both solvers: 1/rho, so pair loops do not
    // divide, and material properties per particle, so pair loops read contiguous arrays
    // instead of indexing the material table: support h, mass/depth, viscosity, mass, rest
    // density, surface tension, 1/mass, rest area V = m/(depth rho0), pair pressure.
    std::vector<float> invRho;
    std::vector<float> h, massPerDepth, viscosity, mass, restDensity, gamma;
    std::vector<float> invMass, volume, pairPressure, invLattice;
    // A yield-stress material's skin (tuning::kSkinCohesion), sized only in a world with a
    // yield-stress material with cohesion and another material (else empty): the skin's extra
    // cohesion gamma per particle (0 for other materials), the material index as a float (for
    // the pair passes' comparisons) and, written by each viscosity run's first pass, the share
    // of the particle's kernel weight that other materials hold (1).
    std::vector<float> skinGamma, materialTag, otherShare;
    // ---- Optional channels (groups.cpp), empty until a world uses them ----
    // Interpolation: positions at the start of the last sub-step (m), permuted by the sort of
    // the last sub-step only (WorldState::permuteLast); empty while interpolation is off.
    std::vector<float> lastX, lastY;
    // Packed RGBA8 colour per particle (Colour::pack; alpha 0 = none); empty until some
    // particle gets a colour. Permuted by every sort when present.
    std::vector<uint32_t> colour;

    uint32_t size() const { return static_cast<uint32_t>(px.size()); }
    /// The float channels that persist between steps (besides material, slot and expiry).
    std::array<std::vector<float>*, 11> keptFloats() {
        return {&px, &py, &vx, &vy, &density, &pressure, &sxx, &sxy, &structure, &kx, &ky};
    }
    /// See `keptFloats`.
    std::array<const std::vector<float>*, 11> keptFloats() const {
        return {&px, &py, &vx, &vy, &density, &pressure, &sxx, &sxy, &structure, &kx, &ky};
    }
};

/// The explicit solver's scratch (solver_explicit.cpp, sph_loops.cpp): per sub-step channels
/// in sorted order, sized at the start of each step, never saved.
struct ExplicitScratch {
    std::vector<float> ax, ay;    // total acceleration (m/s^2)
    std::vector<float> ex, ey;    // the force plugins' acceleration (m/s^2)
    std::vector<float> nx, ny;    // surface normals [Akinci 2013] (1)
    std::vector<float> pOverRho2; // the pair term's pressure over rho^2 (m^5/(kg s^2))
    std::vector<float> qx, qy;    // positions before the last integrate, for the boundaries (m)
};

/// The position-based solver's scratch (solver_position_based.cpp, pbf_loops.cpp,
/// pbf_coarse.cpp): per sub-step channels in sorted order, sized at the start of each step,
/// never saved. Each holds one thing for the whole sub-step.
struct PositionBasedScratch {
    std::vector<float> extX, extY;     // the force plugins' acceleration (m/s^2)
    std::vector<float> startX, startY; // positions before the prediction, for the boundaries (m)
    std::vector<float> ox, oy;         // the admissible prediction x* (m; sorted with particles)
    std::vector<float> constraint;     // the density constraint C (1)
    std::vector<float> diagonal;       // the diagonal D of its system (1/(kg m^2))
    std::vector<float> lambda;         // the accumulated multiplier (kg m^2, <= 0)
    std::vector<float> change;         // the multiplier's change in the current sweep (kg m^2)
    std::vector<float> dx, dy;         // the last sweep's displacement (m)
    std::vector<float> cx, cy;         // the sub-step's total correction of x* (m) ...
    std::vector<float> prevX, prevY;   // ... and its value one sweep back (Chebyshev)
    std::vector<float> lambdaTotal;    // the multiplier the accelerated corrections stand for
    std::vector<float> lambdaPrev;     // ... and its value one sweep back
    std::vector<float> coarseP;        // the coarse move's share x potential at the particle (m^2)
    std::vector<float> vorticity;      // the viscosity pass's vorticity, for the surface pass (1/s)
    std::vector<float> normalX, normalY; // its surface normals, for the surface pass (1)
    std::vector<float> nextVx, nextVy;   // a viscosity pass's new velocity (m/s), swapped into v
    // A viscosity run split by viscosity (pbfViscosity's `split`): 1 for a particle of a
    // material that needs the run's passes, else 0; and 1 for a particle with one in its
    // support (from the run's first pass), else 0.
    std::vector<float> viscousTag, viscousFlag;
};

/// The yield model's scratch in a yielding world (position-based: pbf_loops.cpp,
/// simd/pbf_pairs.inc), sorted order, never saved; its state (Particles::sxx, sxy, kx, ky) is.
struct YieldScratch {
    // The stress over rho0^2 (m^2/s^2) and how far below its yield stress each particle is
    // (1 - |s| / tau_y in [0, 1]; 0 for a Newtonian one), from the viscosity pass.
    std::vector<float> tx, ty, rigidity;
    // From the stress pass: the unit direction from the walls within reach to the particle
    // (0, 0 with none) and its adhesion to them (acceleration along that direction over the
    // length of the walls' kernel gradient sum; <= 0), which the walls' reaction reads.
    std::vector<float> wallNx, wallNy, wallAdhesion;
    // The surface pass's acceleration (m/s^2), which the stress pass adds to.
    std::vector<float> surfaceAx, surfaceAy;
    // The shear constraint (pbf_shear.cpp), per sub-step: the positions the sweeps start from,
    // where its kernel gradients are taken, and the displacement since the sub-step's start
    // (m); 1 for a particle of a yielding material, else 0; the inverse of the kernel
    // gradient's correction matrix (symmetric: xx, xy, yy; 1; shearRead leaves M itself there
    // until the particle's return inverts it), the gradient sum H (xx, xy, yx, yy; 1), sum V_j
    // grad W_ij (1/m) and the compliance trace (1/(kg m^2)) of the last reading; the multiplier
    // applied so far (the stress times -2 V dt^2: components xx and xy; kg m per depth), its
    // last change times M^-1 (t00..t11), and the sweep's displacement (m).
    std::vector<float> refX, refY, ux, uy, yields;
    // The walls' hold (pbf_shear.cpp, holdOnWalls): the walls' part of S (1/m), their velocity
    // (m/s) and weight (sum of friction-weighted kernel values; 1), as the first reading
    // took them; and the hold's net displacement so far in the sub-step (m).
    std::vector<float> wallX, wallY, wallVx, wallVy, wallWeight;
    std::vector<float> holdX, holdY;
    bool matrixRead = false; // M and S of this sub-step read (its first reading)
    std::vector<float> mxx, mxy, myy;
    std::vector<float> hxx, hxy, hyx, hyy, sumX, sumY, trace;
    std::vector<float> appliedA, appliedB;
    std::vector<float> t00, t01, t10, t11;
    std::vector<float> shearDx, shearDy;
};

/// Per-material constants the hot loops read, refreshed at the start of every step.
struct MaterialConstants {
    float mass = 0;               // 3D mass m (kg)
    float massPerDepth = 0;       // m / depth (kg/m): the mass a 2D kernel sum weighs with
    float restDensity = 0;        // rho0 (kg/m^3)
    float viscosity = 0;          // mu (Pa s)
    float stiffness = 0;          // k (m^2/s^2)
    float taitB = 0;              // rho0 c^2 / 7 (Pa)
    float backgroundPressure = 0; // fluid-fluid pairs only: explicit, added to Tait's pressure;
                                  // position-based, the artificial pressure of s_corr (Pa)
    float support = 0;            // h (m)
    float gamma = 0;              // surface tension (Akinci 2013)
    float lattice = 0;    // V sum W over the material's square lattice (1; 1.0042 for water)
    float neighbours = 0; // lattice points within h of one (count; 29 water, 49 yoghurt)
    float diagonal = 0;   // position-based: the density constraint's denominator sum_j w_j
                          // |grad_j C|^2 for a particle inside the lattice (1/(kg m^2))
    // Herschel-Bulkley law (Material::yieldStress etc.); `yielding` false for a Newtonian one.
    bool yielding = false;
    float yieldStress = 0;  // tau_y (Pa)
    float consistency = 0;  // K (Pa s^n)
    float flowIndex = 1;    // n
    float shearModulus = 0; // G as the material asks (Pa; 0: the solver's bound)
};

/// Boundary samples of all boundary plugins, sorted by cell for the sub-step.
struct Samples {
    std::vector<float> px, py, vx, vy, friction, pressure;
    std::vector<uint32_t> source; // index in the concatenation of the plugins' sample arrays
    std::vector<float> fx,
        fy; // force on each sample (N), in concatenation order, summed over sub-steps
    std::vector<float> drag; // d(force)/d(sample velocity) (N s/m), same order and weighting
    std::vector<uint32_t> pluginBegin; // first concatenated index of each plugin (+ total)
    // Sorted indices of the samples whose plugin wants forces, and for each of them the
    // position-based solver's push on it in the current sub-step (N), with the previous
    // sweep's value for the Chebyshev recurrence.
    std::vector<uint32_t> reporting;
    std::vector<float> pushX, pushY, pushPrevX, pushPrevY;
    // The rigid body (index in WorldState::bodies) each sample belongs to, -1 for none: in
    // concatenation order (gatherSamples) and in sorted order (placeSamples).
    std::vector<int32_t> bodyOf, body;
    Grid grid;
    uint32_t size() const { return static_cast<uint32_t>(px.size()); }
};

/// A boundary plugin's rigid body with a mass (`BoundaryPlugin::rigidBodies`) during a step: an
/// unknown of the coarse pressure solve (pbf_coarse.cpp). Rebuilt by every gatherSamples.
struct BodyState {
    uint32_t plugin = 0;                     // index in WorldState::boundaries
    uint32_t index = 0;                      // index in that plugin's rigidBodies()
    uint32_t sampleBegin = 0, sampleEnd = 0; // its samples, in concatenation order
    float mass = 0;                          // kg
    // The coarse solve's corrections so far: a velocity change (dvx, dvy) and a position offset
    // at time t into the step of (dvx, dvy) t + (ox, oy); placeSamples adds them.
    float dvx = 0, dvy = 0, ox = 0, oy = 0;
    double impulseX = 0, impulseY = 0; // summed over the step (N s)
};
/// Contact events (contacts.cpp; fluid/contacts.h): the rigid bodies that ask for them in this
/// step, what the sub-steps found, and the last step's events. Never saved.
struct ContactState {
    struct Body {
        uint32_t plugin = 0, index = 0;          // plugin and index in its rigidBodies()
        uint32_t sampleBegin = 0, sampleEnd = 0; // its samples, in concatenation order
        int32_t state = -1;                      // its entry in WorldState::bodies, or -1
    };
    struct Touch {
        uint32_t slot = 0;
        uint16_t material = 0;
    };
    std::vector<Body> bodies;      // gatherSamples; empty: the step pays nothing
    std::vector<int32_t> bodyOf;   // per concatenated sample: its entry in `bodies`, or -1
    std::vector<uint32_t> samples; // sorted indices of the asking bodies' samples
    std::vector<uint32_t> stamp;   // per particle: the last (sub-step, body) mark that took it
    uint32_t mark = 0;             // the first mark of the current sub-step
    float reach = 0.0f;            // kContactReach sample spacings (m)
    std::vector<std::vector<Touch>> touches; // per body: (particle, sub-step) contacts
    std::vector<double> sumX, sumY;          // per body: their positions summed (m)
    std::vector<float> approach;             // per body: the largest approach speed (m/s)
    std::vector<BodyContact> events;         // the last step's
    std::vector<ParticleHandle> handles;     // the events' particles, event by event
    std::vector<uint32_t> handleBegin;       // per event, then the total
};

/// An emitter: its settings, and the state a snapshot carries.
struct EmitterState {
    EmitterDef def;
    double carry = 0.0;   // rows owed but not emitted yet, in [0, 1)
    uint32_t emitted = 0; // particles emitted so far
    uint64_t random = 0;  // splitmix64 state, seeded from def.seed
};

/// The coarse grid's placement: its lower-left node (x0, y0) (m), 1 / cell (1/m) and nodes
/// across and up (count). Thread rule: read-only while a correction's phases run.
struct CoarseLayout {
    float x0 = 0, y0 = 0, invH = 0;
    int nx = 0, ny = 0;
    /// Cell (i, j) of the point (x, y) (clamped to the grid) and its bilinear fractions in it.
    void cell(float x, float y, int& i, int& j, float& fx, float& fy) const {
        const float gx = (x - x0) * invH, gy = (y - y0) * invH;
        i = std::clamp(int(std::floor(gx)), 0, nx - 2);
        j = std::clamp(int(std::floor(gy)), 0, ny - 2);
        fx = std::clamp(gx - float(i), 0.0f, 1.0f);
        fy = std::clamp(gy - float(j), 0.0f, 1.0f);
    }
};

/// The position-based solver's coarse grid (pbf_coarse.cpp), kept between sub-steps so that
/// its arrays are allocated once.
struct CoarseGrid {
    std::vector<float> fluid, solid;       // fill of the node by particles and by samples (1: full)
    std::vector<uint32_t> cell;            // per particle: its cell's lower-left node
    std::vector<float> fx, fy;             // per particle: its bilinear fractions in the cell
    std::vector<uint8_t> type;             // 0 air, 1 fluid, 2 solid
    std::vector<float> psi, rhs, r, d, q;  // potential and conjugate-gradient vectors
    std::vector<float> z;                  // preconditioned residual
    std::vector<uint32_t> active;          // the fluid nodes, in order (the unknowns)
    std::vector<int32_t> slot;             // per node: its unknown, -1 for air and solid
    std::vector<float> diagonal;           // per unknown: the operator's diagonal
    std::vector<int32_t> neighbours;       // per unknown: 4 neighbouring unknowns (the unknowns'
                                           // count for none: d keeps a 0 there)
    std::vector<int32_t> owner;            // per node: the body it lies inside, or -1
    std::vector<float> bodyFill;           // per node: the bodies' fill from their outlines
    std::vector<float> ownFill;            // scratch: one body's outline fill over its box
    std::vector<float> samplesFill;        // scratch: one body's samples' fill over its box
    std::vector<uint8_t> inside;           // scratch: one body's inside test on a fine lattice
    // Worlds without bodies: per unknown its region (the connected set of fluid nodes it
    // belongs to, through their 4 neighbours), per region 1 when a node of it holds a wall's
    // fill, and per particle the region of its cell's first fluid corner (-1: none, its move is
    // 0). Each region away from walls keeps its momentum (keepRegionMomentum).
    std::vector<int32_t> region;
    std::vector<uint8_t> regionWalled;
    std::vector<int32_t> particleRegion;
    struct RegionRun { // scratch: a block's run of particles of one region, its momentum sums
        int32_t region = 0;
        double mx = 0, my = 0, m = 0;
    };
    std::vector<std::vector<RegionRun>> regionRuns; // per block of kReduceBlock particles
    std::vector<uint32_t> regionStack;              // scratch of labelRegions
    std::vector<double> regionSum;                  // per region: mass times move (x, y), mass
    std::vector<float> regionMean;                  // per region: the mean move taken off
    // Per material: its particles' share of the solve's move, rho / rho0 (setMoveScale in
    // pbf_coarse.cpp); empty when every particle has the same rest density.
    std::vector<float> moveScale;
    // The bodies' Jacobian G: per entry, the flux a body's displacement (x, y) drives out of an
    // unknown's cell (m): from the outlined bodies' gradient weights, or for a body without an
    // inside test per face between an unknown and one of its nodes. G^T psi sums them.
    struct BodyFace {
        uint32_t unknown = 0, body = 0;
        float gx = 0, gy = 0;
    };
    std::vector<BodyFace> bodyFaces;
    // A body's gradient weights: per node of its box, the integral over the body's inside (its
    // outline's lattice) of the node's bilinear gradient (m). The body's row of the Jacobian is
    // -sum w v over them (v: the node values, extended into the body): the same -integral of
    // grad psi that moves the water in its place. Bodies in order, each's nodes in node order.
    struct NodeWeight {
        uint32_t node = 0, body = 0;
        float wx = 0, wy = 0;
    };
    std::vector<NodeWeight> bodyGradient;
    std::vector<float> boxGradient; // scratch: one body's weights over its box (x, y per node)
    std::vector<uint8_t> outlined;  // per body: 1 when its fill and weights come from its outline
    // The node values inside bodies, as combinations of the unknowns: node k's value is the sum
    // of extTerms[extStart[2k] .. extStart[2k + 1]) (unknown, weight); filled for the nodes
    // inside an outlined body, empty ranges elsewhere.
    struct ExtTerm {
        uint32_t unknown = 0;
        float weight = 0;
    };
    std::vector<uint32_t> extStart;
    std::vector<ExtTerm> extTerms;
    // Between the phases of one correction (pbfCoarseFill, pbfCoarseSolve, pbfCoarseMove): the
    // grid's placement, whether the fill found work, the bodies' mobility and flux sums, and
    // whether the solve coupled bodies.
    CoarseLayout layout;
    bool filled = false, solved = false, coupled = false;
    std::vector<double> mobility, bodySum;
    // Worlds with bodies: per node the share of it the bodies leave open to the flow (1 away
    // from them; tuning::kCoarseBodyFade), and per unknown its four faces' coefficients in the
    // operator (left, right, below, above; 0 for none). Without bodies every face's coefficient
    // is 1 and faceWeight is empty.
    std::vector<float> open;
    std::vector<float> faceWeight;
    // The solve's multigrid preconditioner (coarse_multigrid.h).
    CoarseMultigrid multigrid;
};

// A world object's tag in its handles (ParticleHandle::world): 1 for the first world the
// process makes, then counting up, never reused, so a handle from a destroyed world names no
// particle of a later one. A program that makes its worlds in the same order gets the same tags
// in every run, so hashes of handles and events agree between runs. Thread-safe.
class WorldTag {
public:
    WorldTag();
    WorldTag(const WorldTag&) = delete;
    WorldTag& operator=(const WorldTag&) = delete;
    uint32_t value() const { return m_value; }

private:
    uint32_t m_value = 0;
};

/// A test hook: called on the stepping thread after each stage of a sub-step with the stage's
/// index in the solver's stage list (the profile's names), so that a diagnostic can read the
/// state between stages. Never set outside tests.
using StageProbe = std::function<void(uint32_t stage)>;

struct WorldState {
    WorldDef def;
    std::unique_ptr<ThreadPool> pool; // own pool when the host gave no hook
    TaskHook tasks;
    // Threads that run `tasks` (the own pool's, or the hook's worker count): what splits work
    // into one piece per thread uses it, never the worker count.
    uint32_t threads() const {
        return pool != nullptr ? pool->threadCount() : std::max(1u, tasks.workerCount);
    }

    std::vector<Material> materials;
    // Capacity for `count` particles in every channel append fills and in the handle table
    // (growing geometrically), so that appending cannot fail half way.
    void reserveParticles(size_t count);
    // Index of the material with the finest spacing (0 without materials).
    size_t finestMaterial() const;
    // World::positionLimit (unit: m).
    float positionLimit() const;
    // Throws unless `x` lies within positionLimit(): "<function>: <what> = (x, y) is outside
    // the position range ...".
    void checkInRange(const char* function, const char* what, glm::vec2 x) const;
    std::vector<MaterialConstants> constants;
    // Some particle is of a material that follows the Herschel-Bulkley law (refreshConstants
    // for the materials, the position-based step for the particles): the stress channels are
    // sorted and stepped. A world with a yielding material but no such particle, such as a
    // water tank in a level that also lists yoghurt, steps as a Newtonian one.
    bool yielding = false;
    // The yielding particles step with the elastoplastic shear constraint (pbf_shear.cpp)
    // instead of the stress pass.
    bool elastoplastic = false;
    /// The stress pass's model: a yielding step without the shear constraint.
    bool stressPass() const { return yielding && !elastoplastic; }
    // Particles::kx, ky hold changes not yet applied (a yielding step wrote them).
    bool kicksPending = false;

    Particles particles;
    // Handles: slot -> index and generation; free slots reused last-in first-out.
    std::vector<uint32_t> slotIndex;
    std::vector<uint32_t> slotGeneration;
    // This world object's tag in its handles, never saved (a loaded world has its own), so
    // that snapshots of equal states are equal.
    WorldTag tag;
    std::vector<uint32_t> freeSlots;

    std::vector<std::unique_ptr<ForcePlugin>> forces;
    std::vector<std::unique_ptr<BoundaryPlugin>> boundaries;

    Grid grid;
    Samples samples;
    std::vector<BodyState> bodies;
    // Per boundary plugin, its rigid bodies' shifts by the coarse solve for its projection
    // (ProjectContext::bodyShifts; projectBoundaries); empty for a plugin none of whose bodies
    // has moved.
    std::vector<std::vector<BodyShift>> bodyShifts;
    CoarseGrid coarse;
    ExplicitScratch explicitScratch;
    PositionBasedScratch pbfScratch;
    YieldScratch yieldScratch;
    std::vector<float> sortScratch;   // also carries slots and materials (sortParticles)
    std::vector<double> sortScratchD; // expiry, only when some particle has a lifetime
    // What the last fillMaterialChannels wrote when every particle had one material: their
    // count, the material, whether the skin channels were filled, and its constants then
    // (uniform false otherwise). A fill that would write the same values skips the writes.
    struct UniformFill {
        bool uniform = false, skin = false;
        uint16_t material = 0;
        uint32_t count = 0;
        MaterialConstants constants;
    } materialFill;
    uint64_t sorts = 0; // particle sorts so far (EmissionUndo: has this step reordered them?)

    std::vector<EmitterState> emitters;
    std::vector<DrainDef> drains;
    std::vector<SensorDef> sensors;
    std::vector<SensorReading> sensorReadings; // sensor-major: [sensor * materials + material]
    std::vector<RemovedEvent> removed;         // the last step's removals
    ContactState contacts;                     // contact events (contacts.cpp)

    Profile profile;
    // True while World::step runs: calls that change the world refuse (checkIdle), so that a
    // plugin's hook calling back into the world that runs it cannot reallocate what the step
    // is iterating over, nest a second step, or destroy the world under itself.
    bool stepping = false;
    // Throws fluid::Error (ErrorCode::WrongState) "<function>: called during the world's own
    // step ..." while `stepping`.
    void checkIdle(const char* function) const;
    // checkIdle, then counts a change to the world (`changes`): every call that changes the
    // world starts with it, so the query grid knows when it is stale.
    void changing(const char* function) {
        checkIdle(function);
        ++changes;
    }
    uint64_t changes = 0;
    // The region queries' grid (query.cpp): particles sorted into cells of `cell` metres, built
    // by the first query after a change (`builtAt` != `changes`), under `mutex`, so that
    // queries from several threads between steps share it.
    struct QueryGrid {
        std::mutex mutex;
        uint64_t builtAt = ~uint64_t(0);
        uint32_t count = 0;
        float cell = 0.0f;
        Grid grid;
        // The particles' bounding box when built (unit: m; ray casts clip to it).
        float minX = 0.0f, minY = 0.0f, maxX = 0.0f, maxY = 0.0f;
    };
    std::unique_ptr<QueryGrid> queryGrid = std::make_unique<QueryGrid>();

    // ---- Groups, user data, colours, interpolation (groups.cpp) ----
    // Groups by index; a free entry has live false and is listed in freeGroups (reused
    // last-in first-out, its generation bumped). Membership and user data are kept per handle
    // slot (slotGroup, slotUserData: empty until first used, possibly shorter than the handle
    // table: a missing entry reads kNoGroup / 0), so sorts never touch them.
    static constexpr uint32_t kNoGroup = UINT32_MAX;
    struct Group {
        uint32_t generation = 1;
        uint32_t count = 0;
        bool live = false;
        uint32_t userData = 0; // GroupDef
        uint32_t colour = 0;   // GroupDef, packed
    };
    std::vector<Group> groups;
    std::vector<uint32_t> freeGroups;
    std::vector<uint32_t> slotGroup;
    std::vector<uint32_t> slotUserData;
    // Colour mixing's fractions: per handle slot, 8 bits below each 8-bit channel of the
    // particle's colour (r in the low byte), so that mixing trades colour at 1/256 of a level
    // and keeps each channel's sum exactly; empty until mixing first runs, 0 for a colour just
    // set (leaveSlot, setColour).
    std::vector<uint32_t> slotColourFraction;
    // Colour mixing's scratch (groups.cpp mixColours), kept so that a frame allocates nothing:
    // its grid, the positions and 8.8 colours in the grid's order, the new colours, and the
    // one-thread path's trades (4 channels per particle, in the grid's order).
    struct ColourMixScratch {
        Grid grid;
        std::vector<float> x, y;
        std::vector<uint64_t> colour;
        std::vector<uint32_t> next, nextFraction;
        std::vector<int64_t> acc;
    } colourMix;
    std::vector<uint32_t> emitterGroup; // per emitter: the group its particles join
    bool interpolate = false;           // keep Particles::lastX, lastY
    bool interpolateSteps = false;      // ... from a step's start (Interpolation::Step)
    bool permuteLast = false;           // the sort permutes lastX, lastY (last sub-step)
    float colourMixing = 0.0f;          // 1/s
    uint32_t groupOfSlot(uint32_t slot) const {
        return slot < slotGroup.size() ? slotGroup[slot] : kNoGroup;
    }
    // A new group entry (live, count 0) with the given spawn data; returns its index.
    uint32_t newGroup(uint32_t userData, uint32_t colour);
    // The particle at `index` joins group `g` (leaving its old one): membership, count, and
    // when `spawn` the group's user data and colour.
    void joinGroup(uint32_t index, uint32_t g, bool spawn);
    // A particle in `slot` is gone: its group count and user data (releaseSlot calls it).
    void leaveSlot(uint32_t slot);
    // The colour channel, allocated (zeros) if it was not.
    std::vector<uint32_t>& colourChannel();
    StageProbe stageProbe; // tests only: see StageProbe
    double time = 0.0;
    // Position-based: frame time passed to World::step that no sub-step has simulated yet (s, in
    // [-h / 2, h / 2) for the sub-step h: negative when the sub-steps ran ahead of the frames),
    // and the sub-steps the frame being stepped takes (World::step sets it).
    double carry = 0.0;
    uint32_t plannedSubsteps = 0;
    float soundSpeed = 0.0f; // derived Tait sound speed, never decreasing
    // Per material: 1 when some particle has it at the start of the step being stepped (or the
    // last one); steps read only these materials (presentMaterials in step_common.h).
    std::vector<uint8_t> present;
    bool isPresent(size_t material) const {
        return present.size() != materials.size() || present[material] != 0;
    }
    float fieldGH = 0.0f; // g H of the external field, measured in the last step (m^2/s^2)
    bool fieldMeasured = false;
    float lastMaxAccel = 0.0f;

    std::optional<uint32_t> findIndex(ParticleHandle handle) const; // nullopt: null or stale
    /// Adds a particle at the end of the arrays (the caller checked inputs and capacity), with
    /// `structure` (in [0, 1]) when its material yields and 0 otherwise.
    ParticleHandle append(glm::vec2 x, glm::vec2 v, uint16_t material, double expiry,
                          float structure = 0.0f);
    /// The handle of the particle in `slot` now: its generation and this world's tag.
    ParticleHandle handleOf(uint32_t slot) const {
        return ParticleHandle{slot, slotGeneration[slot], tag.value()};
    }
    /// Marks a removed particle's slot free and its handles stale.
    void releaseSlot(uint32_t slot);
    uint32_t checkedIndex(ParticleHandle handle, const char* function) const;
    void removeAt(uint32_t index);
    /// Removes every particle whose `kill` entry is non-zero, keeping the others in order.
    void removeMarked(const std::vector<uint8_t>& kill);
};

/// What `World::step` needs to take emission back when a plugin's `prepare` throws: the
/// emitters' clocks, the handle table's free list and size, the particle count and profile.
/// Restoring is exact while the emitted particles still sit at the end of the arrays, which
/// holds until the first sort of the step (after every prepare hook).
class EmissionUndo {
public:
    explicit EmissionUndo(const WorldState& s);
    void restore(WorldState& s) const;

private:
    bool m_active = false; // some emitter is open: the copies below were taken
    std::vector<EmitterState> m_emitters;
    std::vector<uint32_t> m_freeSlots;
    size_t m_slots = 0;
    uint32_t m_count = 0;
    uint64_t m_sorts = 0;
    Profile m_profile;
};

/// When a particle given `lifetime` seconds at simulated time `now` expires (unit: s; a
/// lifetime of 0 means never: +infinity).
inline double expiryTime(double now, float lifetime) {
    return lifetime > 0.0f ? now + double(lifetime) : std::numeric_limits<double>::infinity();
}

/// Emitters' particles for a step of `frameDt` (start of `World::step`); returns the count.
/// `blocked` counts those the particle limit refused, `skipped` those not placed because the
/// liquid at their place stands at rest density already.
uint32_t emitParticles(WorldState& s, float frameDt, uint32_t& blocked, uint32_t& skipped);

/// After a step (time already advanced): drains and expired lifetimes remove particles (into
/// `removed`), sensors measure. Returns the count removed.
uint32_t finishGameplay(WorldState& s);

/// Drops the last step's contact events (a step that simulated nothing; contacts.cpp).
void clearContacts(WorldState& s);

/// Particles across one emitter row: 1 + round(width / spacing) (unit: count).
inline double emitterLanes(float width, float spacing) {
    return 1.0 + std::round(double(width) / double(spacing));
}

/// `direction` scaled to unit length, computed in double so that neither a tiny nor a huge
/// vector underflows or overflows; (0, 0) for a zero or non-finite one.
inline glm::vec2 unitDirection(glm::vec2 direction) {
    const double len = std::hypot(double(direction.x), double(direction.y));
    if (!(len > 0.0) || !std::isfinite(len)) {
        return {0.0f, 0.0f};
    }
    return {float(double(direction.x) / len), float(double(direction.y) / len)};
}

/// The index of the live group `group` names; throws fluid::Error "<function>: ..." for a
/// null, stale or other world's handle (groups.cpp).
uint32_t checkedGroup(const WorldState& s, GroupHandle group, const char* function);
/// Colour mixing over `seconds` of simulated time (groups.cpp; World::step after the solver,
/// before removals): nothing unless a rate is set and some particle has a colour.
void mixColours(WorldState& s, double seconds);
/// Interpolation (groups.cpp): previous = current for every particle (when turned on, after an
/// explicit step, after a load).
void resetPrevious(WorldState& s);

/// The explicit solver's step (solver_explicit.cpp).
void stepExplicit(WorldState& state, float frameDt);

/// The position-based solver's step (solver_position_based.cpp).
void stepPositionBased(WorldState& state, float frameDt);
/// The position-based solver's sub-step (s): 1/60 s over `perFrame` (World::substepLength).
double substepLength(uint32_t perFrame);
/// The whole sub-steps of length `h` nearest to `due` seconds (a half rounds up; 0 for `due`
/// under h / 2): the world's clock stays within half a sub-step of the frames given, so a
/// frame a little short of a sub-step still takes it and the next frames pay the time back.
uint32_t dueSubsteps(double due, double h);

} // namespace fluid::detail

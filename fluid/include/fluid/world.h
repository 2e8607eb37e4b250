// fluid — 2D SPH liquid for games.
#pragma once

#include <fluid/error.h>
#include <fluid/gameplay.h>
#include <fluid/handle.h>
#include <fluid/material.h>
#include <fluid/plugin.h>
#include <fluid/task.h>

#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fluid {

class Registry;

/// The pressure solver a world runs every sub-step.
enum class Solver : uint8_t {
    /// Position-based fluids [Macklin & Mueller 2013]: predict positions, iterate the density
    /// constraint, velocity from positions, viscosity, vorticity confinement, surface tension.
    /// Holds water within a few percent of its rest density at 4 sub-steps per 60 Hz frame;
    /// the default (docs/position_based.md).
    PositionBased,
    /// The seed's explicit loop: density (eq. 2.3), equation of state (2.4), symmetric pressure
    /// force (2.5), viscosity (2.6), external forces, symplectic Euler (2.8, 2.9). Needs about
    /// 100 CFL sub-steps per frame to hold water incompressible.
    Explicit,
};

/// Pressure from density for `Solver::Explicit`.
enum class EquationOfState : uint8_t {
    /// The seed's eq. 2.4, p = k (rho - rho0), k = `Material::stiffness`. Negative pressure kept.
    /// Soft: fine for small zero-g blobs, not for tanks (water's k = 3 is a 1.7 m/s sound speed).
    Linear,
    /// Tait [Becker & Teschner 2007]: p = rho0 c^2 / 7 ((rho/rho0)^7 - 1), clamped at 0 (free
    /// surfaces held by cohesion instead), c = `WorldDef::soundSpeed` or derived from the scene.
    Tait,
};

/// Settings of `Solver::PositionBased`. Read them with `World::def().positionBased`; change them
/// between steps with `World::setPositionBased` (stepping thread).
struct PositionBasedDef {
    /// Sub-steps per 1/60 s of simulated time (unit: count; range [1, 12]): each is 1/60 s over
    /// this count whatever the frame length, so a 1 s frame at 4 takes 240, a 1/240 s frame
    /// one, and a shorter one carries its time to the next frame (`World::step`); the settings
    /// hold at any frame rate at the same cost per simulated second (`Profile::substeps` reports
    /// the count taken). Default 4, the `Quality::Game` preset's (`Quality::Precise` too, with
    /// 8 iterations). Fewer are faster and
    /// more compressible; a particle moves at most two support radii per sub-step (faster ones
    /// are slowed and counted in `Profile::speedClamped`). Without the coarse correction, below
    /// 3 x 3, 6 x 2 or 8 x 1 a deep tank boils (docs/position_based_method.md, "Settings"). Above
    /// 12 the game preset gains energy and the precise one costs over 38 ms per 2,000-particle
    /// frame (docs/levels.md, Corners).
    uint32_t substeps = 4;
    /// Density-constraint iterations (Jacobi sweeps) per sub-step (unit: count; range
    /// [1, 32], more costs over 50 ms per 2,000-particle frame; 1 only with `coarseCorrection`
    /// above 0, without it a dam gains energy: docs/levels.md, Corners). Default 1
    /// (`Quality::Game`, with the coarse correction; `Quality::Precise`: 8).
    uint32_t iterations = 1;
    /// Sub-steps between runs of viscosity, vorticity confinement and surface tension (unit:
    /// count; range [1, 64]); each run covers the time since the last one, and the frame's last
    /// sub-step always runs them. Default 2 (`Quality::Game`: saves two neighbour passes per
    /// skipped sub-step); `Quality::Precise` runs them every sub-step (1).
    uint32_t viscosityInterval = 2;
    /// Share of the coarse-grid density correction applied before the sweeps of each sub-step
    /// (unit: 1; range [0, 1]; 0 turns it off). The sweeps carry pressure about one support
    /// radius each, so a deep tank needs many of them; the coarse correction removes the
    /// large-scale compression (above 5%) in one grid solve, which lets few sweeps hold deep
    /// water (docs/position_based_method.md, "Coarse correction"). Default 0.4 (`Quality::Game`;
    /// `Quality::Precise`: 0).
    float coarseCorrection = 0.4f;
    /// Vorticity confinement strength epsilon (unit: 1; range [0, 1]): the share of a vortex's
    /// rotation speed at one support radius given back per radian turned, when the surface
    /// pass runs every 1/120 s or more often (both presets); longer runs give back
    /// proportionally less, and a particle spinning faster than a radian per run counts one
    /// (the confinement feeds
    /// the spin it reads; docs/position_based_method.md, "Velocity, viscosity, surface").
    /// 0 turns it off.
    float vorticity = 0.0f;
    /// How materials with a yield stress step (unit: switch; range [0, 1]): 1 with the
    /// elastoplastic shear constraint inside the sweeps, an elastic state and a structure per
    /// particle returned to the Herschel-Bulkley surface after every sweep, heaps that come to
    /// rest at the game preset; 0 with the stress pass after the solve (heaps creep at the game
    /// preset; docs/yield_stress.md, "Yield stress"). Newtonian materials step the same
    /// either way, bit for bit. Default 1 (both presets). Stepping thread, between steps.
    uint32_t shearConstraint = 1;
};

/// Named accuracy presets of the position-based solver (`positionBasedPreset`;
/// docs/position_based.md, "Which preset", has their measured compression and cost).
enum class Quality : uint8_t {
    /// The default (`PositionBasedDef{}`): 4 sub-steps x 1 iteration with the coarse correction
    /// (0.4), viscosity and surface tension every second sub-step: about a quarter of
    /// `Precise`'s cost for a few times its compression (docs/position_based.md, "Which preset").
    Game,
    /// 4 sub-steps x 8 iterations, no coarse correction, viscosity every sub-step: the least
    /// compression and the calmest floating Box2D bodies (docs/box2d.md, "Which preset").
    Precise,
};

/// The position-based settings of a named preset (pure function; any thread).
PositionBasedDef positionBasedPreset(Quality quality);

/// The solvers' names, as level files ("solver": "explicit") and messages write them: the one
/// table of them.
inline constexpr EnumName<Solver> kSolverNames[] = {
    {Solver::PositionBased, "position_based"},
    {Solver::Explicit, "explicit"},
};

/// The name of `solver` ("position_based", "explicit"); "" for a value not listed. Pure
/// function; any thread.
constexpr std::string_view solverName(Solver solver) {
    return nameIn(kSolverNames, solver);
}

/// The solver named `name` (exact, as `solverName` writes it), nothing for an unknown name.
/// Pure function; any thread.
constexpr std::optional<Solver> solverFromName(std::string_view name) {
    return valueIn(kSolverNames, name);
}

/// The equations of state's names, as level files ("equationOfState": "linear") and tools
/// write them: the one table of them.
inline constexpr EnumName<EquationOfState> kEquationOfStateNames[] = {
    {EquationOfState::Tait, "tait"},
    {EquationOfState::Linear, "linear"},
};

/// The name of `eos` ("tait", "linear"); "" for a value not listed. Pure function; any thread.
constexpr std::string_view equationOfStateName(EquationOfState eos) {
    return nameIn(kEquationOfStateNames, eos);
}

/// The equation of state named `name`, nothing for an unknown name. Pure function; any thread.
constexpr std::optional<EquationOfState> equationOfStateFromName(std::string_view name) {
    return valueIn(kEquationOfStateNames, name);
}

/// The presets' names, as level files ("quality": "precise"), the C API
/// (fluid_world_def_set_quality) and the tools' --quality write them: the one table of them.
inline constexpr EnumName<Quality> kQualityNames[] = {
    {Quality::Game, "game"},
    {Quality::Precise, "precise"},
};

/// The name of `quality` ("game", "precise"); "" for a value not listed. Pure function; any
/// thread.
constexpr std::string_view qualityName(Quality quality) {
    return nameIn(kQualityNames, quality);
}

/// The preset named `name` (exact, as `qualityName` writes it), nothing for an unknown name.
/// Pure function; any thread.
constexpr std::optional<Quality> qualityFromName(std::string_view name) {
    return valueIn(kQualityNames, name);
}

/// The long-frame rule: how many equal sub-steps a frame of `frameDt` takes when a 1/60 s
/// frame takes `perFrame` (unit: count). `perFrame` for a frame up to a tenth longer than
/// 1/60 s (a frame pacer's 1/59.94 s adds none), else as many as keep each sub-step no
/// longer than at 60 Hz, rounded up: `ceil(frameDt * 60 * perFrame - perFrame / 10)` (1 s at 4:
/// 240). So a setting tuned at 60 Hz holds at any frame rate at the same cost per simulated
/// second. A coupled Box2D frame of the explicit solver takes this many rounds
/// (`fluid::box2d::Coupling::step`); the position-based solver steps sub-steps of a fixed
/// length instead and carries what is left of a frame (`World::step`). `perFrame` in [1, 64]
/// (unit: count), `frameDt` finite in (0, 1] (unit: s); throws `fluid::Error` naming the
/// argument otherwise. Result in [perFrame, 66 x perFrame]. Pure function; any thread.
uint32_t frameSubsteps(uint32_t perFrame, float frameDt);

/// Everything a world is created from. Every field has a usable default.
struct WorldDef {
    /// Pressure solver. Default: `Solver::PositionBased`.
    Solver solver = Solver::PositionBased;
    /// Settings of the position-based solver (ignored by the explicit one).
    PositionBasedDef positionBased{};
    /// Equation of state of the explicit solver (ignored by the position-based one). Default
    /// Tait (stiff water under gravity).
    EquationOfState equationOfState = EquationOfState::Tait;
    /// Tait sound speed c of the explicit solver (unit: m/s; range 0 or [0.1, 1e4]). 0 derives
    /// it from the scene at every step: c = max(sqrt(k), 10 sqrt(g H), 10 sqrt(gamma m h / A))
    /// over the materials, g the largest external acceleration and H the fluid's extent along
    /// it (measured during the previous step; the first step has neither), the last term for
    /// the squeeze of surface tension; never decreasing over the world's life (the dam-break
    /// column collapses, its speed does not). Ten times the wave speeds keeps density errors
    /// near 1% (docs/solver.md).
    float soundSpeed = 0.0f;
    /// Slab depth that reads the materials' 3D mass and density in 2D (unit: m; range
    /// [1e-4, 1e3]). See `Material`. Default `kDefaultDepth` = 0.1293 m.
    float depth = kDefaultDepth;
    /// Courant number lambda of the explicit solver's sub-step dt <= lambda * spacing /
    /// (c + v_max) (unit: 1; range [0.01, 1]). Default 0.4.
    float courant = 0.4f;
    /// Most sub-steps one explicit `step` may take (unit: count; range [1, 1000]). When the
    /// CFL limit asks for more, the step uses this many, longer sub-steps and the speed cap
    /// holds it. It bounds a frame's cost: a sub-step costs about 0.3-0.8 us per particle on
    /// one thread, so 1000 sub-steps of 400 particles take about 0.3 s (the range went down
    /// from 10000, at which such a frame took 3.7 s).
    uint32_t maxSubsteps = 512;
    /// Most particles the world holds (unit: count; range [1, 2^26]); adding more throws.
    uint32_t maxParticles = 1u << 20;
    /// Workers of the world's own pool when `tasks.enqueue` is null (unit: count; range
    /// [1, 256]). 1 = serial on the stepping thread. They run on at most `usableCores()` threads
    /// (`Profile::threads`); results are the same for any count.
    uint32_t workerCount = 1;
    /// The host's thread system; when `enqueue` is set it is used and `workerCount` ignored.
    TaskHook tasks{};
};

/// Particle positions reach at most this many spacings of the world's finest material from the
/// origin (unit: count; 2^18): beyond it float rounds a position by more than 1/32 spacing
/// (docs/gameplay.md, Far from the origin, has the figures).
inline constexpr float kPositionSpacings = 262144.0f;
/// The position limit for coarse materials (unit: m): `World::positionLimit` never exceeds it.
inline constexpr float kMaxPositionLimit = 1e5f;

/// The numbers of `PositionBasedDef` (see `Field`), in the order snapshots store them. Static
/// storage. Any thread.
std::span<const Field<PositionBasedDef>> positionBasedFields();
/// The plain numbers of `WorldDef` (see `Field`): depth, courant, maxSubsteps and maxParticles,
/// in the order snapshots store them. `soundSpeed` (0 or a range), `workerCount` (with `tasks`)
/// and the enums are checked on their own. Static storage. Any thread.
std::span<const Field<WorldDef>> worldFields();

/// A block of liquid to spawn: the shape is filled on a square lattice at the material's spacing
/// (lattice points whose position lies inside the shape). Plain data.
struct BlobDef {
    /// The region filled (see `Shape`; `Shape::box`, `Shape::circle`, `Shape::polygon`), on the
    /// material's lattice; a circle of a yield-stress material (`Material::yieldStress` > 0)
    /// in rings a spacing apart instead, the outermost half a spacing inside the circle all
    /// round: a paste keeps the outline it starts with, and the lattice's is a staircase
    /// (docs/yield_stress.md, "A round outline").
    Shape shape;
    /// Initial velocity of every particle (unit: m/s; finite).
    glm::vec2 velocity{0.0f, 0.0f};
    /// Material of the particles (from `World::addMaterial`).
    MaterialId material{};
    /// Lifetime of every particle (unit: s; range [0, 1e6]; 0 = lives forever).
    float lifetime = 0.0f;
    /// Structure a yielding material's particles start with (unit: 1; range [0, 1]; read only
    /// with `PositionBasedDef::shearConstraint`): 0, the default, is freshly sheared paste, as
    /// an emitter pours it, which holds its yield stress at once but grips walls only as its
    /// structure rebuilds (about 0.5 s: a layer put on a wall first sags 1.5-11 cm); 1 is paste
    /// that has rested, which grips walls and holds up to twice its yield stress from the
    /// first step (docs/yield_stress.md, "The shear constraint"). Unused for other
    /// materials.
    float structure = 0.0f;
    /// Rotation of the lattice the blob is filled on, counter-clockwise (unit: rad; range
    /// [-6.2832, 6.2832]): 0, the default, lays rows along x; a layer on a slope filled with
    /// its rows along the slope has a flat top, where rows along x leave steps a spacing high
    /// that a yield-stress material keeps (a level file's blob key "latticeAngle"). A yielding
    /// circle's rings start at this angle.
    float latticeAngle = 0.0f;
    // ---- Groups (groups.h) ----
    /// The group the particles join (`createGroup`): they take its user data and colour
    /// (`GroupDef`). Null, the default, makes a new group for the blob (`spawnGroup` returns it;
    /// `groupOf` finds it from any of its particles). A stale handle is refused.
    GroupHandle group{};
};

/// The most stages a step's profile names (unit: count).
inline constexpr uint32_t kMaxProfileStages = 12;

/// One named stage of a step and the wall-clock time it took.
struct StageTime {
    /// The stage's name, fixed by the solver ("prepare", "sort", "density sweeps"...; static
    /// storage, never freed; docs/architecture.md lists each solver's stages).
    const char* name = nullptr;
    /// Wall-clock time summed over the step's sub-steps (unit: ms; >= 0).
    float ms = 0.0f;
};

/// Timings and counters of the last `World::step`. Times are wall-clock milliseconds summed over
/// the step's sub-steps; counters describe the last step. Read it on the thread that steps.
struct Profile {
    /// Whole step (unit: ms).
    float step = 0.0f;
    /// The step's stages in the order they run: "prepare", the solver's sub-step stages, then
    /// "finish"; entries [0, stageCount) are filled.
    std::array<StageTime, kMaxProfileStages> stages{};
    /// Filled entries of `stages` (unit: count; 0 before the first step, <= kMaxProfileStages).
    uint32_t stageCount = 0;
    /// The filled stages (a view into this profile).
    std::span<const StageTime> stageTimes() const { return {stages.data(), stageCount}; }
    /// The time of the stage called `name` (unit: ms; 0 when the solver has no such stage).
    float stage(std::string_view name) const;
    /// Sub-steps taken (unit: count).
    uint32_t substeps = 0;
    /// Density-constraint iterations per sub-step (unit: count; 0 for the explicit solver).
    uint32_t iterations = 0;
    /// Sub-step chosen by the CFL condition before the cap (unit: s; the explicit solver only).
    float cflDt = 0.0f;
    /// Tait sound speed used (unit: m/s; 0 with the linear equation of state or the
    /// position-based solver).
    float soundSpeed = 0.0f;
    /// Largest compression max(rho/rho0 - 1, 0) over particles at the end of the step (unit: 1).
    float densityErrorMax = 0.0f;
    /// Mean compression over particles at the end of the step (unit: 1).
    float densityErrorAvg = 0.0f;
    /// Particles whose speed hit the safety cap during the step (unit: count, summed over
    /// sub-steps).
    uint32_t speedClamped = 0;
    /// Particles whose acceleration was non-finite and was zeroed (unit: count; should be 0).
    uint32_t nonFiniteRepaired = 0;
    /// Particles to which a force plugin gave a non-finite acceleration: that plugin's
    /// contribution to them was dropped, the other plugins' kept (unit: count, summed over
    /// sub-steps and plugins; should be 0).
    uint32_t forceDropped = 0;
    /// The first force plugin, by its index in `World::forces()`, whose contribution was
    /// dropped during the step (unit: index; -1 for none).
    int32_t forceDroppedPlugin = -1;
    /// Particles to which a boundary plugin's `project` gave a non-finite position or velocity:
    /// each kept what it had before that plugin's call, the other plugins' moves kept (unit:
    /// count, summed over calls and plugins; should be 0). Not saved: a loaded world reads 0
    /// until it steps.
    uint32_t boundaryDropped = 0;
    /// The first boundary plugin, by its index in `World::boundaries()`, whose `project` was
    /// undone for some particle during the step (unit: index; -1 for none). Not saved.
    int32_t boundaryDroppedPlugin = -1;
    /// Particles found at exactly the position of another (projected onto the same wall
    /// corner, or spawned there) and moved 1/64 support off it (unit: count, summed over
    /// sub-steps).
    uint32_t separated = 0;
    /// Particles in the world at the end of the step (unit: count).
    uint32_t particles = 0;
    /// Particles emitters added at the start of the step (unit: count).
    uint32_t emitted = 0;
    /// Particles emitters could not add because the world was full (unit: count).
    uint32_t emitBlocked = 0;
    /// Particles emitters did not place because the liquid at their place already stood at
    /// its rest density (a full cup, a submerged nozzle), or the place lies inside a solid or
    /// outside a container (unit: count).
    uint32_t emitSkipped = 0;
    /// Particles drains and lifetimes removed at the end of the step (unit: count).
    uint32_t removed = 0;
    /// Threads that ran the step's tasks (unit: count; >= 1): the world's own pool runs
    /// `WorldDef::workerCount` workers on at most `usableCores()` threads; with the host's
    /// `tasks` hook, its `workerCount`. Not saved: a loaded world reads 1 until it steps.
    uint32_t threads = 1;
};

/// The instruction set the position-based solver's pair passes run on: "avx512", "avx2" or
/// "sse2" (plain C++ off x86). Chosen once per process, the widest the processor runs unless
/// the environment variable FLUID_SIMD names a narrower one. Results are bit-identical on every
/// set. Thread-safe.
const char* instructionSet();

class World;
namespace detail {
struct WorldState;
/// The world's internal state, for the project's own diagnostics and tests (fluid/src is not
/// installed: a game has no use for it). Stepping thread.
WorldState& stateOf(World& world);
} // namespace detail

/// A liquid simulation: particles, materials, plugins. No globals: worlds are independent.
/// Thread rule: a world is used from one thread at a time (the stepping thread); it uses the
/// task hook's workers only inside `step`. Spans returned by accessors stay valid until the next
/// call that changes the world (`step`, add, remove, spawn).
class World {
public:
    /// Creates an empty world; throws `fluid::Error` naming the first out-of-range field.
    explicit World(const WorldDef& def = {});
    /// Destroys the world, its plugins and its own thread pool (stepping thread, between steps).
    ~World();
    /// Moves the whole world; the moved-from world may only be destroyed or assigned.
    World(World&&) noexcept;
    /// Move assignment, as the move constructor.
    World& operator=(World&&) noexcept;

    /// Adds a material (validated, see `validate(Material)`); at most 65535. Its spacing in this
    /// world's depth must lie in [`kMinSpacing`, `kMaxSpacing`] and its smoothing distance in
    /// [`kMinSupportSpacings`, `kMaxSupportSpacings`] spacings; the error names the fields.
    /// Thread rule: the stepping thread, between steps.
    MaterialId addMaterial(const Material& material);
    /// Replaces a material's parameters (validated as by `addMaterial`). Throws for an unknown
    /// id. Thread rule: the stepping thread, between steps.
    void setMaterial(MaterialId id, const Material& material);
    /// The material behind `id`; throws for an unknown id.
    const Material& material(MaterialId id) const;
    /// Number of materials (unit: count).
    uint32_t materialCount() const;

    /// Adds one particle (finite position and velocity, unit: m and m/s; known material).
    /// Throws when the world is full (`WorldDef::maxParticles`).
    ParticleHandle addParticle(glm::vec2 position, glm::vec2 velocity, MaterialId material);
    /// Fills the blob's shape on its material's lattice; all or nothing. Lattice points that a
    /// boundary plugin `contains` (inside a solid, outside a container) are left out, and their
    /// count is written to `insideSolids` when given. Returns the particle count added (0 if
    /// the shape holds no free lattice point). Throws for bad geometry or a full world; when
    /// memory runs out, `fluid::Error` "spawnBlob: memory ran out making room for the blob's
    /// about N particles ..." with the `std::bad_alloc` nested in it (`std::rethrow_if_nested`
    /// finds it), the world left as it was.
    uint32_t spawnBlob(const BlobDef& blob, uint32_t* insideSolids = nullptr);
    /// Removes the particle; throws `fluid::Error` for a stale or null handle.
    void removeParticle(ParticleHandle handle);
    /// `handle` with this world's tag (same slot and generation): for a handle saved alongside a
    /// snapshot (or taken from the world it was saved from), used with the world loaded from
    /// it. Checks nothing; the particle's existence is `isValid`'s to say. Any thread.
    ParticleHandle adopt(ParticleHandle handle) const;
    /// `id` with this world's tag (same index): for an id of the world a snapshot was saved
    /// from, used with the world loaded from it. Checks nothing; the calls that take it check
    /// the index. Any thread.
    MaterialId adopt(MaterialId id) const;
    /// See `adopt(MaterialId)`.
    EmitterId adopt(EmitterId id) const;
    /// See `adopt(MaterialId)`.
    DrainId adopt(DrainId id) const;
    /// See `adopt(MaterialId)`.
    SensorId adopt(SensorId id) const;
    /// True while the particle behind `handle` exists.
    bool isValid(ParticleHandle handle) const;
    /// Current slot of the particle in the spans below, or nullopt for a stale handle.
    std::optional<uint32_t> indexOf(ParticleHandle handle) const;
    /// Handle of the particle in slot `index` (unit: index < particleCount()).
    ParticleHandle handleAt(uint32_t index) const;
    /// Position of a particle (unit: m); throws for a stale handle.
    glm::vec2 position(ParticleHandle handle) const;
    /// Velocity of a particle (unit: m/s); throws for a stale handle.
    glm::vec2 velocity(ParticleHandle handle) const;
    /// Sets a particle's velocity (unit: m/s, finite); throws for a stale handle.
    void setVelocity(ParticleHandle handle, glm::vec2 velocity);
    /// Gives a particle `seconds` more to live (unit: s; range [0, 1e6]; 0 = forever); it is
    /// removed at the end of the step in which it runs out (`RemovalCause::Lifetime`).
    void setLifetime(ParticleHandle handle, float seconds);
    /// Time the particle has left (unit: s; +infinity when it lives forever).
    float lifetime(ParticleHandle handle) const;

    /// Adds an emitter (see `EmitterDef`); throws `fluid::Error` naming the field for a bad
    /// definition (an unknown material, a rate the nozzle cannot fit).
    EmitterId addEmitter(const EmitterDef& def);
    /// Replaces an emitter's settings (move or aim the faucet; a rate of 0 closes it), keeping
    /// its clock, count and random state. Validated as `addEmitter`.
    void setEmitter(EmitterId id, const EmitterDef& def);
    /// An emitter's settings; throws for an unknown id.
    const EmitterDef& emitter(EmitterId id) const;
    /// Particles the emitter has emitted so far (unit: count); throws for an unknown id.
    uint32_t emittedCount(EmitterId id) const;
    /// Number of emitters (unit: count).
    uint32_t emitterCount() const;

    /// Adds a drain (see `DrainDef`); throws `fluid::Error` for a bad shape or material.
    DrainId addDrain(const DrainDef& def);
    /// A drain's settings; throws for an unknown id.
    const DrainDef& drain(DrainId id) const;
    /// Number of drains (unit: count).
    uint32_t drainCount() const;

    /// Adds a sensor (see `SensorDef`); throws `fluid::Error` for a bad shape. Amortized
    /// constant time: adding n sensors costs O(n). Stepping thread, between steps.
    SensorId addSensor(const SensorDef& def);
    /// A sensor's settings; throws for an unknown id.
    const SensorDef& sensor(SensorId id) const;
    /// Number of sensors (unit: count).
    uint32_t sensorCount() const;
    /// What the sensor held at the end of the last step, one entry per material (indexed by
    /// `MaterialId::index`). Zeros before the first step, and after `addMaterial` until the
    /// next step measures; a sensor added by `addSensor` reads zeros until then (the others
    /// keep their last readings). Throws for an unknown id.
    std::span<const SensorReading> sensorReading(SensorId id) const;

    /// Particles drains and lifetimes removed during the last step, ordered by drain (in the
    /// order added, lifetimes last) and then by the particles' array index (the position in
    /// the spans above) before removal: the same for any number of workers.
    std::span<const RemovedEvent> removedEvents() const;

    /// Writes the whole world (settings, materials, particles and handles, plugins with their
    /// parameters and state, emitters with their clocks and random state, drains, sensors,
    /// solver state, the last step's sensor readings and profile) to `out` in fluid's binary
    /// snapshot format. A world loaded from it continues bit-identically. Not saved: the task
    /// hook, the last step's `removedEvents` and the profile's stage times (wall-clock
    /// readings: a loaded world reads 0 for them), so two saves of the same state give the same
    /// bytes. Throws `fluid::Error` (`ErrorCode::Io`) if the stream fails.
    void save(std::ostream& out) const;
    /// `save` into the file `path` (replaced); throws `fluid::Error` (`ErrorCode::Io`) naming
    /// the file.
    void saveFile(const std::string& path) const;
    /// Reads a snapshot written by `save`. Plugins are re-created by type from `registry`
    /// (load your own plugin libraries into it first). `workerCount` 0 keeps the saved count;
    /// a set `tasks.enqueue` lends the host's threads instead. The header (magic, version,
    /// payload size) is read and checked first, the size against the bytes the stream holds
    /// when it can tell (a seekable stream), before the payload is read or allocated. Throws
    /// `fluid::Error` for a truncated, padded or corrupt snapshot (checksum), an unknown version
    /// or plugin type, or a value out of range (naming it: "particle 3 vx = inf is not
    /// finite"); a plugin's parameters pass its own checks, each value and then all together
    /// (`Plugin::checkParams`): "snapshot: boundary plugin 0: plugin 'boundary.box': the inner
    /// rectangle [0, 1] x [0, -0] is empty; ...". The code is `ErrorCode::UnknownName` for a
    /// plugin type not in `registry`, `ErrorCode::BadFile` for anything else the bytes hold
    /// (values the API's checks refuse included), `ErrorCode::OutOfMemory` for memory that ran
    /// out. Thread rule: any thread (the new world is the caller's).
    static World load(std::istream& in, const Registry& registry, uint32_t workerCount = 0,
                      const TaskHook& tasks = {});
    /// `load` from the file `path`; errors name the file (`ErrorCode::Io` for one that cannot be
    /// opened).
    static World loadFile(const std::string& path, const Registry& registry,
                          uint32_t workerCount = 0, const TaskHook& tasks = {});

    /// Adds a force plugin; the world owns it. Returns a reference valid for the world's life.
    ForcePlugin& addForce(std::unique_ptr<ForcePlugin> plugin);
    /// Adds a boundary plugin; the world owns it.
    BoundaryPlugin& addBoundary(std::unique_ptr<BoundaryPlugin> plugin);
    /// The force plugins, in the order added (they are applied in this order).
    std::span<const std::unique_ptr<ForcePlugin>> forces() const;
    /// The boundary plugins, in the order added.
    std::span<const std::unique_ptr<BoundaryPlugin>> boundaries() const;

    /// Replaces the position-based solver's settings (validated like `WorldDef`; throws
    /// `fluid::Error` naming the field and leaves them unchanged). Takes effect at the next step.
    void setPositionBased(const PositionBasedDef& settings);

    /// True while `step` runs, as seen from a plugin's hook or a task during it: the calls that
    /// change, save or step the world then throw `fluid::Error` with `ErrorCode::WrongState`
    /// (docs/plugins.md, "Calling back into the world"). Stepping thread.
    bool stepping() const;
    /// Advances the world by one game frame (unit: s; finite, range (0, 1]; typically 1/60; it
    /// may change from frame to frame). The position-based solver steps in sub-steps of a fixed
    /// length, `substepLength()` (1/240 s at the default 4 per 1/60 s): the frame simulates the
    /// whole sub-steps nearest to the time due, the carried time plus frameDt (`substepsFor`),
    /// and carries the difference, positive or negative, to the next frame (`carriedTime`), so
    /// `time()` stays within half a sub-step of the sum of the frames given, any sequence of
    /// frame lengths steps the same sub-steps as a fixed 60 Hz, frames of 1/240 s with a timer's
    /// jitter step one sub-step each, and a frame that leaves less than half a sub-step due
    /// steps nothing (no events, an empty `profile()`). The explicit solver steps the whole
    /// frame in as many sub-steps as its CFL condition asks (see `Profile::substeps`). In
    /// order: emitters add the frame's particles, the solver runs, drains and lifetimes remove
    /// particles (`removedEvents`), sensors measure (`sensorReading`). Throws `fluid::Error`
    /// for a bad frameDt, and passes on what a plugin's `prepare` throws, leaving the world
    /// unchanged in both cases; a hook that throws later, during the sub-steps, leaves it
    /// mid-step.
    void step(float frameDt);
    /// The sub-steps the position-based solver takes for a `step(frameDt)` now: the whole
    /// number of `substepLength()`s nearest to `carriedTime() + frameDt`, a half rounded up
    /// (unit: count; range [0, 3840]; 0 when the frame only adds to the carried time). For the
    /// explicit solver, which picks its own during the step from the CFL condition
    /// (`Profile::substeps`), this is the long-frame rule's
    /// `frameSubsteps(def().positionBased.substeps, frameDt)`. `frameDt` as `step` (unit: s;
    /// finite, range (0, 1]); throws `fluid::Error` ("World::substepsFor: frameDt = ... is out
    /// of range ...") otherwise. Stepping thread, between steps.
    uint32_t substepsFor(float frameDt) const;
    /// The position-based solver's sub-step (unit: s): 1/60 s over
    /// `def().positionBased.substeps` (1/240 s by default, range [1/3840, 1/60]). Stepping
    /// thread, between steps.
    double substepLength() const;
    /// Frame time given to `step` that the position-based solver has not simulated yet, negative
    /// when its sub-steps ran ahead of the frames (unit: s; range [-substepLength() / 2,
    /// substepLength() / 2) for the settings of the last step; a world loaded from a snapshot
    /// of an earlier release may hold up to one sub-step): the next step starts with it. 0 for
    /// the explicit solver. Saved in snapshots. Stepping thread, between steps.
    double carriedTime() const;

    /// Particles in the world (unit: count).
    uint32_t particleCount() const;
    /// Position x, y per slot (unit: m).
    std::span<const float> positionX() const;
    /// See `positionX`.
    std::span<const float> positionY() const;
    /// Velocity x, y per slot (unit: m/s).
    std::span<const float> velocityX() const;
    /// See `velocityX`.
    std::span<const float> velocityY() const;
    /// Density per slot from the last sub-step (unit: kg/m^3; 0 before the first step).
    std::span<const float> density() const;
    /// Pressure per slot from the last sub-step (unit: Pa; the position-based solver's: its
    /// sweeps' and its coarse correction's together).
    std::span<const float> pressure() const;
    /// Deviatoric stress s_xx (= -s_yy) per slot (unit: Pa): the stress a yielding material
    /// (`Material::yieldStress`, `consistency`) holds, at most the yield stress at rest and
    /// tau_y + K rate^n in flow (with `PositionBasedDef::shearConstraint`, up to twice the yield
    /// stress at rest once the particle's structure has rebuilt); 0 for a Newtonian material.
    /// hypot(s_xx, s_xy) over the yield stress tells how close a particle is to flowing (1:
    /// flowing). Thread rule: as `density`.
    std::span<const float> stressXX() const;
    /// Deviatoric shear stress s_xy per slot (unit: Pa); see `stressXX`.
    std::span<const float> stressXY() const;
    /// Material index per slot.
    std::span<const uint16_t> materialIndex() const;

    /// Timings and counters of the last step.
    const Profile& profile() const;
    /// Sub-steps the last step took (unit: count), same as `profile().substeps`.
    uint32_t lastSubsteps() const;
    /// Simulated time since creation (unit: s): the frames stepped, less `carriedTime()` (so up
    /// to half a sub-step ahead of them when that is negative). Stepping thread, between steps.
    double time() const;
    /// The definition the world was created from.
    const WorldDef& def() const;
    /// Lattice spacing of material `id` in this world's slab (unit: m).
    float spacing(MaterialId id) const;
    /// Largest |x| and |y| a particle may have (unit: m; 0 before the first material): float
    /// keeps positions to 1/32 of the finest spacing of the world's materials out to
    /// `kPositionSpacings` spacings (2,621 m for 1 cm water), and never beyond
    /// `kMaxPositionLimit`. Particles, blobs and emitters outside it are refused; a particle
    /// that leaves it is removed at the end of the step (`RemovalCause::OutOfRange`); a world
    /// larger than this moves its origin (docs/gameplay.md, Far from the origin). Any thread
    /// while no step runs.
    float positionLimit() const;

private:
    friend detail::WorldState& detail::stateOf(World& world);
    void validateEmitter(const EmitterDef& def, const char* function) const;
    uint32_t placeBlob(const BlobDef& blob, glm::vec2 lo, glm::vec2 hi, float spacing,
                       double cols, double rows, uint32_t* insideSolids);
    std::unique_ptr<detail::WorldState> m_state;
};

} // namespace fluid

// fluid — 2D SPH liquid for games.
#pragma once

#include <fluid/error.h>
#include <fluid/material.h>

#include <glm/vec2.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace fluid {

/// What kind of value a declared parameter holds.
enum class ParamType : uint8_t {
    /// One number (a double), checked against [minValue, maxValue].
    Number,
    /// A list of points (x, y) in metres, e.g. a polygon's vertices; its length is checked
    /// against [minValue, maxValue] (unit: count) and every coordinate must be finite. Set with
    /// `Plugin::setPoints`; `defaultValue` is unused (a new plugin starts with no points).
    Points,
};

/// One parameter a plugin declares: what level files, tuning panels and error messages show.
/// Thread rule: plain data, usually a `static constexpr` array in the plugin class.
struct ParamDecl {
    /// Key in level files and `Plugin::setParam` (ASCII identifier, e.g. "strength"; at most
    /// `kMaxNameBytes` bytes and no control character: `Registry::add` refuses others).
    std::string_view name;
    /// SI unit shown next to the value (e.g. "m/s^2"; "1" for dimensionless).
    std::string_view unit;
    /// Value a new plugin starts with (unit: `unit`).
    double defaultValue = 0.0;
    /// Smallest accepted value (unit: `unit`).
    double minValue = 0.0;
    /// Largest accepted value (unit: `unit`).
    double maxValue = 0.0;
    /// One line for humans.
    std::string_view description;
    /// Number (the default) or a point list.
    ParamType type = ParamType::Number;
};

/// Appends plain values to a plugin's snapshot state (see `Plugin::saveState`).
/// Thread rule: stepping thread, inside `saveState` only.
class StateWriter {
public:
    /// Appends the bytes of `value` (a trivially copyable type: numbers, flags, small structs).
    template <class T> void write(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>, "StateWriter::write: plain data only");
        const auto* bytes = reinterpret_cast<const std::byte*>(&value);
        m_bytes.insert(m_bytes.end(), bytes, bytes + sizeof(T));
    }
    /// Everything written so far.
    const std::vector<std::byte>& bytes() const { return m_bytes; }

private:
    std::vector<std::byte> m_bytes;
};

/// Reads back what a `StateWriter` wrote, in the same order (see `Plugin::restoreState`).
/// Thread rule: stepping thread, inside `restoreState` only.
class StateReader {
public:
    /// Reads from `bytes`, which must outlive the reader.
    explicit StateReader(std::span<const std::byte> bytes) : m_bytes(bytes) {}
    /// Reads the next value; throws `fluid::Error` when the state is shorter than asked.
    template <class T> T read() {
        static_assert(std::is_trivially_copyable_v<T>, "StateReader::read: plain data only");
        if (m_bytes.size() - m_offset < sizeof(T)) {
            throw Error("snapshot: plugin state is truncated (" + std::to_string(m_bytes.size()) +
                        " bytes, read past the end at byte " + std::to_string(m_offset) + ")");
        }
        T value;
        std::memcpy(&value, m_bytes.data() + m_offset, sizeof(T));
        m_offset += sizeof(T);
        return value;
    }
    /// Bytes not read yet (unit: count).
    std::size_t remaining() const { return m_bytes.size() - m_offset; }

private:
    std::span<const std::byte> m_bytes;
    std::size_t m_offset = 0;
};

struct StepContext;

/// Which hook set a plugin implements.
enum class PluginKind : uint8_t {
    /// `ForcePlugin`: adds acceleration to particles.
    Force,
    /// `BoundaryPlugin`: solids the fluid cannot enter.
    Boundary,
};

/// The particles as plugins see them during a sub-step: structure of arrays in the sub-step's
/// (cell-sorted) order, all spans `count` long. Valid only inside the hook call.
struct ParticleView {
    /// Position x, y (unit: m).
    std::span<const float> px, py;
    /// Velocity x, y (unit: m/s).
    std::span<const float> vx, vy;
    /// Material index of each particle (see `World::material`).
    std::span<const uint16_t> material;
    /// The world's materials, by index.
    std::span<const Material> materials;
    /// Number of particles (unit: count).
    uint32_t count = 0;
};

/// Base of every plugin: a type name and the declared parameters with their current values.
/// Thread rule: `setParam` and `param` only between steps, on the stepping thread.
class Plugin {
public:
    /// `type` is the registry's string ("force.gravity"); `params` must outlive the plugin
    /// (a static array); values start at their defaults.
    Plugin(std::string_view type, PluginKind kind, std::span<const ParamDecl> params);
    /// Destroyed by its owner (the world or the caller); not while a step runs.
    virtual ~Plugin() = default;
    /// Plugins are not copyable: a world owns each one.
    Plugin(const Plugin&) = delete;
    /// Not assignable either.
    Plugin& operator=(const Plugin&) = delete;

    /// Registry type string, e.g. "boundary.box".
    std::string_view type() const { return m_type; }
    /// Force or boundary.
    PluginKind kind() const { return m_kind; }
    /// Declared parameters, in declaration order.
    std::span<const ParamDecl> params() const { return m_decls; }
    /// Current value of parameter `name` (unit: its `ParamDecl::unit`); throws `fluid::Error`
    /// naming the plugin type and the unknown name.
    double param(std::string_view name) const;
    /// Sets parameter `name`; throws `fluid::Error` for an unknown name, a non-finite value or
    /// a value outside [minValue, maxValue], naming the plugin, key, value, range and unit.
    void setParam(std::string_view name, double value);
    /// Current points of the `ParamType::Points` parameter `name` (unit: m); throws
    /// `fluid::Error` for an unknown name or a number parameter.
    std::span<const glm::vec2> points(std::string_view name) const;
    /// Sets the point list `name` (unit: m); throws `fluid::Error` naming the plugin and key for
    /// an unknown name, a number parameter, a non-finite coordinate or a count outside
    /// [minValue, maxValue].
    void setPoints(std::string_view name, std::span<const glm::vec2> points);
    /// Throws `fluid::Error` when the parameters together do not make a valid plugin (a box
    /// whose minX is not below its maxX), naming the plugin, the values and what was expected.
    /// `setParam` checks one value at a time, and values set one by one may pass through a
    /// combination that is not valid, so this is a separate check: `Registry::create` and the
    /// level loader call it once every value is set. Default: nothing. Stepping thread, between
    /// steps.
    virtual void checkParams() const {}

    /// Once per `World::step`, after the sub-steps, on the stepping thread (advance a kinematic
    /// pose, forget a one-shot trigger). Default: nothing.
    virtual void finish(const StepContext& /*context*/) {}
    /// Writes the plugin's own state beyond its parameters (which the world saves itself) into
    /// a snapshot: anything a restored world needs to continue bit-identically. Default: nothing.
    virtual void saveState(StateWriter& /*out*/) const {}
    /// Reads what `saveState` wrote, after the parameters were restored; throws `fluid::Error`
    /// for bad state. Default: nothing.
    virtual void restoreState(StateReader& /*in*/) {}

protected:
    /// Current value of the parameter at `index` in declaration order (for plugin code).
    double value(std::size_t index) const { return m_values[index]; }
    /// Points of the `ParamType::Points` parameter at `index` (for plugin code; unit: m).
    std::span<const glm::vec2> pointsAt(std::size_t index) const { return m_points[index]; }
    /// Stores a value the plugin computed itself (a pose advanced by its velocity, a trigger
    /// reset), without range checks and without `onParamChanged`. Stepping thread only.
    void storeValue(std::size_t index, double value) { m_values[index] = value; }
    /// Called after `setParam` or `setPoints` changed a value (stepping thread); it may throw
    /// `fluid::Error` to refuse the value, which then reverts to the old one. Default: nothing.
    virtual void onParamChanged(std::size_t /*index*/) {}

private:
    std::string m_type;
    PluginKind m_kind;
    std::span<const ParamDecl> m_decls;
    std::vector<double> m_values;
    std::vector<std::vector<glm::vec2>> m_points; // per declaration; empty for numbers
};

/// What a force plugin gets once per sub-step.
struct ForceContext {
    /// The particles (read only).
    ParticleView particles;
    /// Acceleration accumulators x, y (unit: m/s^2): add to slot i for i in your range only.
    std::span<float> ax, ay;
    /// Sub-step length (unit: s).
    float dt = 0.0f;
    /// Simulated time at the start of the sub-step (unit: s).
    double time = 0.0;
};

/// What every plugin gets once per `World::step`: the same values in `prepare` (before the
/// sub-steps) and in `finish` (after them; `time` is still the step's start).
struct StepContext {
    /// The time this step simulates (unit: s): the frame passed to `World::step`, or for the
    /// position-based solver the whole sub-steps it takes (`World::step`, "carries").
    float frameDt = 0.0f;
    /// Simulated time at the start of the step (unit: s).
    double time = 0.0;
    /// Spacing at which boundary samples are laid (unit: m): the lattice spacing of the first
    /// material (by index) that some particle has, or of material 0 in a world without
    /// particles; it changes when that material does (rebuild the samples then).
    float sampleSpacing = 0.0f;
    /// Largest smoothing distance of the materials the particles have (unit: m; all of the
    /// world's materials when it has no particles).
    float supportRadius = 0.0f;
};

/// An external acceleration field (gravity, wind, vortex, pointer...).
/// Thread rule: `prepare` runs on the stepping thread once per step; `apply` runs on worker
/// threads in parallel over disjoint ranges and must write only `ax[i], ay[i]` for i in
/// [begin, end), reading anything in the context; keep it free of shared mutable state.
class ForcePlugin : public Plugin {
public:
    /// See `Plugin::Plugin`.
    ForcePlugin(std::string_view type, std::span<const ParamDecl> params)
        : Plugin(type, PluginKind::Force, params) {}
    /// Once per step before the sub-steps (read host input, precompute). Default: nothing.
    virtual void prepare(const StepContext& /*context*/) {}
    /// Adds this field's acceleration to particles [begin, end).
    virtual void apply(const ForceContext& context, uint32_t begin, uint32_t end) = 0;
};

/// Boundary samples: points filling a solid's skin, at `StepContext::sampleSpacing`, several
/// layers deep (enough to cover one support radius). They act as fluid at rest density in the
/// density sum, carry a pressure extrapolated from the fluid [Adami 2012, eq. 27] and so push
/// back, and pass their velocity to the fluid through the wall viscosity. Volume of each sample:
/// sampleSpacing^2 (unit: m^2).
struct BoundarySamples {
    /// Position x, y (unit: m).
    std::vector<float> px, py;
    /// Velocity x, y of the solid at the sample (unit: m/s); the world moves samples with it
    /// during the sub-steps of a step.
    std::vector<float> vx, vy;
    /// Drops every sample.
    void clear() {
        px.clear();
        py.clear();
        vx.clear();
        vy.clear();
    }
    /// Appends one sample.
    void add(float x, float y, float velX = 0.0f, float velY = 0.0f) {
        px.push_back(x);
        py.push_back(y);
        vx.push_back(velX);
        vy.push_back(velY);
    }
    /// Number of samples (unit: count).
    std::size_t size() const { return px.size(); }
};

/// How the position-based solver's coarse pressure solve has moved one of a plugin's rigid bodies
/// (`BoundaryPlugin::rigidBodies`) within the step so far: at time t into the step the body stands
/// `offset + velocity t` away from where its host's poses put it (its samples already do). A
/// plugin that projects particles out of the body's shape moves the shape with it, so the
/// particles end outside where the body will be once the host takes the correction
/// (`receiveBodyImpulses`). Plain data.
struct BodyShift {
    /// The velocity the solve gave the body (unit: m/s).
    glm::vec2 velocity{0.0f, 0.0f};
    /// The offset at the step's start (unit: m): the shift at time t is offset + velocity t.
    glm::vec2 offset{0.0f, 0.0f};
};

/// What a boundary plugin's `project` gets after particles moved: once per sub-step after the
/// explicit solver's integration; twice per sub-step with the position-based solver (on the
/// predicted positions before the density constraint, and at the end of the sub-step).
struct ProjectContext {
    /// Position x, y (unit: m), writable for slots in your range only.
    std::span<float> px, py;
    /// Where each particle was before this move (unit: m), at `prevTimeInStep`: on the
    /// admissible side of every solid when the previous projection held. A solid tests the
    /// path prev -> current against its surface, so a fast particle cannot tunnel through a
    /// thin wall.
    std::span<const float> prevX, prevY;
    /// Velocity x, y (unit: m/s), writable for slots in your range only.
    std::span<float> vx, vy;
    /// Material index of each particle.
    std::span<const uint16_t> material;
    /// Sub-step length (unit: s).
    float dt = 0.0f;
    /// Time since the start of the step at the end of this sub-step (unit: s; the same for
    /// both calls of a position-based sub-step).
    float timeInStep = 0.0f;
    /// Time since the start of the step at which the particles stood at `prevX, prevY` (unit:
    /// s): the start of the sub-step for the first call, `timeInStep` for a position-based
    /// sub-step's second call.
    float prevTimeInStep = 0.0f;
    /// The step's boundary sample spacing, `StepContext::sampleSpacing` (unit: m).
    float spacing = 0.0f;
    /// Per body of this plugin's `rigidBodies()`, in that order, the coarse solve's shift of it
    /// (`BodyShift`); empty when nothing shifted any (no bodies, no coarse solve). Read-only.
    std::span<const BodyShift> bodyShifts;
};

/// A rigid body whose samples a boundary plugin lays (a Box2D body, or another physics engine's):
/// what the position-based solver's coarse pressure solve needs to make the body one of its
/// unknowns (docs/position_based.md, "Bodies in the coarse solve"). The solve moves the body
/// along x and y; its turning comes from the sweeps' forces on its samples (`receiveForces`).
/// A body left out of `BoundaryPlugin::rigidBodies`, or with `mass` 0, is moved by the host only
/// (static, kinematic): the solve takes no flux through it. A body may also be listed only to
/// ask for contact events (`contacts`). Plain data.
struct RigidBody {
    /// Mass (unit: kg, weighed as the fluid's particles are: `Material::mass`, a slab
    /// `WorldDef::depth` deep; range (0, 1e9], or 0 for a body the fluid cannot move).
    float mass = 0.0f;
    /// Its samples: [sampleBegin, sampleEnd) of the plugin's `samples()` (unit: index).
    uint32_t sampleBegin = 0, sampleEnd = 0;
    /// True to have the world report the liquid's contacts with this body after each step
    /// (`fluid::bodyContacts`, <fluid/contacts.h>); a body of any mass, 0 included, may ask.
    /// False (the default) costs nothing.
    bool contacts = false;
};

/// What the coarse pressure solve did to one `RigidBody` over a `World::step`: the pressure's
/// impulse, and the displacement it gave the body's samples during the step (the fluid was
/// moved out of the way of the body at its corrected place). A host that wants the fluid and its
/// body to agree adds `impulse / mass` to the body's velocity and moves it by `displacement` (as
/// `fluid::box2d::Coupling` does). Plain data.
struct RigidBodyImpulse {
    /// Impulse (unit: N s).
    glm::vec2 impulse{0.0f, 0.0f};
    /// How far the samples were moved beyond their own velocity's path by the end of the step
    /// (unit: m).
    glm::vec2 displacement{0.0f, 0.0f};
};

/// A solid the fluid cannot enter (container, polygon, moving paddle, rigid body...).
/// What a boundary's `project` keeps, which decides when it projects (see `BoundaryPlugin::role`).
enum class BoundaryRole : uint8_t {
    /// Keeps particles out of a solid (a disc, a polygon, a Box2D body).
    Solid,
    /// Keeps particles on their side of a wall they cannot cross (a chain of segments).
    Wall,
    /// Keeps particles inside the region the liquid lives in (a tank: `boundary.box`).
    Container,
};

/// Thread rule: `prepare` and `receiveForces` run on the stepping thread; `project` runs on
/// worker threads in parallel over disjoint ranges and writes only slots [begin, end).
class BoundaryPlugin : public Plugin {
public:
    /// See `Plugin::Plugin`.
    BoundaryPlugin(std::string_view type, std::span<const ParamDecl> params)
        : Plugin(type, PluginKind::Boundary, params) {}
    /// Once per step: refresh `samples()` (positions at the start of the step and velocities).
    virtual void prepare(const StepContext& context) = 0;
    /// Safety net after particles moved (see `ProjectContext`): moves particles [begin, end)
    /// that ended up inside the solid back to its surface and removes their velocity into it.
    virtual void project(const ProjectContext& context, uint32_t begin, uint32_t end) = 0;
    /// True to have the fluid's force on each sample reported through `receiveForces`.
    virtual bool wantsForces() const { return false; }
    /// What `project` keeps (stepping thread; constant for the plugin's life). The step
    /// projects solids first, then walls, then containers, each group in the order added: where
    /// a moving solid pushes a particle against a tank's wall, the tank has the last word and
    /// the particle stays in the liquid's domain (the next projection pushes it out of the
    /// solid). Default: `BoundaryRole::Solid`.
    virtual BoundaryRole role() const { return BoundaryRole::Solid; }
    /// After the step: the fluid's force on each sample, averaged over the step's sub-steps
    /// (unit: N), and how fast its viscous part grows with the sample's velocity against the
    /// fluid's, `drag` = -dF/dv_sample >= 0 (unit: N s/m; a host integrating a body explicitly
    /// needs it to stay stable in a viscous fluid), all in sample order. Default: nothing.
    virtual void receiveForces(std::span<const float> /*fx*/, std::span<const float> /*fy*/,
                               std::span<const float> /*drag*/) {}
    /// Wall friction: scale of the fluid's viscosity against this solid (unit: 1; 0 = free slip,
    /// 1 = the fluid's own viscosity, larger = stickier).
    virtual float friction() const { return 0.0f; }
    /// The rigid bodies among this plugin's samples, as the last `prepare` left them (see
    /// `RigidBody`); the position-based solver's coarse correction takes each one with a mass
    /// as an unknown, so the fluid's large-scale pressure moves it. Stepping thread. Default:
    /// none.
    virtual std::span<const RigidBody> rigidBodies() const { return {}; }
    /// After the step, before `receiveForces`: what the coarse pressure solve did to each body
    /// of `rigidBodies()`, in the same order (all zero without the coarse correction).
    /// Stepping thread. Default: nothing.
    virtual void receiveBodyImpulses(std::span<const RigidBodyImpulse> /*impulses*/) {}
    /// True when `point` (unit: m) lies inside rigid body `body` (index in `rigidBodies()`) at
    /// the place its samples stand at `timeInStep` seconds into the step (moved by their own
    /// velocities). The coarse solve reads the body's outline on its grid with it; a plugin that
    /// answers false everywhere has the outline read from its samples instead (coarser).
    /// Stepping thread, during the sub-steps: read only. Default: false.
    virtual bool bodyContains(uint32_t /*body*/, glm::vec2 /*point*/, float /*timeInStep*/) const {
        return false;
    }
    /// The call that must step the world while this plugin is in it, or nullptr when a bare
    /// `World::step` is fine (the default). A plugin that carries another engine's bodies
    /// returns its host's step function (such as "fluid::box2d::Coupling::step"), except while
    /// that host is stepping the world itself: `World::step` then refuses to run, throwing
    /// `fluid::Error` with this name, so that the obvious call cannot leave the bodies behind.
    /// Stepping thread; read at the start of every `World::step`.
    virtual const char* steppedBy() const { return nullptr; }
    /// True when `point` (unit: m) lies in what `project` keeps particles out of: inside a
    /// solid, outside a container; a wall has no inside. Read from the plugin's parameters as
    /// they are now (it may be called before any `prepare`): `World::spawnBlob` leaves out the
    /// lattice points it returns true for. Default: false (the plugin does not say). Stepping
    /// thread.
    virtual bool contains(glm::vec2 /*point*/) const { return false; }
    /// The samples, as left by the last `prepare`.
    const BoundarySamples& samples() const { return m_samples; }

protected:
    /// Filled by the plugin in `prepare`.
    BoundarySamples m_samples;
};

} // namespace fluid

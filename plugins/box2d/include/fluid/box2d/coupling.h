// fluid — two-way coupling with Box2D 2.4 rigid bodies (library target fluid::box2d).
#pragma once

#include <fluid/contacts.h>
#include <fluid/material.h>
#include <fluid/world.h>

#include <glm/vec2.hpp>

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <span>
#include <unordered_set>
#include <vector>

class b2Body;
class b2Fixture;
class b2World;

namespace fluid::box2d {

/// Which fixtures touch fluid, and the settings of the frame `Coupling::step` runs.
/// Plain data; validated by the `Coupling` constructor and `Coupling::setDef` (they throw
/// `fluid::Error` naming the field, its value and range).
struct CouplingDef {
    /// A fixture touches fluid when `(fixture.GetFilterData().categoryBits & categoryMask) != 0`
    /// (unit: bit mask; default 0xFFFF: every fixture). Sensors (`b2Fixture::IsSensor`) never do.
    uint16_t categoryMask = 0xFFFF;
    /// Per-fixture choice on top of the mask (for example from the game's `userData`): a
    /// fixture touches fluid only if this returns true. Empty = every fixture the mask lets
    /// through. Called on the stepping thread at every step, for every fixture; must not
    /// create or destroy bodies.
    std::function<bool(const b2Fixture&)> filter;
    /// Wall viscosity of every fixture (unit: 1; range [0, 10]; 0 = free slip, 1 = the
    /// fluid's own viscosity against the surface, larger = stickier).
    float friction = 1.0f;
    /// A body that starts touching fluid with its centre of mass moving faster than this makes
    /// a `SplashEvent` (unit: m/s; range [0, 1e3]).
    float splashSpeed = 1.0f;
    /// Velocity iterations of the `b2World::Step` that `Coupling::step` runs (unit: count;
    /// range [1, 1000]).
    int32_t velocityIterations = 8;
    /// Position iterations of that `b2World::Step` (unit: count; range [1, 1000]).
    int32_t positionIterations = 3;
};

/// What the fluid did to one body during the last step, and how much of it is in fluid.
/// Plain data; valid until the next step.
struct BodyReport {
    /// The body (owned by the game's `b2World`).
    b2Body* body = nullptr;
    /// The fluid's force on the body, pressure and viscosity, averaged over the step (unit: N).
    /// Reported for every body; dynamic bodies receive it through the added-mass relaxation
    /// (see `Coupling`), which gives the same force once it holds steady.
    glm::vec2 force{0.0f, 0.0f};
    /// The fluid's torque about the body's centre of mass, averaged over the step (unit: N m;
    /// counter-clockwise positive).
    float torque = 0.0f;
    /// Area of the body's circle and polygon fixtures that lies in fluid at the end of the step
    /// (unit: m^2; see `Coupling` for how it is measured).
    float submergedArea = 0.0f;
    /// `submergedArea` over the area of the body's coupled circle and polygon fixtures (unit: 1;
    /// range [0, 1]; 0 for a body with only edges and chains).
    float submergedFraction = 0.0f;
    /// Coupled outline points of the body with fluid next to them (unit: count): 0 = dry.
    uint32_t wetPoints = 0;
    /// The material most of the wet points touch (one of the world's; meaningful when
    /// `wetPoints > 0`).
    MaterialId material{};
};

/// A body entered fluid fast: it was dry at the end of the previous step, is wet now, and its
/// centre of mass moved faster than `CouplingDef::splashSpeed`. Plain data.
struct SplashEvent {
    /// The body.
    b2Body* body = nullptr;
    /// Mean position of the body's wet outline points (unit: m): where the splash is.
    glm::vec2 position{0.0f, 0.0f};
    /// Speed of the body's centre of mass during the fluid's step (unit: m/s): from where the
    /// previous step left it to where Box2D put it, over dt.
    float speed = 0.0f;
    /// The material it hit (one of the world's).
    MaterialId material{};
};

/// Whether a contact began or ended.
enum class ContactPhase : uint8_t {
    /// The body was dry after the previous step and is wet now.
    Begin,
    /// The body was wet after the previous step and is dry now (or stopped being coupled:
    /// its fixtures were filtered out; a destroyed body reports nothing).
    End,
};

/// A body started or stopped touching fluid (one event per body, not per particle).
struct ContactEvent {
    /// The body.
    b2Body* body = nullptr;
    /// Begin or end.
    ContactPhase phase = ContactPhase::Begin;
    /// The material touched most (Begin: now; End: at the last wet step).
    MaterialId material{};
};

/// What the liquid did to one body that asked for contact events (`Coupling::setContactEvents`)
/// during the last `Coupling::step` or `stepFluid`, over all its rounds: the world's
/// `fluid::BodyContact` (<fluid/contacts.h>) for a Box2D body. Made for each asking body that
/// some particle touched (came within `fluid::kContactReach` sample spacings of its samples at
/// the end of a sub-step); a dry body reports nothing. Plain data; valid until the next step.
struct ParticleContact : ContactSummary {
    /// The body (owned by the game's `b2World`).
    b2Body* body = nullptr;
};

/// The areal density of a material (unit: kg/m^2): rest density x the world's slab depth. A
/// Box2D body with this `b2FixtureDef::density` is neutrally buoyant in that material; half of
/// it floats half submerged. Any thread.
float arealDensity(const World& world, MaterialId material);

/// The least mass a coupled dynamic body may have (unit: kg). Box2D divides by a body's mass:
/// under about 3e-39 kg the inverse overflows a float and the body turns NaN at its first step,
/// and the fluid's impulses throw a body of, say, 1e-30 kg to an infinite speed. A milligram is
/// far below any body a game floats (a 5 mm box at a hundredth of water's areal density weighs
/// 3e-5 kg). Level files, Box2D saves and `Coupling::step` refuse lighter dynamic bodies. Any
/// thread.
inline constexpr float kMinBodyMass = 1e-6f;
/// The least rotational inertia about its centre of mass a coupled dynamic body that turns may
/// have (unit: kg m^2): Box2D divides by it as by the mass. A body of `kMinBodyMass` the size of
/// Box2D's linear slop (5 mm) has 4e-12. Refused where `kMinBodyMass` is. Any thread.
inline constexpr float kMinBodyInertia = 1e-12f;

class BodyBoundary;

/// Registers the type "box2d.bodies", the coupling's boundary plugin, in `registry` so that
/// `World::load` reads snapshots of coupled worlds (see `Coupling`, "Saving"). The plugin is
/// not for levels or `Registry::create` by hand: detached, it is an empty boundary until a
/// `Coupling` takes it over. Throws `fluid::Error` if the type is registered already. Thread
/// rule: as `Registry::add`.
void registerCouplingPlugin(Registry& registry);

/// Two-way coupling of a fluid `World` with a Box2D `b2World`.
///
/// Every coupled fixture (circle, polygon, edge, chain; static, kinematic or dynamic body) is a
/// boundary of the fluid: it is sampled like the built-in shapes (`boundary.circle`,
/// `boundary.polygon`, `boundary.chain`), so it adds to the density and pressure near it and
/// particles never enter it. Bodies and fixtures created or destroyed between steps are picked
/// up at the next step. The fluid's pressure and viscous forces on each body's samples are
/// summed in sample order and applied to dynamic bodies at their centre of mass, with the torque
/// about it: buoyancy and drag come out of the fluid, not a formula.
///
/// One frame (`step`) of dt is one round per sub-step the position-based solver takes for dt
/// (`World::substepsFor(dt)`: the whole number of `World::substepLength()`s, 1/240 s at the
/// default 4 per 1/60 s, nearest to the world's carried time plus dt; the rest of the frame,
/// positive or negative, stays carried, and Box2D's time with it, so the world's time is the
/// rounds' and within half a sub-step of the frames' sum), the world stepping one sub-step at
/// a time; with the explicit solver, `frameSubsteps(4, dt)` rounds, each in its own CFL
/// sub-steps. So frames of any length, varying or not, have the rounds of 60 Hz frames and
/// their cost per simulated second. A round of h:
///   1. the `b2World` steps by h, with the fluid's forces of the previous round applied to its
///      dynamic bodies (and whatever the game applied);
///   2. the fluid world steps by h; every body sweeps rigidly from where the fluid last saw it
///      to where Box2D has just put it (centre of mass along a line, turning at a constant
///      rate), so the fluid ends the round exactly around the bodies' poses; a body seen for
///      the first time, or moved by hand (`b2Body::SetTransform`, a jump of more than two
///      sample spacings beyond its velocity), comes in along its velocity instead of sweeping
///      the fluid along the jump;
///   3. the reports (`bodies`), splashes and contact events are made from the particles and
///      the bodies' poses;
///   4. the fluid's force and torque on each dynamic body, averaged over the round and relaxed
///      (below), are applied (`b2Body::ApplyForce` at the centre of mass, `ApplyTorque`, waking
///      the body): Box2D integrates them at the next round's step 1.
/// Rounds as short as the fluid's sub-steps matter: a body answers the fluid one round late,
/// and with whole 1/60 s frames a box floating in a 0.64 m compartment bobbed and rocked
/// without end (up to 0.4 m/s and 1.3 rad/s), where with 4 rounds it rests (under 0.01 m/s);
/// with one round per frame the explicit solver let a light hull in levels/crates.json rock up
/// to 23 rad/s and throw water over the tank's wall. The fluid costs the same; Box2D steps 4
/// times a 1/60 s frame. A game that steps Box2D itself calls
/// its own `b2World::Step(dt, ...)` and then `stepFluid(world, dt)` (steps 2-4, one round):
/// bodies then answer a whole frame late, so floating boxes may rock (`step` is the remedy);
/// the forces wait in the bodies for its next `Step` (`b2World::SetAutoClearForces` must stay
/// on, its default). Events of all rounds of a frame are kept; reports are the last round's.
///
/// The force on a body is the momentum the fluid took from it: the reaction to each density
/// sweep's wall term and to each viscosity pass's wall friction, with the positions and
/// velocities the solver used, plus what the projection gave the particles it set to the
/// body's velocity (a particle in the way of a fast body). In zero gravity a body thrown into
/// a blob and the blob keep their total momentum within 0.2% (tests/box2d).
///
/// Relaxation: within a round the body moves as if it were infinitely heavy, so a light body
/// (the fluid it pushes aside weighs more than it does) pushes more fluid than it could, and
/// would get back ever larger kicks: so
///   - the hydrostatic part, the areal density of the material touched x the submerged area
///     x -gravity (Box2D's gravity x the body's gravity scale), is applied as measured;
///   - the rest joins a debt (an impulse, N s), of which a share w is paid each round,
///     w = m / (m + m_added + h c), c the drag rate the fluid reports for the body's samples
///     (N s/m), m_added = the areal density x the larger of the submerged area (a submerged
///     disc's added mass in 2D potential flow) and pi/8 x the wet chord^2 (a plate entering a
///     free surface), or 0 when the material touched has a yield stress (a paste holds the body
///     on its elastic strain, a spring the relaxation would delay and so pump: docs/box2d.md);
///     the torque likewise with the moment of inertia. Every impulse the fluid
///     took is paid, whatever w does from round to round;
///   - but never more against the body's motion than its momentum m |v|: a light body slammed
///     into water has pushed more of it than it could, and paying that would throw the body
///     back out (a crate dropped onto water bounced off); that excess is dropped.
/// Steady forces (buoyancy at rest, steady drag) are applied unchanged; a dry body gets its
/// debt at once (w = 1).
///
/// Coarse correction (`PositionBasedDef::coarseCorrection`, the `game` preset): every dynamic
/// body is an unknown of the world's coarse pressure solve (`BoundaryPlugin::rigidBodies`). After
/// each round the body takes the solve's velocity change at once (no relaxation: the solve
/// already moved the fluid with it) and is moved by its displacement (`SetTransform`), and its
/// report's force includes that impulse. The precise preset holds floating bodies stiller than
/// the game preset (the world's default), and the game preset's static and kinematic bodies'
/// reports miss the coarse solve's push: scenes with floating bodies name precise (figures:
/// docs/box2d.md, "Which preset").
///
/// Submerged area: each circle and polygon fixture carries points along its outline at the
/// world's sample spacing; a point is wet when a particle centre lies within 0.75 spacing of it.
/// The longest run of wet points along the outline (gaps of up to two dry points bridged)
/// and the straight chord between its ends enclose the submerged part of the (convex) fixture,
/// plus a band one spacing deep above the chord (the top particles' centres lie below the
/// surface); a lone drop on top of a crate does not count as submerging it. Measured on
/// floating discs at 0.25, 0.5 and 0.75 of water's and yoghurt's density and a square at 0.5
/// of water's: within 5% of the area under the far-field waterline (tests/box2d).
///
/// Units: Box2D's own (m, kg, s), which are fluid's. A body's mass in Box2D is density x area
/// (kg/m^2 x m^2); use `arealDensity` to relate a body to a material. Polygon skin radius
/// (`b2_polygonRadius`, 0.01 m) is ignored: the fluid sees the core polygon.
///
/// Order among boundaries: the coupling is one boundary plugin of the world (type
/// "box2d.bodies"), added by the constructor; boundaries added after it have the final word in
/// each projection, so add containers (`boundary.box`) before creating the coupling.
/// Saving: `World::save` writes the plugin in its place among the boundaries; a registry with
/// `registerCouplingPlugin` loads it back detached, and a `Coupling` made for the loaded world
/// takes it over. The Box2D world is saved with `savePhysics` (physics_save.h) and the
/// coupling's own state with `save`; `fluid::Level::save` does all three for a level.
///
/// Limits: a body farther than 1e5 m from the origin, or whose speed exceeds 1e3 m/s, is
/// skipped for that step (it is neither a boundary nor pushed); a chain of more than 4096
/// vertices throws `fluid::Error` naming the body from `step`.
///
/// Thread rule: the stepping thread only; Box2D is not thread-safe, and the coupling reads the
/// `b2World` only in `step`/`stepFluid` (the fluid's workers never touch it). Lifetime: the
/// `b2World` must outlive the coupling, and the world its coupling (the world owns the plugin
/// the coupling talks to). Destroying the coupling first leaves that plugin in the world,
/// empty: bodies stop being boundaries. The world is passed to every step rather than kept,
/// so that a `World` (a movable value) may be moved after the coupling was made.
class Coupling {
public:
    /// Attaches `physics` to `world`: takes over the world's first detached "box2d.bodies"
    /// boundary plugin (one a loaded snapshot brought back, keeping its place among the
    /// boundaries), or adds one. Throws `fluid::Error` for a bad `def`. Stepping thread,
    /// between steps.
    Coupling(World& world, b2World& physics, const CouplingDef& def = {});
    /// Detaches: the world's plugin stops seeing bodies.
    ~Coupling();
    /// Not copyable.
    Coupling(const Coupling&) = delete;
    /// Not assignable.
    Coupling& operator=(const Coupling&) = delete;

    /// One game frame (see the class comment): per round, Box2D step, fluid step, reports,
    /// forces to bodies. The `b2World` steps once per round (its contact listeners fire each
    /// time), and `World::profile()` and `World::removedEvents()` afterwards describe the last
    /// round: read the frame's from `profile()` and `removedEvents()` here.
    /// `world` must be the world given to the constructor (it may have been moved since);
    /// `dt` as `World::step` (unit: s; range (0, 1]). Throws `fluid::Error` for another world, a
    /// bad dt or a dynamic body lighter than `kMinBodyMass` or `kMinBodyInertia` (naming its
    /// index in `GetBodyList()`; all before anything moves), and what `World::step` throws (Box2D
    /// has stepped by then; the fluid is left unchanged).
    void step(World& world, float dt);
    /// Steps 2 to 4 of `step`, for games that call `b2World::Step(dt, ...)` themselves: call
    /// it right after that. Same arguments and errors.
    void stepFluid(World& world, float dt);

    /// The settings.
    const CouplingDef& def() const;
    /// Replaces the settings (validated; throws `fluid::Error` naming the field and keeps the
    /// old ones). Takes effect at the next step.
    void setDef(const CouplingDef& def);

    /// One report per coupled body after the last step, in the `b2World`'s body order
    /// (`GetBodyList`). Valid until the next step.
    std::span<const BodyReport> bodies() const;
    /// The report of `body` after the last step; nullptr if it was not coupled then.
    const BodyReport* report(const b2Body* body) const;
    /// Splashes of the last step, in body order. Valid until the next step.
    std::span<const SplashEvent> splashes() const;
    /// Contact begin and end events of the last step, in body order (ends of bodies no longer
    /// coupled last). Valid until the next step.
    std::span<const ContactEvent> contacts() const;

    /// Asks for contact events with `body` (`particleContacts`) from the next step on, or stops
    /// them (the default: off, at no cost). `body` must be a body of `physics()` (throws
    /// `fluid::Error` naming the function otherwise; nullptr too). The setting is kept by the
    /// body's address until the body is destroyed (a later step forgets it; a game that
    /// destroys a body and makes another before the next step turns it off first, as
    /// `Level::destroyBody` does), and saved with the coupling (`save`). Stepping thread,
    /// between frames.
    void setContactEvents(const b2Body* body, bool on);
    /// True when `body` asks for contact events.
    bool contactEvents(const b2Body* body) const;
    /// The contacts of the last `step` or `stepFluid` (see `ParticleContact`), in the
    /// `b2World`'s body order: the same for any number of workers and after a save and load.
    /// Valid until the next step.
    std::span<const ParticleContact> particleContacts() const;
    /// The particles that touched the body of `particleContacts()[contact]` during the last
    /// frame, by handle, in increasing slot order. Throws `fluid::Error` naming the index and
    /// the count for `contact` >= `particleContacts().size()`.
    std::span<const ParticleHandle> contactParticles(uint32_t contact) const;

    /// Particles drains and lifetimes removed during the last `step` or `stepFluid`, over all
    /// its rounds: each removal once, rounds in order, each round's events as
    /// `World::removedEvents` orders them (which after a coupled step holds only the last
    /// round's). Valid until the next step.
    std::span<const RemovedEvent> removedEvents() const;

    /// The fluid's profile of the last `step` or `stepFluid`, over all its rounds: times,
    /// sub-steps and counters summed; compression, particle count, iterations and sound speed
    /// from the last round (`World::profile()` holds only the last round's). Valid until the
    /// next step.
    const Profile& profile() const;

    /// The Box2D world.
    b2World& physics() const;

    /// Writes the coupling's state between frames to `out`: per body (by its index in the
    /// `b2World`'s `GetBodyList()`) the wet state and material the contact events compare with,
    /// the relaxation's unpaid impulse, the force and torque applied for Box2D's next step, and
    /// the pose the fluid last saw it at; and the bodies that ask for contact events
    /// (`setContactEvents`). Bodies stand by index, so the Box2D world must be
    /// restored with its bodies in the same order (`savePhysics` and `loadPhysics` keep it).
    /// Reports and events of the last frame are not state and are not saved. Stepping thread,
    /// between frames; throws `fluid::Error` if the stream fails.
    void save(std::ostream& out) const;
    /// Reads what `save` wrote into this coupling, whose Box2D world has just been restored
    /// (before any step): replaces the state above and applies the saved forces and torques to
    /// their bodies, unless a body already holds a force or torque for the next step (a world
    /// `loadPhysics` restored from a version-2 save carries Box2D's accumulated forces, these
    /// among them; adding them again would double them). Throws `fluid::Error` ("coupling save: ...") for a truncated or malformed
    /// save, a body index beyond the Box2D world's bodies, or a value that is not finite or out
    /// of its range, naming the body and field ("coupling save: body 1 debt x = 5e+237 is not
    /// finite or out of [-1e+12, 1e+12] (unit: N s)"): unpaid impulse at most 1e12 N s (1e9 kg
    /// at 1e3 m/s), angular impulse 1e17 N m s, force 1e15 N and torque 1e20 N m (those over
    /// 1 ms), seen position 1e5 m; the coupling is unchanged then.
    /// Stepping thread, between frames.
    void load(std::istream& in);

private:
    void checkWorld(const World& world, const char* function) const;
    void checkBodies(const World& world, const char* function) const;
    // Steps the world by `given` s, which simulates `simulated` s (the position-based solver's
    // whole sub-steps), then hands the fluid's forces and corrections to the bodies.
    void fluidRound(World& world, float given, float simulated);
    void addProfile(const Profile& round);
    void applyForces(float dt);
    void applyCorrections();
    void makeReports(const World& world);
    void collectContacts(const World& world, float dt);
    void finishContacts(const World& world);
    // A frame's start (step, stepFluid): the last frame's reports, profile and contact events
    // cleared, the contact settings of destroyed bodies forgotten.
    void startFrame(const World& world);
    void forgetDestroyedContactBodies();
    void remember();

    // A body after the previous round: wet state and material for contact events, and what
    // the relaxation still owes it.
    struct Previous {
        b2Body* body = nullptr;
        bool wet = false;
        MaterialId material{};
        glm::dvec2 debt{0.0, 0.0}; // impulse measured but not applied yet (N s)
        double torqueDebt = 0.0;   // angular impulse likewise (N m s)
        glm::vec2 applied{0.0f, 0.0f}; // force handed to Box2D for its next step (N)
        float appliedTorque = 0.0f;    // torque likewise (N m)
    };

    b2World* m_physics;
    BodyBoundary* m_boundary; // owned by the world
    CouplingDef m_def;
    std::vector<BodyReport> m_reports;
    std::vector<SplashEvent> m_splashes;
    std::vector<ContactEvent> m_contacts;
    std::vector<Previous> m_previous;
    Profile m_profile;              // summed over the rounds of the last frame
    std::vector<RemovedEvent> m_removed; // the rounds' removals of the last frame, in order
    std::vector<glm::dvec2> m_debt; // per body of the step, in body order: see Previous
    std::vector<double> m_torqueDebt;
    std::vector<glm::vec2> m_applied; // per body of the step: see Previous
    std::vector<float> m_appliedTorque;
    std::vector<double> m_addedMass; // per body of the step (kg), for the relaxation
    std::vector<double> m_displaced; // fluid mass displaced (kg): submerged area x density
    // Contact events: the bodies that ask (lookup only, never iterated), and the frame's
    // rounds gathered per body in body order, then the events made from them.
    std::unordered_set<const b2Body*> m_contactBodies;
    struct ContactSum {
        b2Body* body = nullptr;
        std::vector<ParticleHandle> handles;
        std::vector<uint32_t> materials; // per handle
        glm::dvec2 impulse{0.0, 0.0}, pointSum{0.0, 0.0};
        double touches = 0.0;
        float approach = 0.0f;
    };
    std::vector<ContactSum> m_contactSums;
    std::vector<ParticleContact> m_particleContacts;
    std::vector<ParticleHandle> m_contactHandles;
    std::vector<uint32_t> m_contactBegin;
};

} // namespace fluid::box2d

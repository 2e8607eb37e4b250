// fluid — base of the built-in shape boundaries: a pose, its velocities, sampled walls.
#pragma once

#include <fluid/plugin.h>

#include <glm/vec2.hpp>

#include <array>
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

namespace fluid {

/// One straight piece of a shape's outline in its local frame: a -> b, its length and the unit
/// normal on its left (cross(b - a, x - a) > 0 is the left side). Plain data.
struct ShapeSegment {
    /// End points (unit: m).
    glm::dvec2 a{0.0, 0.0}, b{0.0, 0.0};
    /// Unit normal on the left of a -> b.
    glm::dvec2 normal{0.0, 1.0};
    /// |b - a| (unit: m).
    double length = 0.0;
};

/// Base of "boundary.polygon", "boundary.chain" and "boundary.circle": a rigid shape given in its
/// own (local) frame, placed by a pose (x, y, angle) that moves with velocities (vx, vy, omega).
///
/// Kinematic motion: at time t into a step the pose is (x + vx t, y + vy t, angle + omega t);
/// at the end of the step (`finish`) the pose parameters advance by the frame's dt, so a host
/// that sets only the velocities sees the shape move, and a host that sets the pose before every
/// step gets exactly that pose (set the velocities too, so that the walls push the fluid with
/// the right speed and particles swept over are caught on the right side). The angle is kept in
/// [-pi, pi] as it advances. The position stays inside the declared range of x and y ([-1e5,
/// 1e5] m) so that a snapshot of the world can always be loaded again: a shape reaching the edge
/// of that range stops there (x or y is clamped to it and the velocity component pointing out,
/// vx or vy, is set to 0).
///
/// Shape parameters (points, radius, flags) are checked as soon as they are set: `setParam` and
/// `setPoints` throw `fluid::Error` for a bad shape (a self-crossing polygon, a closed chain of 2
/// points, a coordinate outside [-kMaxCoordinate, kMaxCoordinate]) and keep the old value, so
/// the shape stays what it was. Checks needing several parameters run whichever
/// of them is set last; a shape with no points yet is not checked until its first step.
/// The first step after a shape or spacing change throws `fluid::Error` when the shape would need
/// more than `kMaxSamples` boundary samples at the world's spacing.
///
/// Samples are laid once in the local frame (when the shape or the spacing changes) and carried
/// to the world at every `prepare` with the velocity v + omega x r of the solid at each sample.
/// `project` follows each particle's path from where it stood (at `prevTimeInStep`, in the pose
/// of that time) to where it is (at `timeInStep`) in the shape's frame, so that fast particles
/// cannot tunnel through thin parts, and removes the velocity into the wall relative to the
/// wall's own velocity there. Where solids touch or overlap, solids project before walls and
/// walls before containers (`BoundaryPlugin::role`), each group in the order added: a tank keeps
/// what a shape pushes against its wall. Thread rule: see `BoundaryPlugin`; parameters only
/// between steps.
class KinematicShape : public BoundaryPlugin {
public:
    /// Indices of the parameters every shape declares first, in this order.
    enum : std::size_t { kX, kY, kAngle, kVx, kVy, kOmega, kFriction, kPoseParamCount };
    /// Largest |coordinate| of a point in a shape's local frame (unit: m): the same bound as the
    /// pose's x and y, so that every world coordinate of a shape stays well inside float and
    /// int range.
    static constexpr double kMaxCoordinate = 1e5;
    /// Most boundary samples one shape may lay (unit: count): a polygon with a 5 km outline at
    /// water spacing (0.01 m, 4 layers). Laying that many took 3.5 s and 240 MB at peak on the
    /// development machine (a 2.5 km outline: 1 s), once, at the first step or after the shape
    /// or spacing changed.
    static constexpr std::size_t kMaxSamples = 2'000'000;
    /// The pose, velocity and friction parameters; a shape's own parameters follow them.
    static constexpr std::array<ParamDecl, kPoseParamCount> kPoseParams{{
        {"x", "m", 0.0, -1e5, 1e5, "Position x of the shape's local origin."},
        {"y", "m", 0.0, -1e5, 1e5, "Position y of the shape's local origin."},
        {"angle", "rad", 0.0, -1e4, 1e4,
         "Rotation of the shape about its origin (counter-clockwise)."},
        {"vx", "m/s", 0.0, -1e3, 1e3, "Velocity x of the origin (the pose advances by it)."},
        {"vy", "m/s", 0.0, -1e3, 1e3, "Velocity y of the origin (the pose advances by it)."},
        {"omega", "rad/s", 0.0, -1e3, 1e3,
         "Angular velocity (counter-clockwise; the angle advances by it)."},
        {"friction", "1", 1.0, 0.0, 10.0,
         "Wall viscosity scale: 0 free slip, 1 the fluid's own viscosity, 10 sticky."},
    }};

    /// The rigid motion at one instant: where the local origin is, how the frame is turned, and
    /// how fast both change. Plain data; any thread.
    struct Pose {
        /// World position of the local origin (unit: m).
        glm::dvec2 origin{0.0, 0.0};
        /// cos and sin of the angle (unit: 1).
        double cosA = 1.0, sinA = 0.0;
        /// Linear velocity of the origin (unit: m/s).
        glm::dvec2 velocity{0.0, 0.0};
        /// Angular velocity (unit: rad/s; counter-clockwise positive).
        double omega = 0.0;
        /// Local point -> world point (unit: m).
        glm::dvec2 toWorld(glm::dvec2 local) const {
            return origin +
                   glm::dvec2(cosA * local.x - sinA * local.y, sinA * local.x + cosA * local.y);
        }
        /// World point -> local point (unit: m).
        glm::dvec2 toLocal(glm::dvec2 world) const {
            const glm::dvec2 d = world - origin;
            return {cosA * d.x + sinA * d.y, -sinA * d.x + cosA * d.y};
        }
        /// Local direction -> world direction (rotation only).
        glm::dvec2 rotate(glm::dvec2 local) const {
            return {cosA * local.x - sinA * local.y, sinA * local.x + cosA * local.y};
        }
        /// Velocity of the solid at the world point `world`: v + omega x r (unit: m/s).
        glm::dvec2 velocityAt(glm::dvec2 world) const {
            const glm::dvec2 r = world - origin;
            return velocity + glm::dvec2(-omega * r.y, omega * r.x);
        }
    };

    /// The pose `t` seconds into the current step (unit: s; 0 = the pose parameters now):
    /// (x + vx t, y + vy t, angle + omega t).
    Pose pose(double t = 0.0) const;
    /// Sets x, y (unit: m) and angle (unit: rad); validated like `setParam`.
    void setPose(glm::vec2 position, float angle);
    /// Sets vx, vy (unit: m/s) and omega (unit: rad/s); validated like `setParam`.
    void setVelocity(glm::vec2 velocity, float omega);

    /// Lays the local samples if the shape or spacing changed (throws `fluid::Error` for a bad
    /// shape), then places them in the world with their velocities.
    void prepare(const StepContext& context) final;
    /// Keeps particles [begin, end) out of the solid (see the class comment). Needs a `prepare`
    /// first (it builds the geometry).
    void project(const ProjectContext& context, uint32_t begin, uint32_t end) final;
    /// What `project` works out once per call: the poses at the path's two ends and the
    /// tolerances. Plain data; any thread.
    struct Sweep {
        /// Pose at `ProjectContext::prevTimeInStep` and at `timeInStep`.
        Pose before, now;
        /// Lattice spacing (unit: m) and how far outside a surface a particle is put (unit: m).
        double spacing = 0.0, eps = 0.0;
        /// Local bounds enlarged by `reach` and `eps` (unit: m): paths missing them are skipped.
        glm::dvec2 lo{0.0, 0.0}, hi{0.0, 0.0};
    };
    /// The sweep of one `project` call. Valid after `prepare` built the geometry (`built()`).
    Sweep sweep(const ProjectContext& context) const;
    /// What `project` does to particle `i`, with the sweep of this call: for owners that
    /// keep several shapes and pick, per particle, the ones near it (the Box2D coupling).
    /// Writes only slot `i`; any worker thread.
    void projectParticle(const Sweep& sweep, const ProjectContext& context, uint32_t i) const;
    /// Puts particle `i` on the nearest surface point if it stands inside the shape at the
    /// sweep's end pose (its path ignored); returns true if it moved. For owners of overlapping
    /// shapes that must end outside all of them (a body's fixtures). Writes only slot `i`; any
    /// worker thread.
    bool pushOutParticle(const Sweep& sweep, const ProjectContext& context, uint32_t i) const;
    /// True once `prepare` built the geometry for the current shape and spacing.
    bool built() const { return m_built; }
    /// Axis-aligned bounds of the shape in its local frame (unit: m), as last built.
    glm::dvec2 localMin() const { return m_bounds.lo; }
    /// See `localMin`.
    glm::dvec2 localMax() const { return m_bounds.hi; }
    /// Advances the pose by its velocities over the frame, x and y clamped to their declared
    /// range (a shape stops at its edge: see the class comment). Stepping thread.
    void finish(const StepContext& context) override;
    /// The `friction` parameter.
    float friction() const override { return static_cast<float>(value(kFriction)); }
    /// True when `point` (unit: m) lies inside the shape at its pose now (`insideLocal`).
    bool contains(glm::vec2 point) const final;

    /// The samples in the local frame, as last laid (unit: m). Empty before the first `prepare`.
    std::span<const glm::dvec2> localSamples() const { return m_local; }

    /// Asks the world for contact events with this shape (`fluid::bodyContacts`, plugin = this
    /// plugin's index, body 0) from the next step on, or stops them (the default: off, at no
    /// cost). Saved with the world's snapshots. Stepping thread, between steps.
    void setContactEvents(bool on);
    /// True when the shape asks for contact events.
    bool contactEvents() const { return m_contacts; }
    /// With contact events on: the whole shape as one rigid body of mass 0 (the host moves it),
    /// asking for them; otherwise none.
    std::span<const RigidBody> rigidBodies() const override;
    /// Writes the contact-events flag when it is on (nothing otherwise, so that the snapshots
    /// of shapes without it stay as they were).
    void saveState(StateWriter& out) const override;
    /// Reads what `saveState` wrote (an empty state: off); throws `fluid::Error` for a flag
    /// other than 0 or 1.
    void restoreState(StateReader& in) override;

protected:
    /// `params` must start with `kPoseParams` (see `withPoseParams`).
    KinematicShape(std::string_view type, std::span<const ParamDecl> params);

    /// Axis-aligned bounds of the shape in its local frame (unit: m).
    struct LocalBounds {
        glm::dvec2 lo{0.0, 0.0}, hi{0.0, 0.0};
    };
    /// Where `collide` puts a particle: a point on the admissible side (local frame, unit: m)
    /// and the wall normal there pointing into that side (unit vector).
    struct Contact {
        glm::dvec2 point{0.0, 0.0};
        glm::dvec2 normal{0.0, 1.0};
    };

    /// Checks the shape's parameters and rebuilds its geometry caches and local samples (at
    /// `spacing` m, covering `support` m behind the surface) into `out`, and its local bounds.
    /// Throws `fluid::Error` for a bad shape (also one with no points yet) and, before laying
    /// anything, for one needing more than `kMaxSamples` samples (see `checkSampleCount`).
    /// Stepping thread.
    virtual void build(double spacing, double support, std::vector<glm::dvec2>& out,
                       LocalBounds& bounds) = 0;
    /// Checks the shape's own parameters as they are now (throws `fluid::Error` with the same
    /// message `build` would); called whenever one changes, so that `setParam` and `setPoints`
    /// fail at once. A shape whose points are not set yet passes. Default: nothing to check.
    virtual void validate() const {}
    /// Throws `fluid::Error` when a point of the point parameter at `index` has a coordinate
    /// outside [-kMaxCoordinate, kMaxCoordinate], naming the plugin, parameter, point and value.
    void checkCoordinates(std::size_t index) const;
    /// Throws `fluid::Error` when `estimate` samples (unit: count; computed in double, before any
    /// integer cast) exceed `kMaxSamples`. `what` names the size that needs them, e.g.
    /// "radius 10000 m"; `spacing` is the sample spacing (unit: m).
    void checkSampleCount(double estimate, std::string_view what, double spacing) const;
    /// Sample layers that cover `support` behind the surface at `spacing` (unit: count, >= 1;
    /// a double, so that an absurd ratio reaches `checkSampleCount` instead of an int cast).
    static double layerCount(double spacing, double support);
    /// The particle moved from `prev` to `cur` (local frame, unit: m). Returns false when it
    /// stays where it is; else fills `out`. `spacing` is the fluid's lattice spacing (unit: m),
    /// `eps` how far outside a surface a particle is put (unit: m). Called from worker threads:
    /// reads only what `build` made.
    virtual bool collide(glm::dvec2 prev, glm::dvec2 cur, double spacing, double eps,
                         Contact& out) const = 0;
    /// True when `local` (the shape's frame, unit: m) lies inside the solid, from the shape's
    /// parameters as they are now (before any `build`). Default: false (a wall has no inside).
    virtual bool insideLocal(glm::dvec2 /*local*/) const { return false; }
    /// How far from the surface `collide` may act (unit: m): the bounds are enlarged by it.
    virtual double reach(double /*spacing*/) const { return 0.0; }
    /// Marks the local samples and geometry stale when a shape parameter changed, and checks
    /// the shape (`validate`), which throws to refuse it (the old value then stays).
    void onParamChanged(std::size_t index) override;

private:
    // Puts particle `i` at `contact` (local frame of the sweep's end pose) and takes away its
    // velocity into the wall, relative to the wall's own velocity there.
    void place(const Sweep& sweep, const ProjectContext& context, uint32_t i,
               const Contact& contact) const;

    std::vector<glm::dvec2> m_local;
    bool m_contacts = false;
    RigidBody m_body; // the shape as a body, for contact events
    LocalBounds m_bounds;
    bool m_built = false;
    float m_builtSpacing = 0.0f;
    float m_builtSupport = 0.0f;
};

/// `KinematicShape::kPoseParams` followed by a shape's own parameters, for its `kParams`.
template <std::size_t N>
constexpr std::array<ParamDecl, KinematicShape::kPoseParamCount + N>
withPoseParams(const std::array<ParamDecl, N>& own) {
    std::array<ParamDecl, KinematicShape::kPoseParamCount + N> out{};
    for (std::size_t i = 0; i < KinematicShape::kPoseParamCount; ++i) {
        out[i] = KinematicShape::kPoseParams[i];
    }
    for (std::size_t i = 0; i < N; ++i) {
        out[KinematicShape::kPoseParamCount + i] = own[i];
    }
    return out;
}

} // namespace fluid

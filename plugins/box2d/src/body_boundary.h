// fluid::box2d — the boundary plugin that turns Box2D fixtures into fluid boundaries (internal).
#pragma once

#include <fluid/box2d/coupling.h>
#include <fluid/plugin.h>
#include <fluid/plugins/kinematic_shape.h>

#include <glm/common.hpp>
#include <glm/ext/vector_int2_sized.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

class b2Body;
class b2Fixture;
class b2World;

namespace fluid::box2d {

/// Signed area of the closed polygon `points` (unit: m^2; positive when counter-clockwise). Any
/// thread.
double shoelace(std::span<const glm::dvec2> points);

/// The cell (x, y) of side `cell` (unit: m, positive) that holds the body-frame point `p`
/// (unit: m): the cells a fixture's probes are sorted and looked up by. Inline: the wet test
/// asks it for every particle near a fixture. Any thread.
inline glm::i64vec2 probeCellOf(glm::dvec2 p, double cell) {
    return {static_cast<int64_t>(std::floor(p.x / cell)),
            static_cast<int64_t>(std::floor(p.y / cell))};
}

/// The sort key of probe cell `c` (FixtureEntry::probeCells). Any thread.
inline int64_t cellKey(glm::i64vec2 c) {
    return c.x * (int64_t(1) << 32) + c.y;
}

/// Axis-aligned box in world coordinates (unit: m).
struct Box {
    float loX = 0.0f, loY = 0.0f, hiX = 0.0f, hiY = 0.0f;
    /// True when the two boxes share a point.
    bool overlaps(const Box& o) const {
        return loX <= o.hiX && o.loX <= hiX && loY <= o.hiY && o.loY <= hiY;
    }
};

/// A uniform grid of boxes: which boxes meet each cell (CSR lists in box order). A particle
/// whose path stays within two cells in x and in y tests only those cells' lists, merged in box
/// order; a longer path tests every box (rare: cells are much larger than a particle's move per
/// sub-step).
class BoxGrid {
public:
    /// Rebuilds the grid over `boxes` with cells about `cellSize` m wide (larger if the boxes
    /// span more than 256 cells in x or y).
    void build(std::span<const Box> boxes, float cellSize);
    /// Calls `visit(index)` for every box that may meet `query`, in box order, each once.
    template <class F> void forEach(const Box& query, std::span<const Box> boxes, F&& visit) const {
        if (m_cellsX == 0 || !query.overlaps(m_bounds)) {
            return;
        }
        const int x0 = cellX(query.loX), x1 = cellX(query.hiX);
        const int y0 = cellY(query.loY), y1 = cellY(query.hiY);
        if (x0 == x1 && y0 == y1) {
            const uint32_t cell = uint32_t(y0) * m_cellsX + uint32_t(x0);
            for (uint32_t k = m_start[cell]; k < m_start[cell + 1]; ++k) {
                const uint32_t index = m_entries[k];
                if (boxes[index].overlaps(query)) {
                    visit(index);
                }
            }
            return;
        }
        if (x1 - x0 <= 1 && y1 - y0 <= 1) {
            // Up to four cells: their lists merged, a box in several of them visited once.
            uint32_t at[4], end[4];
            int lists = 0;
            for (int y = y0; y <= y1; ++y) {
                for (int x = x0; x <= x1; ++x) {
                    const uint32_t cell = uint32_t(y) * m_cellsX + uint32_t(x);
                    at[lists] = m_start[cell];
                    end[lists] = m_start[cell + 1];
                    ++lists;
                }
            }
            for (;;) {
                uint32_t index = UINT32_MAX;
                for (int l = 0; l < lists; ++l) {
                    if (at[l] < end[l]) {
                        index = std::min(index, m_entries[at[l]]);
                    }
                }
                if (index == UINT32_MAX) {
                    return;
                }
                for (int l = 0; l < lists; ++l) {
                    if (at[l] < end[l] && m_entries[at[l]] == index) {
                        ++at[l];
                    }
                }
                if (boxes[index].overlaps(query)) {
                    visit(index);
                }
            }
        }
        for (uint32_t index = 0; index < boxes.size(); ++index) {
            if (boxes[index].overlaps(query)) {
                visit(index);
            }
        }
    }

private:
    // Inline: every particle asks them once or twice a sub-step.
    int cellX(float x) const {
        const float c = std::floor((x - m_bounds.loX) * m_invCell);
        return static_cast<int>(std::clamp(c, 0.0f, float(m_cellsX - 1)));
    }
    int cellY(float y) const {
        const float c = std::floor((y - m_bounds.loY) * m_invCell);
        return static_cast<int>(std::clamp(c, 0.0f, float(m_cellsY - 1)));
    }

    Box m_bounds;
    float m_invCell = 1.0f;
    uint32_t m_cellsX = 0, m_cellsY = 0;
    std::vector<uint32_t> m_start, m_entries;
};

/// One coupled fixture as the fluid sees it, cached between steps (its samples are laid once).
struct FixtureEntry {
    /// The Box2D fixture (compared by address and geometry: a new fixture at a freed address
    /// with another shape is rebuilt).
    b2Fixture* fixture = nullptr;
    /// The fixture's geometry in its body's centre-of-mass frame, as numbers: kind, sizes,
    /// vertices. A change rebuilds the entry.
    std::vector<float> signature;
    /// The sampled shape (polygon, circle or chain) the world never sees directly.
    std::unique_ptr<KinematicShape> shape;
    /// Centre of a circle in the body's centre-of-mass frame (unit: m; 0 for other shapes,
    /// which are laid out in that frame).
    glm::dvec2 offset{0.0, 0.0};
    /// Vertices of a polygon, edge or chain in the centre-of-mass frame (unit: m; empty for a
    /// circle) and a circle's radius (unit: m; 0 for the others).
    std::vector<glm::dvec2> outline;
    double radius = 0.0;
    /// Points along the outline in the centre-of-mass frame, in order, at most the sample
    /// spacing apart, a polygon's vertices among them (unit: m).
    std::vector<glm::dvec2> probes;
    /// True when the outline is a loop (circle, polygon, closed chain).
    bool closed = false;
    /// Area enclosed (unit: m^2; 0 for edges and chains) and the area of the probe polygon
    /// (to scale a run's area for the circle's discretisation).
    double area = 0.0, probeArea = 0.0;
    /// Probes sorted by cell of side `probeCell` (cell key, probe index), for wet tests.
    std::vector<std::pair<int64_t, uint32_t>> probeCells;
    /// The same cells as a table over the probes' box of cells, column by column: the probes
    /// of cell (x, y) are probeCells[probeStart[c]] to probeCells[probeStart[c + 1]], c =
    /// (x - probeX0) probeRows + (y - probeY0); a column's cells are contiguous. Empty when
    /// the box has too many cells for its probes (a long chain), which then search probeCells.
    std::vector<uint32_t> probeStart;
    int64_t probeX0 = 0, probeY0 = 0, probeColumns = 0, probeRows = 0;
    /// Spacing and cell size the probes were laid for (unit: m).
    double probeSpacing = 0.0, probeCell = 0.0;
    /// Seen at the last `prepare` (entries not seen are dropped).
    bool seen = false;
};

/// A coupled body at the last `prepare`.
struct BodyEntry {
    /// The body.
    b2Body* body = nullptr;
    /// Box2D body type (b2BodyType).
    int type = 0;
    /// Centre of mass at the start of the fluid's step (unit: m) and the velocity it sweeps at
    /// (unit: m/s): from where the previous step left it to where Box2D has put it.
    glm::dvec2 com{0.0, 0.0}, velocity{0.0, 0.0};
    /// Angle at the start (unit: rad, in [-pi, pi]) and the angular velocity of the sweep
    /// (unit: rad/s).
    double angle = 0.0, omega = 0.0;
    /// The fluid's force (unit: N) and torque about `com` (unit: N m), averaged over the step.
    glm::dvec2 force{0.0, 0.0};
    double torque = 0.0;
    /// How fast the viscous force grows with the body's speed through the fluid (unit: N s/m),
    /// and the viscous torque with its angular velocity (unit: N m s): sums over its samples.
    double drag = 0.0, angularDrag = 0.0;
    /// The body's colliders: [colliderBegin, colliderEnd) in `BodyBoundary::colliders`.
    uint32_t colliderBegin = 0, colliderEnd = 0;
    /// What the coarse pressure solve did to it over the step (see `RigidBodyImpulse`): zero
    /// without the coarse correction, and for bodies that are not dynamic.
    RigidBodyImpulse coarse;
};

/// A coupled fixture in this step: its cache entry, samples and swept box.
struct Collider {
    /// Index in the fixture cache.
    uint32_t entry = 0;
    /// Index in `BodyBoundary::bodies`.
    uint32_t body = 0;
    /// Its samples: [sampleBegin, sampleEnd) of the plugin's samples.
    uint32_t sampleBegin = 0, sampleEnd = 0;
};

/// "box2d.bodies": the boundary plugin of a `Coupling`. `registerCouplingPlugin` registers it
/// so that snapshots of coupled worlds load; made by the registry it is detached (an empty
/// boundary) until a `Coupling` attaches the game's `b2World`. Thread rule: see
/// `BoundaryPlugin`; `attach` and the accessors on the stepping thread between steps.
class BodyBoundary final : public BoundaryPlugin {
public:
    /// Type string.
    static constexpr std::string_view kType = "box2d.bodies";
    /// Detached: no samples until `attach`.
    BodyBoundary();
    ~BodyBoundary() override;

    /// Reads `physics` from the next step on (nullptr detaches); `def` must outlive the plugin's
    /// use (the coupling owns it and detaches before it goes).
    void attach(b2World* physics, const CouplingDef* def);
    /// True when attached.
    bool attached() const { return m_physics != nullptr; }

    void prepare(const StepContext& context) override;
    void project(const ProjectContext& context, uint32_t begin, uint32_t end) override;
    bool wantsForces() const override { return m_physics != nullptr; }
    void receiveForces(std::span<const float> fx, std::span<const float> fy,
                       std::span<const float> drag) override;
    float friction() const override;
    /// The dynamic bodies with their mass; the others with mass 0 (moved by Box2D only). One
    /// per `bodies()` entry, in that order.
    std::span<const RigidBody> rigidBodies() const override { return m_rigid; }
    /// Keeps each body's correction in `BodyEntry::coarse`, and moves its seen pose with it
    /// (the `Coupling` moves the body there).
    void receiveBodyImpulses(std::span<const RigidBodyImpulse> impulses) override;
    /// `b2Fixture::TestPoint` on the body's coupled circles and polygons, the point carried
    /// from the sweep pose at `timeInStep` to the body's pose now. Stepping thread only (it
    /// keeps the last pose it turned).
    bool bodyContains(uint32_t body, glm::vec2 point, float timeInStep) const override;
    /// True when `point` lies in a coupled fixture of a body (`b2Fixture::TestPoint`).
    bool contains(glm::vec2 point) const override;
    /// Attached and not inside the coupling's own step: "fluid::box2d::Coupling::step" (a bare
    /// `World::step` would leave the Box2D bodies frozen); otherwise nullptr.
    const char* steppedBy() const override;
    /// Marks the coupling's own `World::step` calls (set while one runs; stepping thread).
    void setHostStepping(bool stepping) { m_hostStepping = stepping; }
    /// The bodies that ask for contact events (`RigidBody::contacts`); owned by the coupling,
    /// nullptr for none. Stepping thread, between steps.
    void setContactBodies(const std::unordered_set<const b2Body*>* bodies) {
        m_contactBodies = bodies;
    }

    /// The coupled bodies of the last `prepare`, in body-list order.
    std::span<const BodyEntry> bodies() const { return m_bodies; }
    /// The coupled fixtures of the last `prepare`, body by body.
    std::span<const Collider> colliders() const { return m_colliders; }
    /// The fixture cache entry `index`.
    const FixtureEntry& entry(uint32_t index) const { return m_entries[index]; }
    /// Sample spacing of the last `prepare` (unit: m; 0 before).
    double spacing() const { return m_spacing; }
    /// Frame time of the last `prepare` (unit: s): the bodies stood at com + velocity x
    /// frameDt, angle + omega x frameDt at the end of the fluid's step.
    double frameDt() const { return m_frameDt; }
    /// The mass of each material of the world, by index (unit: kg): what a particle weighs
    /// when a projection changes its velocity. Set before each step.
    void setMaterialMasses(std::vector<double> masses) { m_masses = std::move(masses); }

    /// Where the fluid's last step left a body (centre of mass, unit: m; angle, unit: rad).
    struct SeenPose {
        const b2Body* body = nullptr;
        glm::dvec2 com{0.0, 0.0};
        double angle = 0.0;
    };
    /// Every body's pose at the end of the last step, in the `b2World`'s body order (saves).
    std::vector<SeenPose> seenPoses() const;
    /// Replaces them (a restored save); bodies not listed come in as if new.
    void setSeenPoses(std::span<const SeenPose> poses);

private:
    bool couples(const b2Fixture& fixture) const;
    uint32_t findOrBuild(b2Fixture& fixture, const glm::dvec2& localCenter, uint32_t bodyIndex,
                         uint32_t fixtureIndex);

    b2World* m_physics = nullptr;
    bool m_hostStepping = false; // inside the coupling's own World::step
    const CouplingDef* m_def = nullptr;
    const std::unordered_set<const b2Body*>* m_contactBodies = nullptr;
    std::vector<FixtureEntry> m_entries;
    std::unordered_map<const b2Fixture*, uint32_t> m_index; // lookup only, never iterated
    std::vector<BodyEntry> m_bodies;
    std::vector<RigidBody> m_rigid; // per body of m_bodies
    std::vector<Collider> m_colliders;
    std::vector<Box> m_boxes; // per collider: where it sweeps during the step
    BoxGrid m_grid;
    double m_spacing = 0.0;
    double m_frameDt = 0.0;
    // Where each body stood at the end of the fluid's last step (centre of mass, angle):
    // lookup only, never iterated.
    struct LastPose {
        glm::dvec2 com{0.0, 0.0};
        double angle = 0.0;
    };
    std::unordered_map<const b2Body*, LastPose> m_lastPose, m_nextPose;
    // A particle's velocity change by one collider's projection, during the step: the body
    // takes the opposite impulse (see receiveForces). Collected from the worker threads in
    // any order, summed in (call, particle, collider) order.
    struct Kick {
        float timeInStep = 0.0f;
        uint32_t second = 0; // 1 for a position-based sub-step's second call
        uint32_t particle = 0;
        uint32_t collider = 0;
        uint16_t material = 0;
        float dvx = 0.0f, dvy = 0.0f; // unit: m/s
        float x = 0.0f, y = 0.0f;     // where the particle was put (unit: m)
    };
    std::vector<Kick> m_kicks;
    std::mutex m_kickMutex;
    std::vector<double> m_masses;
    // bodyContains's last sweep pose, so that the coarse fill's lattice of points over one body
    // (a few hundred calls at one time) turns the body once: the same sums as computing it each
    // call. Kept with the inputs it was computed from (which alone decide it), compared
    // exactly. The plugin interface calls bodyContains from the stepping thread only.
    struct SweepPose {
        double t = -1.0; // no pose yet: no sweep time is negative
        glm::dvec2 com{0.0, 0.0}, velocity{0.0, 0.0};
        double angle = 0.0, omega = 0.0;
        glm::dvec2 at{0.0, 0.0}; // centre of mass at t
        double c = 1.0, s = 0.0; // cos and sin of the angle at t
        uint32_t body = UINT32_MAX;
        float px = 0.0f, py = 0.0f, qs = 0.0f, qc = 1.0f; // its transform in Box2D now
    };
    mutable SweepPose m_sweepPose;
    // With the pose: each of that body's colliders' box in Box2D's frame now (its shape's
    // AABB, the polygon's skin included, grown by a rounding margin), which a point must lie in
    // before the collider's own inside test is asked (a paddle wheel's lattice point lies in at
    // most one or two of its seven fixtures' boxes).
    mutable std::vector<Box> m_sweepBoxes;
};

} // namespace fluid::box2d

// fluid — built-in force plugin: explosion (a one-shot radial impulse).
#pragma once

#include <fluid/plugin.h>

#include <array>

namespace fluid {

/// "force.explosion": a one-shot radial kick. The host sets `trigger` to 1 (between steps);
/// the next `World::step` changes each particle's velocity once, in its first sub-step, by
///
///     dv = J (1 - q^2)^2 r_vec / max(r, c),   q = r / R < 1,   0 at and beyond R,
///
/// J = `impulse` (the speed change next to the centre; negative implodes), R = `radius`,
/// c = half the lattice spacing (`StepContext::sampleSpacing / 2`), applied as the acceleration
/// dv / dt over that sub-step; the plugin then sets `trigger` back to 0 itself (in `finish`).
/// The kick is radial and depends on r only, so a blob symmetric about the centre keeps zero
/// net momentum; the profile eases to 0 with zero slope at R. Within c of the centre it fades
/// linearly to 0: the centre has no direction, and a particle a rounding error off it (the
/// middle particle of a spawned blob) must not get the full kick in an arbitrary direction,
/// which would give the blob a net momentum of m J.
/// The world's speed cap still applies (about 15 m/s for water at 4 position-based sub-steps
/// per 60 Hz frame; `Profile::speedClamped` counts the particles it slowed).
/// Note for the explicit solver with a derived sound speed: it measures the external field in
/// one sub-step per step (the last, or the short probe that opens a world's first step with
/// particles), and its sound speed never decreases. A kick in a one-sub-step step, or in the
/// first step (J / dt over the probe's tiny dt), ratchets the sound speed up for good: fire
/// from the second step on.
/// Thread rule: see `ForcePlugin`; `trigger` is read in `prepare`, so set it between steps.
class ExplosionForce final : public ForcePlugin {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "force.explosion";
    /// Parameter indices.
    enum : std::size_t { kX, kY, kRadius, kImpulse, kTrigger };
    /// Parameters: centre, reach, speed change at the centre, trigger.
    static constexpr std::array<ParamDecl, 5> kParams{{
        {"x", "m", 0.0, -1e5, 1e5, "Centre x."},
        {"y", "m", 0.0, -1e5, 1e5, "Centre y."},
        {"radius", "m", 0.5, 1e-3, 1e4, "Reach: no effect at or beyond this distance."},
        {"impulse", "m/s", 3.0, -1e3, 1e3,
         "Outward speed change next to the centre, easing to 0 at the radius; negative implodes."},
        {"trigger", "1", 0.0, 0.0, 1.0,
         "Set to 1 to fire once at the next step; the plugin resets it to 0."},
    }};
    /// An unarmed 3 m/s explosion of radius 0.5 m at the origin.
    ExplosionForce() : ForcePlugin(kType, kParams) {}
    /// An explosion at `centre` (unit: m) of `radius` (unit: m; [1e-3, 1e4]) and `impulse`
    /// (unit: m/s; [-1e3, 1e3]), not triggered.
    ExplosionForce(glm::vec2 centre, float radius, float impulse);
    /// Sets `trigger` to 1: fires at the next step. Between steps, stepping thread.
    void fire() { setParam("trigger", 1.0); }
    /// Arms the kick for this step's first sub-step when `trigger` is set (stepping thread).
    void prepare(const StepContext& context) override;
    /// Adds dv / dt to particles [begin, end) during the first sub-step of an armed step.
    void apply(const ForceContext& context, uint32_t begin, uint32_t end) override;
    /// Disarms and resets `trigger` to 0 after an armed step (stepping thread).
    void finish(const StepContext& context) override;
    /// Writes the armed flag, the step start time and the core distance.
    void saveState(StateWriter& out) const override;
    /// Reads what `saveState` wrote; throws `fluid::Error` for a bad flag or a short state.
    void restoreState(StateReader& in) override;
    /// True between `prepare` and `finish` of a step that fires.
    bool armed() const { return m_armed; }

private:
    // Set by prepare when trigger was 1, cleared by finish: the kick belongs to one step.
    bool m_armed = false;
    // Simulated time at the start of the armed step (unit: s): apply fires only in the sub-step
    // starting then, i.e. the first.
    double m_stepStart = 0.0;
    // c: within this distance of the centre the kick fades linearly to 0 (unit: m; half the
    // lattice spacing of the step).
    double m_core = 0.0;
};

} // namespace fluid

// fluid — the Herschel-Bulkley stress update of one particle (Material::yieldStress etc.).
//
// The deviatoric stress s of a yielding material is a 2D symmetric traceless tensor, stored as
// a = s_xx = -s_yy and b = s_xy; its von Mises norm |s| = sqrt(a^2 + b^2) is the shear stress
// of simple shear. Over a time dt with deviatoric strain rate D' = (dxx, dxy) and spin w =
// (dvx/dy - dvy/dx) / 2 the update is an elastic trial step with the Jaumann (co-rotational)
// rate, then a return to the Herschel-Bulkley flow surface:
//   trial     s* = s + dt (2 G D' + W s - s W)   (the spin's turn made exactly)
//   |s*| <= tau_y:  s = s*                                  (below yield: an elastic solid)
//   else            |s| = |s*| - G dt g = tau_y + K g^n      (g: the plastic shear rate)
// so under a steady shear rate g the stress settles at tau_y + K g^n, the Herschel-Bulkley law,
// and a material left alone keeps a stress of at most tau_y: it holds its shape. No stress
// above G times an elastic strain of kCarriedStrain (pbf_tuning.h) is stored: the return starts
// at tau_y or there, whichever is less, and returns at most to there. The return is
// implicit in g, so it is stable for any K and n; only G's elastic wave limits the step (the
// solver caps G). Scalar code, compiled into every instruction set's pair passes with the same
// operations in the same order, so every set gives the same bits. As simd/pair_view.h asks of
// what those passes include: no standard header, and functions of internal linkage only
// (compiler builtins for the maths), so no copy built for a wider instruction set can be
// linked in place of another.
#pragma once

#include "pbf_tuning.h"

namespace fluid::detail {

/// One material's Herschel-Bulkley constants as a step uses them.
struct YieldLaw {
    bool yielding = false;   // false: a Newtonian material, stress kept at 0
    float yieldStress = 0;   // tau_y (Pa): the material's, for how rigid a particle is
    float consistency = 0;   // K (Pa s^n)
    float flowIndex = 1;     // n
    float shearModulus = 0;  // G this step (Pa): the material's, capped by the solver
    float carriedStress = 0; // G kCarriedStrain (Pa): the most stress the step stores
    float flowStress = 0;    // where the return starts (Pa): tau_y, at most carriedStress
    float explicitModulus = 0; // the shear constraint: the stiffest G its sweeps read
                               // explicitly (Pa); 0 for the stress pass
};

/// The lesser of a and b, as fminf gives it wherever b is not NaN (a NaN a gives b), without
/// the library call fminf is on x86 (its NaN rule has no instruction).
static inline float lesser(float a, float b) {
    return a < b ? a : b;
}

/// The law of a material with yield stress `tauY` (Pa), consistency `k` (Pa s^n), flow index `n`
/// and shear modulus `g` (Pa, as the solver caps it): the stress the step carries follows.
static inline YieldLaw makeYieldLaw(bool yielding, float tauY, float k, float n, float g) {
    YieldLaw law;
    law.yielding = yielding;
    law.yieldStress = tauY;
    law.consistency = k;
    law.flowIndex = n;
    law.shearModulus = g;
    law.carriedStress = tuning::kCarriedStrain * g;
    law.flowStress = __builtin_fminf(tauY, law.carriedStress);
    return law;
}

/// The plastic shear rate g >= 0 (1/s) with excess - gdt g = K g^n (excess = |s*| - tau_y > 0,
/// gdt = G dt > 0, K > 0), and K g^n (Pa): safeguarded Newton from excess / gdt, the rate
/// without the flow law, which bounds the root from above; f is monotone, so the bracket
/// [lo, hi] always holds the root. The elastic term usually dominates (G dt is about 5-10 Pa s
/// with the solver's cap against K n g^(n-1) of a few Pa s), so two or three steps reach 1e-3;
/// at most kPlasticSteps, each a powf (in a 16k yoghurt dam break the update with 12 steps to
/// 1e-5 took an eighth of the frame). One solve's state, so that many can be stepped side by
/// side (plasticSolves): each takes the same steps, with the same arithmetic, whichever others
/// run beside it.
struct PlasticSolve {
    float excess = 0, gdt = 0, consistency = 0, flowIndex = 1;
    float lo = 0, hi = 0, x = 0;
    float viscous = 0; // K g^n (Pa), once done (plasticPower)
};

inline constexpr int kPlasticSteps = 8;

static inline PlasticSolve plasticStart(float excess, float gdt, float consistency,
                                        float flowIndex) {
    PlasticSolve p;
    p.excess = excess;
    p.gdt = gdt;
    p.consistency = consistency;
    p.flowIndex = flowIndex;
    p.hi = excess / gdt;
    p.x = p.hi;
    return p;
}

/// One Newton step of `p`; true once it has stopped (p.x the rate).
static inline bool plasticStep(PlasticSolve& p) {
    const float x = p.x;
    const float power = __builtin_powf(x, p.flowIndex);
    const float f = p.excess - p.gdt * x - p.consistency * power;
    if (f > 0.0f) {
        p.lo = x;
    } else {
        p.hi = x;
    }
    // f' = -gdt - K n x^(n-1), written without dividing by x when it is 0.
    const float slope = x > 0.0f ? p.gdt + p.consistency * p.flowIndex * power / x : p.gdt;
    float next = x + f / slope;
    if (!(next > p.lo && next < p.hi)) {
        next = 0.5f * (p.lo + p.hi);
    }
    p.x = next;
    return __builtin_fabsf(next - x) <= 1e-3f * x;
}

/// K g^n at the rate the solve stopped at.
static inline void plasticPower(PlasticSolve& p) {
    p.viscous = p.consistency * __builtin_powf(p.x, p.flowIndex);
}

/// One started solve (plasticStart), stepped alone to its end.
static inline void plasticSolve(PlasticSolve& p) {
    for (int it = 0; it < kPlasticSteps && !plasticStep(p); ++it) {
    }
    plasticPower(p);
}

/// One trial stress's return, in three parts so that many can share the plastic solves
/// (plasticSolves): returnOpen reads the trial, the solve runs, returnClose scales.
struct StressReturn {
    float norm = 0;       // |s*| (Pa)
    float target = 0;     // the stress it returns to (Pa), before the flow law's part
    bool below = false;   // at or below the flow stress (or not finite): kept as it is
    bool plastic = false; // needs the plastic rate (rate.viscous adds to the target)
    PlasticSolve rate;
};

/// Fills r (written in place, field by field: a whole struct built aside and copied in stalled
/// on its partial stores) for the trial (a, b) (Pa) over `dt` (s) under `law`.
static inline void returnOpen(const YieldLaw& law, float dt, float a, float b, StressReturn& r) {
    r.norm = __builtin_sqrtf(a * a + b * b);
    r.target = law.flowStress;
    r.below = false;
    r.plastic = false;
    const float excess = r.norm - law.flowStress;
    if (!(excess > 0.0f)) {
        r.below = true;
        return;
    }
    const float gdt = law.shearModulus * dt;
    if (law.consistency > 0.0f && gdt > 0.0f) {
        r.plastic = true;
        r.rate = plasticStart(excess, gdt, law.consistency, law.flowIndex);
    }
}

static inline void returnClose(const YieldLaw& law, const StressReturn& r, float& a, float& b) {
    if (r.below) {
        const bool finite = __builtin_isfinite(r.norm);
        a = finite ? a : 0.0f;
        b = finite ? b : 0.0f;
        return;
    }
    float target = r.target;
    if (r.plastic) {
        target += r.rate.viscous;
        target = lesser(target, law.carriedStress);
    }
    const float scale = lesser(target / r.norm, 1.0f);
    a = __builtin_isfinite(scale) ? a * scale : 0.0f;
    b = __builtin_isfinite(scale) ? b * scale : 0.0f;
}

/// Returns a trial stress (a, b) (Pa) reached over `dt` (s) to the Herschel-Bulkley surface of
/// `law`: unchanged below law.flowStress; above it scaled to flowStress + K g^n, at most
/// law.carriedStress, with g the plastic shear rate taken implicitly (PlasticSolve). A
/// non-finite trial returns 0.
static inline void returnStress(const YieldLaw& law, float dt, float& a, float& b) {
    StressReturn r;
    returnOpen(law, dt, a, b, r);
    if (r.plastic) {
        plasticSolve(r.rate);
    }
    returnClose(law, r, a, b);
}

/// The plastic solves of `count` returns stepped side by side, step by step: the same bits as
/// each stepped alone (returnStress), but one's divisions and powf no longer wait on
/// another's. `active` holds `count` indices, scratch.
static inline void plasticSolves(StressReturn* returns, unsigned* active, unsigned count) {
    unsigned open = 0;
    for (unsigned k = 0; k < count; ++k) {
        if (returns[k].plastic) {
            active[open++] = k;
        }
    }
    for (int it = 0; it < kPlasticSteps && open > 0; ++it) {
        unsigned left = 0;
        for (unsigned j = 0; j < open; ++j) {
            if (!plasticStep(returns[active[j]].rate)) {
                active[left++] = active[j];
            }
        }
        open = left;
    }
    for (unsigned k = 0; k < count; ++k) {
        if (returns[k].plastic) {
            plasticPower(returns[k].rate);
        }
    }
}

/// Advances the stress (a, b) of one particle over `dt` (s) with deviatoric strain rate (dxx,
/// dxy) (1/s) and spin `spin` (1/s) under `law`: the trial step, then returnStress. A
/// non-finite result (from non-finite input) resets the stress to 0, so a bad velocity cannot
/// leave a NaN stress behind.
static inline void yieldStep(const YieldLaw& law, float dxx, float dxy, float spin, float dt,
                             float& a, float& b) {
    // The Jaumann terms turn (a, b) by the angle 2 spin dt; turned exactly (a Cayley rotation:
    // no trigonometry, and the norm kept), since a forward Euler turn grows the norm by
    // sqrt(1 + (2 spin dt)^2) per step and a fast-spinning shear-thickening flow blew up.
    const float u = spin * dt;
    const float inv = 1.0f / (1.0f + u * u);
    const float cosine = (1.0f - u * u) * inv, sine = 2.0f * u * inv;
    const float g2 = 2.0f * law.shearModulus;
    const float ta = (a * cosine + b * sine) + dt * g2 * dxx;
    const float tb = (b * cosine - a * sine) + dt * g2 * dxy;
    a = ta;
    b = tb;
    returnStress(law, dt, a, b);
}

} // namespace fluid::detail

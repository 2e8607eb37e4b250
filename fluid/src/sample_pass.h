// fluid — the loop every sample pass shares (sph_loops.cpp, pbf_loops.cpp): the reactions and
// pressures of boundary samples, each gathered from the particles around the sample.
//
// Each sample gathers over the particle grid's contiguous ranges around it in branch-free
// blocks of kLanes (lanes.h), one accumulator per lane and channel, and sums the lanes in
// laneSum's fixed tree: the result depends only on the (deterministic) grid order. Each sample
// writes only its own slots, so results do not depend on the number of workers either.
#pragma once

#include "lanes.h"
#include "parallel.h"
#include "world_state.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace fluid::detail {

/// Particle j as a boundary sample at (xw, yw) sees it: the offset d = x_j - x_w (unit: m),
/// 1/h_j (unit: 1/m), q = |d| / h_j, the kernel factor t = max(1 - q, 0) and h_j^-4, the
/// factors every sample pass's Wendland terms are made of.
struct WallPair {
    float dx, dy, invH, q, t, invH4;
};

/// What every sample pass reads of the particles: their positions and smoothing lengths.
struct SampleReach {
    const float* __restrict px;
    const float* __restrict py;
    const float* __restrict hs;

    explicit SampleReach(const Particles& p) : px(p.px.data()), py(p.py.data()), hs(p.h.data()) {}

    /// Particle j seen from the sample at (xw, yw).
    WallPair at(size_t j, float xw, float yw) const {
        const float dx = px[j] - xw, dy = py[j] - yw;
        const float invH = 1.0f / hs[j];
        const float q = std::sqrt(dx * dx + dy * dy) * invH;
        return {dx, dy, invH, q, std::max(1.0f - q, 0.0f), (invH * invH) * (invH * invH)};
    }
};

/// One lane's accumulators in an N-channel sample pass: a[c] is channel c's accumulator of
/// the lane the pair term runs in.
template <int N> struct SampleLane {
    float (&acc)[N][kLanes];
    int lane;
    float& operator[](int c) const { return acc[c][lane]; }
};

/// For each of `count` samples: the r-th is sample k = r, or k = indices[r] with `indices` (the
/// reporting samples). begin(k) returns the sample's pair term, term(j, a), which adds particle
/// j's share to the lane accumulators a[0..N) (it states the update itself, += or -=, so each
/// pass keeps its own arithmetic); then finish(r, k, sums) gets the N lane sums.
template <int N, class Begin, class Finish>
void samplePass(WorldState& s, uint32_t count, const uint32_t* indices, Begin&& begin,
                Finish&& finish) {
    const Samples& w = s.samples;
    parallelFor(s.tasks, count, kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t r = b; r < e; ++r) {
            const uint32_t k = indices != nullptr ? indices[r] : r;
            const auto term = begin(k);
            float acc[N][kLanes] = {};
            s.grid.forEachRange(w.px[k], w.py[k], [&](uint32_t jb, uint32_t je) {
                lanes(jb, je, [&](size_t j, int l) { term(j, SampleLane<N>{acc, l}); });
            });
            float sums[N];
            for (int c = 0; c < N; ++c) {
                sums[c] = laneSum(acc[c]);
            }
            finish(r, k, sums);
        }
    });
}

} // namespace fluid::detail

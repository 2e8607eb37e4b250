// fluid — the coarse solve's multigrid preconditioner (coarse_multigrid.h).
#include "coarse_multigrid.h"

#include <algorithm>
#include <cmath>

namespace fluid::detail {

namespace {

// The coarsest level: at most this many unknowns, solved by a dense Cholesky factor.
constexpr size_t kCoarsest = 48;
// Most levels. Each level's lattice is half as wide and high as the one before, so any lattice
// of up to 2^31 nodes a side ends in one unknown within 32 (the coarse grid has at most 2^22
// nodes): the hierarchy always ends at kCoarsest unknowns or fewer, even when the unknowns lie
// apart (spray: each alone in its 2 x 2 cell, a level that does not shrink).
constexpr size_t kMaxLevels = 33;
// The coarse correction's weight, in (0, 2). Iterations per solve to a hundredth of the
// residual, 100,000-particle dam (`fluid-bench --scene dam --particles 100000 --threads 1
// --warmup 10 --frames 30`, 160 solves of about 17,800 unknowns): 1.0 9.9, 1.4 5.5, 1.7 4.8,
// 2.0 5.0 (MIC(0): 25.1).
constexpr float kOverCorrection = 1.7f;

} // namespace

void CoarseMultigrid::build(size_t count, const uint32_t* node, uint32_t width,
                            const float* diagonal, const int32_t* nb, const float* w) {
    if (m_levels.empty()) {
        m_levels.resize(1);
    }
    Level& l0 = m_levels[0];
    l0.count = count;
    l0.unit = w == nullptr;
    l0.diagonal.assign(diagonal, diagonal + count);
    l0.nb.assign(nb, nb + 4 * count);
    if (w != nullptr) {
        l0.w.assign(w, w + 4 * count);
    } else {
        l0.w.resize(4 * count);
        for (size_t k = 0; k < 4 * count; ++k) {
            l0.w[k] = nb[k] != int32_t(count) ? 1.0f : 0.0f;
        }
    }
    l0.ci.resize(count);
    l0.cj.resize(count);
    for (size_t a = 0; a < count; ++a) {
        l0.ci[a] = node[a] % width;
        l0.cj[a] = node[a] / width;
    }
    size_t used = 1;
    while (m_levels[used - 1].count > kCoarsest && used < kMaxLevels) {
        if (m_levels.size() <= used) {
            m_levels.emplace_back();
        }
        coarsen(m_levels[used - 1], m_levels[used]);
        ++used;
    }
    m_levels.resize(used);
    for (Level& l : m_levels) {
        l.invDiagonal.resize(l.count);
        l.red.clear();
        l.black.clear();
        for (size_t a = 0; a < l.count; ++a) {
            l.invDiagonal[a] = 1.0f / l.diagonal[a];
            ((l.ci[a] + l.cj[a]) % 2 == 0 ? l.red : l.black).push_back(uint32_t(a));
        }
        l.f.assign(l.count + 1, 0.0f);
        l.e.assign(l.count + 1, 0.0f);
    }
    factorCoarsest();
}

void CoarseMultigrid::coarsen(Level& fine, Level& coarse) {
    // The coarse unknowns are the lattice's 2 x 2 cells that hold a fine one, row by row.
    uint32_t ni = 0, nj = 0;
    for (size_t a = 0; a < fine.count; ++a) {
        ni = std::max(ni, fine.ci[a] / 2 + 1);
        nj = std::max(nj, fine.cj[a] / 2 + 1);
    }
    m_map.assign(size_t(ni) * size_t(nj), -1);
    for (size_t a = 0; a < fine.count; ++a) {
        m_map[size_t(fine.cj[a] / 2) * ni + fine.ci[a] / 2] = 0;
    }
    coarse.ci.clear();
    coarse.cj.clear();
    int32_t next = 0;
    for (uint32_t cj = 0; cj < nj; ++cj) {
        for (uint32_t ci = 0; ci < ni; ++ci) {
            int32_t& m = m_map[size_t(cj) * ni + ci];
            if (m == 0) {
                m = next++;
                coarse.ci.push_back(ci);
                coarse.cj.push_back(cj);
            }
        }
    }
    const auto count = size_t(next);
    coarse.count = count;
    coarse.unit = false;
    fine.parent.resize(fine.count);
    for (size_t a = 0; a < fine.count; ++a) {
        fine.parent[a] = uint32_t(m_map[size_t(fine.cj[a] / 2) * ni + fine.ci[a] / 2]);
    }
    // P^T A P, summed in double in fine order: an aggregate's diagonal gathers its members'
    // diagonals less their faces inside it (each seen from both sides), and each face between
    // two aggregates adds to their coefficient in its direction.
    m_sumDiagonal.assign(count, 0.0);
    m_sumW.assign(4 * count, 0.0);
    coarse.nb.assign(4 * count, int32_t(count));
    const auto none = int32_t(fine.count);
    for (size_t a = 0; a < fine.count; ++a) {
        const uint32_t p = fine.parent[a];
        m_sumDiagonal[p] += double(fine.diagonal[a]);
        for (size_t k = 0; k < 4; ++k) {
            const int32_t b = fine.nb[4 * a + k];
            if (b == none) {
                continue;
            }
            const uint32_t q = fine.parent[size_t(b)];
            if (q == p) {
                m_sumDiagonal[p] -= double(fine.w[4 * a + k]);
            } else {
                m_sumW[4 * p + k] += double(fine.w[4 * a + k]);
                coarse.nb[4 * p + k] = int32_t(q);
            }
        }
    }
    coarse.diagonal.resize(count);
    coarse.w.resize(4 * count);
    for (size_t c = 0; c < count; ++c) {
        coarse.diagonal[c] = float(m_sumDiagonal[c]);
    }
    for (size_t k = 0; k < 4 * count; ++k) {
        coarse.w[k] = float(m_sumW[k]);
    }
}

void CoarseMultigrid::factorCoarsest() {
    const Level& l = m_levels.back();
    const size_t n = l.count;
    m_chol.assign(n * n, 0.0);
    for (size_t a = 0; a < n; ++a) {
        m_chol[a * n + a] = double(l.diagonal[a]);
        for (size_t k = 0; k < 4; ++k) {
            const int32_t b = l.nb[4 * a + k];
            if (b != int32_t(n)) {
                m_chol[a * n + size_t(b)] -= double(l.w[4 * a + k]);
            }
        }
    }
    // The lower factor in place, row by row.
    for (size_t c = 0; c < n; ++c) {
        double d = m_chol[c * n + c];
        for (size_t k = 0; k < c; ++k) {
            d -= m_chol[c * n + k] * m_chol[c * n + k];
        }
        // The operator is positive definite; a pivot that rounding took to 0 keeps the diagonal
        // (still a symmetric positive definite preconditioner).
        d = d > 1e-9 * double(l.diagonal[c]) ? std::sqrt(d) : std::sqrt(double(l.diagonal[c]));
        m_chol[c * n + c] = d;
        for (size_t row = c + 1; row < n; ++row) {
            double s = m_chol[row * n + c];
            for (size_t k = 0; k < c; ++k) {
                s -= m_chol[row * n + k] * m_chol[c * n + k];
            }
            m_chol[row * n + c] = s / d;
        }
    }
    m_work.assign(n, 0.0);
}

void CoarseMultigrid::solveCoarsest() {
    Level& l = m_levels.back();
    const size_t n = l.count;
    for (size_t a = 0; a < n; ++a) {
        double s = double(l.f[a]);
        for (size_t k = 0; k < a; ++k) {
            s -= m_chol[a * n + k] * m_work[k];
        }
        m_work[a] = s / m_chol[a * n + a];
    }
    for (size_t a = n; a-- > 0;) {
        double s = m_work[a];
        for (size_t k = a + 1; k < n; ++k) {
            s -= m_chol[k * n + a] * m_work[k];
        }
        m_work[a] = s / m_chol[a * n + a];
    }
    for (size_t a = 0; a < n; ++a) {
        l.e[a] = float(m_work[a]);
    }
    l.e[n] = 0.0f;
}

void CoarseMultigrid::smooth(Level& l, const std::vector<uint32_t>& colour) {
    const int32_t* nb = l.nb.data();
    const float* w = l.w.data();
    const float* f = l.f.data();
    const float* inv = l.invDiagonal.data();
    float* e = l.e.data();
    if (l.unit) {
        for (const uint32_t a : colour) {
            const size_t k = 4 * size_t(a);
            const float s = ((f[a] + e[nb[k]]) + e[nb[k + 1]]) + (e[nb[k + 2]] + e[nb[k + 3]]);
            e[a] = s * inv[a];
        }
        return;
    }
    for (const uint32_t a : colour) {
        const size_t k = 4 * size_t(a);
        const float s = ((f[a] + w[k] * e[nb[k]]) + (w[k + 1] * e[nb[k + 1]])) +
                        ((w[k + 2] * e[nb[k + 2]]) + (w[k + 3] * e[nb[k + 3]]));
        e[a] = s * inv[a];
    }
}

void CoarseMultigrid::cycle(size_t level) {
    if (level + 1 == m_levels.size()) {
        solveCoarsest();
        return;
    }
    Level& l = m_levels[level];
    Level& c = m_levels[level + 1];
    // The red sweep from zero (a red unknown's neighbours are black, still 0), then the black.
    std::fill(l.e.begin(), l.e.end(), 0.0f);
    for (const uint32_t a : l.red) {
        l.e[a] = l.f[a] * l.invDiagonal[a];
    }
    smooth(l, l.black);
    // The residual restricted (P^T): the black unknowns' is 0 after their sweep.
    std::fill(c.f.begin(), c.f.end(), 0.0f);
    const int32_t* nb = l.nb.data();
    const float* w = l.w.data();
    const float* e = l.e.data();
    for (const uint32_t a : l.red) {
        const size_t k = 4 * size_t(a);
        const float s = l.unit ? (e[nb[k]] + e[nb[k + 1]]) + (e[nb[k + 2]] + e[nb[k + 3]])
                               : ((w[k] * e[nb[k]]) + (w[k + 1] * e[nb[k + 1]])) +
                                     ((w[k + 2] * e[nb[k + 2]]) + (w[k + 3] * e[nb[k + 3]]));
        c.f[l.parent[a]] += l.f[a] - (l.diagonal[a] * e[a] - s);
    }
    cycle(level + 1);
    for (size_t a = 0; a < l.count; ++a) {
        l.e[a] += kOverCorrection * c.e[l.parent[a]];
    }
    smooth(l, l.black);
    smooth(l, l.red);
}

void CoarseMultigrid::apply(const float* r, float* z) {
    Level& l = m_levels[0];
    std::copy(r, r + l.count, l.f.begin());
    cycle(0);
    std::copy(l.e.begin(), l.e.begin() + std::ptrdiff_t(l.count), z);
}

} // namespace fluid::detail

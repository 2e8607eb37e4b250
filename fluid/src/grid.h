// fluid — uniform neighbour grid (the seed's spatial subdivision), counting-sorted.
#pragma once

#include "simd/pair_view.h"

#include <fluid/task.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace fluid::detail {

/// Cells of one support radius over the bounding box of the points, with no fixed world extent.
/// Points are counting-sorted by cell (stable, so deterministic); a query visits the 3x3 cells
/// around a position as contiguous index ranges of the sorted points. When the box is sparse
/// (far-flung points would need more than max(4096, 4N) cells) the grid hashes cells into
/// 2N buckets instead, so memory stays O(N) for any spread.
class Grid {
public:
    /// Sorts `count` points by cell. After it, `order()[k]` is the original index of the point
    /// that sorts to position k; queries return ranges of sorted positions.
    void build(std::span<const float> px, std::span<const float> py, float cellSize,
               const TaskHook& tasks);

    /// Original index of the point at sorted position k.
    std::span<const uint32_t> order() const { return m_order; }
    /// Number of points sorted (unit: count).
    uint32_t size() const { return static_cast<uint32_t>(m_order.size()); }
    /// True when the grid fell back to hashed buckets.
    bool hashed() const { return m_hashed; }
    /// The grid as plain data for the pair passes (valid until the next build).
    GridView view() const {
        GridView v;
        v.start = m_start.data();
        v.ox = m_ox;
        v.oy = m_oy;
        v.nx = m_nx;
        v.ny = m_ny;
        v.mask = m_mask;
        v.invCell = m_invCell;
        v.count = size();
        v.hashed = m_hashed;
        return v;
    }

    /// Calls `f(begin, end)` for each range of sorted positions in the cells around (x, y) that
    /// may hold points within one cell size. Ranges are visited in a fixed order.
    template <class F> void forEachRange(float x, float y, F&& f) const {
        if (m_order.empty()) {
            return;
        }
        const int64_t cx = cellCoord(x);
        const int64_t cy = cellCoord(y);
        if (!m_hashed) {
            const int64_t x0 = std::max<int64_t>(cx - 1 - m_ox, 0);
            const int64_t x1 = std::min<int64_t>(cx + 1 - m_ox, int64_t(m_nx) - 1);
            if (x0 > x1) {
                return;
            }
            for (int64_t row = cy - 1 - m_oy; row <= cy + 1 - m_oy; ++row) {
                if (row < 0 || row >= int64_t(m_ny)) {
                    continue;
                }
                const uint32_t b = m_start[size_t(row * int64_t(m_nx) + x0)];
                const uint32_t e = m_start[size_t(row * int64_t(m_nx) + x1 + 1)];
                if (b < e) {
                    f(b, e);
                }
            }
            return;
        }
        // Hashed: visit each distinct bucket of the 9 cells once, in bucket order.
        uint32_t buckets[9];
        int n = 0;
        for (int64_t dy = -1; dy <= 1; ++dy) {
            for (int64_t dx = -1; dx <= 1; ++dx) {
                buckets[n++] = hashKey(cx + dx, cy + dy);
            }
        }
        std::sort(buckets, buckets + n);
        for (int k = 0; k < n; ++k) {
            if (k > 0 && buckets[k] == buckets[k - 1]) {
                continue;
            }
            const uint32_t b = m_start[buckets[k]];
            const uint32_t e = m_start[buckets[k] + 1];
            if (b < e) {
                f(b, e);
            }
        }
    }

private:
    int64_t cellCoord(float v) const { return gridCell(v, m_invCell); }
    uint32_t hashKey(int64_t cx, int64_t cy) const { return gridHash(cx, cy, m_mask); }

    float m_invCell = 1.0f;
    bool m_hashed = false;
    int64_t m_ox = 0, m_oy = 0;
    uint32_t m_nx = 0, m_ny = 0;
    uint32_t m_mask = 0;
    std::vector<uint32_t> m_start; // cell -> first sorted position; size cells + 1
    std::vector<uint32_t> m_order;
    std::vector<uint32_t> m_keys;
    std::vector<uint32_t> m_next;
};

} // namespace fluid::detail

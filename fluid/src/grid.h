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

/// How a Grid divides space: cells across one query radius in x and in y, and the most cells
/// its dense mode may use (on top of max(4096 subX subY, 8N)).
struct GridLayout {
    int subX = 4;          // particles: cells R/4 wide ...
    int subY = 2;          // ... and R/2 high (count, 1..kGridMaxRows)
    size_t denseCells = 0; // count
};

/// A counting-sorted neighbour grid over the bounding box of the points, with no fixed world
/// extent. A query returns every point within the query radius R (the `radius` of build) as
/// contiguous index ranges of the sorted points. Cells are R/subX wide and R/subY high (the
/// GridLayout), sorted row by row, so a query is one range per row, clipped to the cells its circle
/// can reach: about 40% fewer candidates than 3x3 cells of R, in as few ranges. Points are
/// counting-sorted by cell (stable, so deterministic). When the box is sparse (more than
/// max(4096 subX subY, 8N, denseCells) cells) the grid hashes cells of R into 2N
/// buckets instead, so memory stays O(N) for any spread; a hashed query visits up to nine
/// bucket ranges and costs about a third more.
class Grid {
public:
    /// Sorts `count` points by cell for queries of `radius` (m, > 0). After it, `order()[k]` is
    /// the original index of the point that sorts to position k; queries return ranges of sorted
    /// positions.
    void build(std::span<const float> px, std::span<const float> py, float radius,
               const TaskHook& tasks, GridLayout layout = {});

    /// Original index of the point at sorted position k.
    std::span<const uint32_t> order() const { return m_order; }
    /// Number of points sorted (unit: count).
    uint32_t size() const { return static_cast<uint32_t>(m_order.size()); }
    /// True when the grid fell back to hashed buckets.
    bool hashed() const { return m_view.hashed; }
    /// The grid as plain data for the pair passes (valid until the next build).
    const GridView& view() const { return m_view; }

    /// Calls `f(begin, end)` for each range of sorted positions that may hold points within the
    /// query radius of (x, y) (gridRanges in simd/pair_view.h). Ranges are visited in a fixed
    /// order.
    template <class F> void forEachRange(float x, float y, F&& f) const {
        gridRanges(m_view, x, y, f);
    }

private:
    GridView m_view;
    std::vector<uint32_t> m_start; // cell -> first sorted position; size cells + 1
    std::vector<uint32_t> m_order;
    std::vector<uint32_t> m_keys;
    std::vector<int64_t> m_cellX, m_cellY; // per point (input order), its cell of the layout
};

} // namespace fluid::detail

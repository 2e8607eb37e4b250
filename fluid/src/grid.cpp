// fluid — uniform neighbour grid, counting sort.
#include "grid.h"

#include "parallel.h"

#include <limits>

namespace fluid::detail {

void Grid::build(std::span<const float> px, std::span<const float> py, float radius,
                 const TaskHook& tasks, GridLayout layout) {
    const auto count = static_cast<uint32_t>(px.size());
    const int sx = std::clamp(layout.subX, 1, 64), sy = std::clamp(layout.subY, 1, kGridMaxRows);
    const size_t denseCells = layout.denseCells;
    GridView& v = m_view;
    v = GridView{};
    v.invCellX = float(sx) / radius;
    v.invCellY = float(sy) / radius;
    m_order.resize(count);
    m_keys.resize(count);
    v.count = count;
    if (count == 0) {
        m_start.assign(1, 0);
        v.start = m_start.data();
        return;
    }

    struct Box {
        int64_t x0, y0, x1, y1;
    };
    const Box init{std::numeric_limits<int64_t>::max(), std::numeric_limits<int64_t>::max(),
                   std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::min()};
    // Each point's cell, kept for the keys (a hashed grid's cells are R wide: the same cells
    // when the layout divides R into one).
    m_cellX.resize(count);
    m_cellY.resize(count);
    const Box box = blockReduce<Box>(
        tasks, count, init,
        [&](uint32_t b, uint32_t e) {
            Box r = init;
            for (uint32_t i = b; i < e; ++i) {
                const int64_t cx = gridCell(px[i], v.invCellX);
                const int64_t cy = gridCell(py[i], v.invCellY);
                m_cellX[i] = cx;
                m_cellY[i] = cy;
                r.x0 = std::min(r.x0, cx);
                r.y0 = std::min(r.y0, cy);
                r.x1 = std::max(r.x1, cx);
                r.y1 = std::max(r.y1, cy);
            }
            return r;
        },
        [](Box a, Box b) {
            return Box{std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1),
                       std::max(a.y1, b.y1)};
        });

    const double nx = double(box.x1 - box.x0 + 1);
    const double ny = double(box.y1 - box.y0 + 1);
    const double denseLimit = std::max({4096.0 * sx * sy, 8.0 * double(count), double(denseCells)});
    v.hashed = nx * ny > denseLimit;
    size_t cells = 0;
    if (!v.hashed) {
        v.ox = box.x0;
        v.oy = box.y0;
        v.nx = uint32_t(nx);
        v.ny = uint32_t(ny);
        cells = size_t(v.nx) * v.ny;
        // Row k's cells lie at least max(0, |k| - 1) R/sy away in y from any point of the
        // query's row, so they can hold points within R only within R sqrt(1 - (that/R)^2) in
        // x: max(0, |dx| - 1) R/sx below that.
        v.rows = sy;
        for (int k = 0; k <= sy; ++k) {
            const double dy = double(std::max(0, k - 1)) / double(sy);
            v.span[k] = int32_t(std::ceil(double(sx) * std::sqrt(1.0 - dy * dy)));
        }
    } else {
        // Sparse: cells of R, hashed, the 3x3 around a query.
        v.invCellX = v.invCellY = 1.0f / radius;
        uint32_t table = 1024;
        while (table < 2 * count) {
            table <<= 1;
        }
        v.mask = table - 1;
        cells = table;
    }

    parallelFor(tasks, count, 4096, [&](uint32_t b, uint32_t e, uint32_t) {
        if (v.hashed && (sx != 1 || sy != 1)) {
            for (uint32_t i = b; i < e; ++i) {
                m_keys[i] =
                    gridHash(gridCell(px[i], v.invCellX), gridCell(py[i], v.invCellY), v.mask);
            }
        } else if (v.hashed) {
            for (uint32_t i = b; i < e; ++i) {
                m_keys[i] = gridHash(m_cellX[i], m_cellY[i], v.mask);
            }
        } else {
            const int64_t* __restrict cx = m_cellX.data();
            const int64_t* __restrict cy = m_cellY.data();
            uint32_t* __restrict keys = m_keys.data();
            const int64_t ox = v.ox, oy = v.oy, width = int64_t(v.nx);
            for (uint32_t i = b; i < e; ++i) {
                keys[i] = uint32_t((cy[i] - oy) * width + (cx[i] - ox));
            }
        }
    });

    // Stable counting sort: points keep their previous relative order inside a cell. Each
    // cell's entry counts its points, then holds where the cell ends (an inclusive prefix
    // sum); the points, placed from the last, move each entry back to where its cell begins.
    m_start.assign(cells + 1, 0);
    for (uint32_t i = 0; i < count; ++i) {
        ++m_start[m_keys[i]];
    }
    for (size_t c = 1; c < cells; ++c) {
        m_start[c] += m_start[c - 1];
    }
    for (uint32_t i = count; i-- > 0;) {
        m_order[--m_start[m_keys[i]]] = i;
    }
    m_start[cells] = count;
    v.start = m_start.data();
}

} // namespace fluid::detail

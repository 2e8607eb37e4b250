// fluid — uniform neighbour grid, counting sort.
#include "grid.h"

#include "parallel.h"

#include <limits>

namespace fluid::detail {

void Grid::build(std::span<const float> px, std::span<const float> py, float cellSize,
                 const TaskHook& tasks) {
    const auto count = static_cast<uint32_t>(px.size());
    m_invCell = 1.0f / cellSize;
    m_order.resize(count);
    m_keys.resize(count);
    if (count == 0) {
        m_start.assign(1, 0);
        m_nx = m_ny = 0;
        return;
    }

    struct Box {
        int64_t x0, y0, x1, y1;
    };
    const Box init{std::numeric_limits<int64_t>::max(), std::numeric_limits<int64_t>::max(),
                   std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::min()};
    const Box box = blockReduce<Box>(
        tasks, count, init,
        [&](uint32_t b, uint32_t e) {
            Box r = init;
            for (uint32_t i = b; i < e; ++i) {
                const int64_t cx = cellCoord(px[i]);
                const int64_t cy = cellCoord(py[i]);
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
    const double denseLimit = std::max(4096.0, 4.0 * double(count));
    m_hashed = nx * ny > denseLimit;
    size_t cells = 0;
    if (!m_hashed) {
        m_ox = box.x0;
        m_oy = box.y0;
        m_nx = uint32_t(nx);
        m_ny = uint32_t(ny);
        cells = size_t(m_nx) * m_ny;
    } else {
        uint32_t table = 1024;
        while (table < 2 * count) {
            table <<= 1;
        }
        m_mask = table - 1;
        cells = table;
    }

    parallelFor(tasks, count, 4096, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            const int64_t cx = cellCoord(px[i]);
            const int64_t cy = cellCoord(py[i]);
            m_keys[i] =
                m_hashed ? hashKey(cx, cy) : uint32_t((cy - m_oy) * int64_t(m_nx) + (cx - m_ox));
        }
    });

    // Stable counting sort: points keep their previous relative order inside a cell.
    m_start.assign(cells + 1, 0);
    for (uint32_t i = 0; i < count; ++i) {
        ++m_start[m_keys[i] + 1];
    }
    for (size_t c = 0; c < cells; ++c) {
        m_start[c + 1] += m_start[c];
    }
    m_next.assign(m_start.begin(), m_start.end() - 1);
    for (uint32_t i = 0; i < count; ++i) {
        m_order[m_next[m_keys[i]]++] = i;
    }
}

} // namespace fluid::detail

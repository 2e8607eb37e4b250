// fluid — region queries (query.h): the particles in a box or a shape, through a grid of their
// own built on the first query after a change.
#include <fluid/query.h>

#include "query_grid.h"

#include <fluid/error.h>
#include <fluid/internal/checks.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace fluid {

namespace detail {

WorldState& queryState(const World& world, const char* function) {
    WorldState& s = stateOf(const_cast<World&>(world));
    if (s.stepping) {
        throw Error(std::string(function) +
                        ": called during the world's own step (from a plugin's hook or a task); "
                        "query the world between its steps",
                    ErrorCode::WrongState);
    }
    return s;
}

// Cells of the largest smoothing distance: a 10 cm query box of water covers about 16.
const WorldState::QueryGrid& queryGrid(WorldState& s) {
    WorldState::QueryGrid& q = *s.queryGrid;
    const std::lock_guard<std::mutex> lock(q.mutex);
    const auto count = uint32_t(s.particles.size());
    if (q.builtAt != s.changes || q.count != count) {
        float cell = 0.0f;
        for (const Material& m : s.materials) {
            cell = std::max(cell, m.smoothingDistance);
        }
        q.cell = cell > 0.0f ? cell : 1.0f;
        q.grid.build(s.particles.px, s.particles.py, q.cell, TaskHook{}, GridLayout{1, 1, 0});
        const auto [x0, x1] = std::minmax_element(s.particles.px.begin(), s.particles.px.end());
        const auto [y0, y1] = std::minmax_element(s.particles.py.begin(), s.particles.py.end());
        const bool any = count > 0;
        q.minX = any ? *x0 : 0.0f;
        q.maxX = any ? *x1 : 0.0f;
        q.minY = any ? *y0 : 0.0f;
        q.maxY = any ? *y1 : 0.0f;
        q.builtAt = s.changes;
        q.count = count;
    }
    return q;
}

} // namespace detail

namespace {

// The array indices of the particles `inside` accepts among those whose cells meet the box
// [lo, hi], in increasing order.
template <class Inside>
std::vector<uint32_t> candidates(detail::WorldState& s, glm::vec2 lo, glm::vec2 hi,
                                 Inside&& inside) {
    const detail::Particles& p = s.particles;
    std::vector<uint32_t> found;
    const auto count = uint32_t(p.size());
    if (count == 0) {
        return found;
    }
    const detail::Grid& grid = detail::queryGrid(s).grid;
    const detail::GridView& g = grid.view();
    const std::span<const uint32_t> order = grid.order();
    const int64_t cx0 = detail::gridCell(lo.x, g.invCellX),
                  cx1 = detail::gridCell(hi.x, g.invCellX);
    const int64_t cy0 = detail::gridCell(lo.y, g.invCellY),
                  cy1 = detail::gridCell(hi.y, g.invCellY);
    const double cells = double(cx1 - cx0 + 1) * double(cy1 - cy0 + 1);
    const auto take = [&](uint32_t b, uint32_t e) {
        for (uint32_t k = b; k < e; ++k) {
            const uint32_t i = order[k];
            if (inside(glm::vec2(p.px[i], p.py[i]))) {
                found.push_back(i);
            }
        }
    };
    if (cells >= double(count)) {
        // A region over more cells than there are particles: a scan is cheaper.
        for (uint32_t i = 0; i < count; ++i) {
            if (inside(glm::vec2(p.px[i], p.py[i]))) {
                found.push_back(i);
            }
        }
        return found;
    }
    if (!g.hashed) {
        // Rows of the dense grid: each row's cells are contiguous in sorted order.
        const int64_t x0 = std::max(cx0, g.ox), x1 = std::min(cx1, g.ox + int64_t(g.nx) - 1);
        const int64_t y0 = std::max(cy0, g.oy), y1 = std::min(cy1, g.oy + int64_t(g.ny) - 1);
        for (int64_t y = y0; y <= y1 && x0 <= x1; ++y) {
            const int64_t row = (y - g.oy) * int64_t(g.nx);
            take(g.start[row + (x0 - g.ox)], g.start[row + (x1 - g.ox) + 1]);
        }
    } else {
        // Buckets of the hashed grid, each once (cells that share one are taken together).
        std::vector<uint32_t> buckets;
        for (int64_t y = cy0; y <= cy1; ++y) {
            for (int64_t x = cx0; x <= cx1; ++x) {
                buckets.push_back(detail::gridHash(x, y, g.mask));
            }
        }
        std::sort(buckets.begin(), buckets.end());
        buckets.erase(std::unique(buckets.begin(), buckets.end()), buckets.end());
        for (const uint32_t b : buckets) {
            take(g.start[b], g.start[b + 1]);
        }
    }
    std::sort(found.begin(), found.end());
    return found;
}

std::vector<uint32_t> inShape(detail::WorldState& s, const Shape& region, const char* function) {
    validate(region, function);
    glm::vec2 lo{0.0f, 0.0f}, hi{0.0f, 0.0f};
    bounds(region, lo, hi);
    return candidates(s, lo, hi, [&](glm::vec2 x) { return contains(region, x); });
}

uint32_t visitAll(const detail::WorldState& s, const std::vector<uint32_t>& found,
                  const QueryVisitor& visit) {
    uint32_t visited = 0;
    for (const uint32_t i : found) {
        ++visited;
        const QueryHit hit{s.handleOf(s.particles.slot[i]), i,
                           MaterialId{s.particles.material[i], s.tag.value()}};
        if (!visit(hit)) {
            break;
        }
    }
    return visited;
}

} // namespace

uint32_t queryParticles(const World& world, const Shape& region, const QueryVisitor& visit) {
    detail::WorldState& s = detail::queryState(world, "queryParticles");
    if (!visit) {
        throw Error("queryParticles: the visitor is empty", ErrorCode::BadArgument);
    }
    return visitAll(s, inShape(s, region, "queryParticles"), visit);
}

uint32_t queryParticles(const World& world, const Shape& region, std::span<ParticleHandle> out) {
    detail::WorldState& s = detail::queryState(world, "queryParticles");
    const std::vector<uint32_t> found = inShape(s, region, "queryParticles");
    for (std::size_t k = 0; k < found.size() && k < out.size(); ++k) {
        out[k] = s.handleOf(s.particles.slot[found[k]]);
    }
    return uint32_t(found.size());
}

uint32_t countParticles(const World& world, const Shape& region, std::span<uint32_t> perMaterial) {
    detail::WorldState& s = detail::queryState(world, "countParticles");
    const std::vector<uint32_t> found = inShape(s, region, "countParticles");
    std::fill(perMaterial.begin(), perMaterial.end(), 0u);
    for (const uint32_t i : found) {
        const uint16_t m = s.particles.material[i];
        if (m < perMaterial.size()) {
            ++perMaterial[m];
        }
    }
    return uint32_t(found.size());
}

uint32_t queryBox(const World& world, glm::vec2 lo, glm::vec2 hi, const QueryVisitor& visit) {
    detail::WorldState& s = detail::queryState(world, "queryBox");
    if (!visit) {
        throw Error("queryBox: the visitor is empty", ErrorCode::BadArgument);
    }
    if (!internal::finite(lo) || !internal::finite(hi) || !(lo.x <= hi.x) || !(lo.y <= hi.y)) {
        std::ostringstream text;
        text << "queryBox: the box [" << lo.x << ", " << hi.x << "] x [" << lo.y << ", " << hi.y
             << "] is not finite or inverted; expected finite lo <= hi on both axes (unit: m)";
        throw Error(text.str(), ErrorCode::BadArgument);
    }
    const std::vector<uint32_t> found = candidates(s, lo, hi, [&](glm::vec2 x) {
        return x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y;
    });
    return visitAll(s, found, visit);
}

} // namespace fluid

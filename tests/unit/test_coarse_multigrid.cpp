// The coarse solve's multigrid preconditioner (fluid/src/coarse_multigrid.h): a symmetric
// positive definite operator, so conjugate gradients may use it; exact on a grid small enough
// for its coarsest level; few iterations on a tank-shaped grid with a free surface and with
// the bodies' face weights; the same bits on every build of the same operator.
#include "coarse_multigrid.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace coarse_multigrid_test {

using fluid::detail::CoarseMultigrid;

// A 5-point operator on the fluid nodes of an nx x ny lattice, the way the coarse solve makes
// it (pbf_coarse.cpp, buildOperator): the nodes in row order, the faces to other fluid nodes
// weighted (w), a face to air adding its surface coefficient to the diagonal, walls adding
// nothing, a small shift on every diagonal.
struct Operator {
    size_t count = 0;
    uint32_t width = 0;                  // nodes per lattice row
    std::vector<uint32_t> i, j, node;    // per unknown: column, row, node (j width + i)
    std::vector<float> diagonal, w;
    std::vector<int32_t> nb;
    bool weighted = false;

    // q = A x.
    std::vector<double> apply(const std::vector<float>& x) const {
        std::vector<double> q(count, 0.0);
        for (size_t a = 0; a < count; ++a) {
            double s = double(diagonal[a]) * double(x[a]);
            for (size_t k = 0; k < 4; ++k) {
                const int32_t b = nb[4 * a + k];
                if (b != int32_t(count)) {
                    s -= double(w[4 * a + k]) * double(x[size_t(b)]);
                }
            }
            q[a] = s;
        }
        return q;
    }
};

// `fluid(x, y)`: the node is an unknown; `air(x, y)`: a non-fluid node beyond a free surface
// (the others, and those outside the lattice, are walls); `weight(a, b)`: a symmetric face
// coefficient in (0, 1], or null for 1.
template <class Fluid, class Air, class Weight>
Operator makeOperator(int nx, int ny, Fluid&& fluid, Air&& air, Weight&& weight) {
    Operator op;
    op.width = uint32_t(nx);
    std::vector<int32_t> slot(size_t(nx) * size_t(ny), -1);
    for (int y = 0; y < ny; ++y) {
        for (int x = 0; x < nx; ++x) {
            if (fluid(x, y)) {
                slot[size_t(y) * size_t(nx) + size_t(x)] = int32_t(op.count++);
                op.i.push_back(uint32_t(x));
                op.j.push_back(uint32_t(y));
                op.node.push_back(uint32_t(y * nx + x));
            }
        }
    }
    op.diagonal.assign(op.count, 1e-3f);
    op.nb.assign(4 * op.count, int32_t(op.count));
    op.w.assign(4 * op.count, 0.0f);
    const int di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
    for (size_t a = 0; a < op.count; ++a) {
        for (size_t k = 0; k < 4; ++k) {
            const int x = int(op.i[a]) + di[k], y = int(op.j[a]) + dj[k];
            if (x < 0 || y < 0 || x >= nx || y >= ny) {
                continue; // a wall
            }
            const int32_t b = slot[size_t(y) * size_t(nx) + size_t(x)];
            if (b >= 0) {
                const float c = weight(int(op.i[a]), int(op.j[a]), x, y);
                op.diagonal[a] += c;
                op.w[4 * a + k] = c;
                op.nb[4 * a + k] = b;
            } else if (air(x, y)) {
                op.diagonal[a] += 2.5f; // a surface 0.4 of a cell beyond the node
            }
        }
    }
    return op;
}

// The tank: fluid below row `level` of an nx x ny lattice, walls left, right and below, air
// above; a column of fluid above it at the left (a dam's).
Operator tankOperator(int nx, int ny, int level, bool weighted) {
    const auto fluid = [=](int x, int y) { return y < level || (x < nx / 4 && y < ny - 1); };
    const auto air = [=](int x, int y) { return !fluid(x, y); };
    const auto weight = [=](int x0, int y0, int x1, int y1) {
        if (!weighted) {
            return 1.0f;
        }
        // Symmetric in the two nodes: a function of the face's midpoint.
        const double mx = 0.5 * (x0 + x1), my = 0.5 * (y0 + y1);
        return float(0.55 + 0.45 * std::sin(0.7 * mx + 1.3 * my));
    };
    Operator op = makeOperator(nx, ny, fluid, air, weight);
    op.weighted = weighted;
    return op;
}

std::vector<float> randomVector(size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<float> v(count);
    for (float& x : v) {
        x = u(rng);
    }
    return v;
}

double dotProduct(const std::vector<float>& a, const std::vector<float>& b) {
    double s = 0.0;
    for (size_t k = 0; k < a.size(); ++k) {
        s += double(a[k]) * double(b[k]);
    }
    return s;
}

void build(CoarseMultigrid& mg, const Operator& op) {
    mg.build(op.count, op.node.data(), op.width, op.diagonal.data(), op.nb.data(),
             op.weighted ? op.w.data() : nullptr);
}

std::vector<float> applyB(CoarseMultigrid& mg, const std::vector<float>& r) {
    std::vector<float> z(r.size());
    mg.apply(r.data(), z.data());
    return z;
}

// Preconditioned conjugate gradients in double for A x = b from 0: iterations until the
// residual is `tolerance` of the start's (at most 200).
int pcgIterations(const Operator& op, CoarseMultigrid* mg, const std::vector<float>& b,
                  double tolerance) {
    const size_t n = op.count;
    std::vector<double> x(n, 0.0), r(b.begin(), b.end());
    const auto precondition = [&](const std::vector<double>& res) {
        std::vector<float> rf(res.begin(), res.end());
        std::vector<float> zf(n);
        if (mg != nullptr) {
            mg->apply(rf.data(), zf.data());
        } else {
            for (size_t a = 0; a < n; ++a) {
                zf[a] = rf[a] / op.diagonal[a];
            }
        }
        return std::vector<double>(zf.begin(), zf.end());
    };
    const auto norm2 = [](const std::vector<double>& v) {
        double s = 0.0;
        for (double e : v) {
            s += e * e;
        }
        return s;
    };
    const double stop = norm2(r) * tolerance * tolerance;
    std::vector<double> z = precondition(r), d = z;
    double rz = 0.0;
    for (size_t a = 0; a < n; ++a) {
        rz += r[a] * z[a];
    }
    for (int it = 1; it <= 200; ++it) {
        const std::vector<double> q = op.apply(std::vector<float>(d.begin(), d.end()));
        double dq = 0.0;
        for (size_t a = 0; a < n; ++a) {
            dq += d[a] * q[a];
        }
        const double alpha = rz / dq;
        for (size_t a = 0; a < n; ++a) {
            x[a] += alpha * d[a];
            r[a] -= alpha * q[a];
        }
        if (norm2(r) <= stop) {
            return it;
        }
        z = precondition(r);
        double next = 0.0;
        for (size_t a = 0; a < n; ++a) {
            next += r[a] * z[a];
        }
        const double beta = next / rz;
        rz = next;
        for (size_t a = 0; a < n; ++a) {
            d[a] = z[a] + beta * d[a];
        }
    }
    return 201;
}

} // namespace coarse_multigrid_test

using namespace coarse_multigrid_test;

TEST_CASE("coarse multigrid: the V-cycle is symmetric and positive definite", "[unit][coarse]") {
    for (const bool weighted : {false, true}) {
        CAPTURE(weighted);
        const Operator op = tankOperator(96, 80, 40, weighted);
        CoarseMultigrid mg;
        build(mg, op);
        CHECK(mg.levels() >= 5);
        for (uint32_t seed = 1; seed <= 6; ++seed) {
            const std::vector<float> x = randomVector(op.count, seed);
            const std::vector<float> y = randomVector(op.count, 100 + seed);
            const std::vector<float> bx = applyB(mg, x), by = applyB(mg, y);
            // y.Bx = x.By up to float rounding over the unknowns' sums.
            const double scale = std::sqrt(dotProduct(bx, bx) * dotProduct(y, y));
            CHECK(std::abs(dotProduct(y, bx) - dotProduct(x, by)) < 1e-5 * scale);
            CHECK(dotProduct(x, bx) > 0.0);
        }
    }
}

TEST_CASE("coarse multigrid: a grid of at most 48 unknowns is solved exactly", "[unit][coarse]") {
    const Operator op = tankOperator(8, 8, 4, true);
    REQUIRE(op.count <= 48);
    CoarseMultigrid mg;
    build(mg, op);
    CHECK(mg.levels() == 1);
    const std::vector<float> b = randomVector(op.count, 7);
    const std::vector<double> ab = op.apply(applyB(mg, b));
    for (size_t a = 0; a < op.count; ++a) {
        CHECK(ab[a] == Approx(b[a]).margin(1e-4));
    }
}

TEST_CASE("coarse multigrid: conjugate gradients need a few iterations where Jacobi's need "
          "many, free surface and face weights included",
          "[unit][coarse]") {
    for (const bool weighted : {false, true}) {
        for (const int size : {64, 160}) {
            CAPTURE(weighted, size);
            const Operator op = tankOperator(size, size, size / 2, weighted);
            CoarseMultigrid mg;
            build(mg, op);
            const std::vector<float> b = randomVector(op.count, 11);
            // The coarse solve's stop: a hundredth of the start's residual.
            const int cycle = pcgIterations(op, &mg, b, 1e-2);
            const int jacobi = pcgIterations(op, nullptr, b, 1e-2);
            const int tight = pcgIterations(op, &mg, b, 1e-5);
            std::printf("[measure] coarse multigrid, %d x %d lattice, %zu unknowns%s: %d "
                        "iterations to 1e-2 (Jacobi %d), %d to 1e-5\n",
                        size, size, op.count, weighted ? ", weighted faces" : "", cycle, jacobi,
                        tight);
            CHECK(cycle <= 8);
            CHECK(jacobi >= 3 * cycle);
            CHECK(tight <= 16);
        }
    }
}

TEST_CASE("coarse multigrid: the same operator gives the same bits, rebuilt after another",
          "[unit][coarse]") {
    const Operator big = tankOperator(120, 90, 45, true), small = tankOperator(40, 30, 15, false);
    const std::vector<float> r = randomVector(big.count, 3);
    CoarseMultigrid mg;
    build(mg, big);
    const std::vector<float> first = applyB(mg, r);
    build(mg, small);
    (void)applyB(mg, randomVector(small.count, 4));
    build(mg, big);
    const std::vector<float> again = applyB(mg, r);
    CoarseMultigrid fresh;
    build(fresh, big);
    const std::vector<float> other = applyB(fresh, r);
    CHECK(first == again);
    CHECK(first == other);
}

TEST_CASE("coarse multigrid: unknowns apart from each other (spray) still coarsen to a small "
          "exact level",
          "[unit][coarse]") {
    // Every other node of every other row is fluid: no two unknowns touch or share a 2 x 2
    // cell, so the first coarsening does not shrink; the ones after it do.
    const auto fluid = [](int x, int y) { return x % 2 == 0 && y % 2 == 0; };
    const auto air = [](int, int) { return true; };
    const auto weight = [](int, int, int, int) { return 1.0f; };
    const Operator op = makeOperator(200, 200, fluid, air, weight);
    REQUIRE(op.count == 10000);
    CoarseMultigrid mg;
    build(mg, op);
    CHECK(mg.levels() <= 12);
    // Each unknown is alone: A is diagonal, and conjugate gradients end in a few iterations.
    const std::vector<float> b = randomVector(op.count, 5);
    CHECK(pcgIterations(op, &mg, b, 1e-5) <= 16);
    const std::vector<float> z = applyB(mg, b);
    CHECK(dotProduct(b, z) > 0.0);
}

// fluid — the positions-only compression measure shared by fluid-bench and the tests, so that
// the figures of bench/README.md and the thresholds of tests/invariants/test_presets.cpp mean
// the same thing (bench/README.md, "Compression").
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

namespace fluid::bench {

/// The q-quantile (q in [0, 1]) of `v`, nearest rank, in linear time; reorders `v` (not empty).
inline double nearestRank(std::vector<double>& v, double q) {
    const auto rank = size_t(std::ceil(q * double(v.size())));
    const size_t k = std::min(v.size() - 1, rank > 0 ? rank - 1 : 0);
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
    return v[k];
}

/// Support radius of the bench's own density sum (unit: m): water's smoothing distance.
constexpr double kCompressionSupport = 0.032;

/// Wendland C2 (2D) kernel without its normalisation (unit: 1; 1 at r = 0, 0 from r = h on):
/// (1 - q)^4 (1 + 4 q), q = r / h. The normalisation cancels in `CompressionMeter`'s ratio.
inline double wendland(double r) {
    const double q = r / kCompressionSupport;
    if (q >= 1.0) {
        return 0.0;
    }
    const double a = 1.0 - q;
    return a * a * a * a * (1.0 + 4.0 * q);
}

/// Compression of one frame over its particles (unit: 1, fractions: 0.01 is 1%).
struct Compression {
    /// Mean over particles.
    double mean = 0.0;
    /// 99th percentile over particles (nearest rank).
    double p99 = 0.0;
    /// Largest over particles.
    double max = 0.0;
};

/// The bench's own compression measure, from particle positions alone (no wall samples, so
/// particles at walls and at the free surface read under-dense, i.e. 0): rho_i = sum_j W(r_ij)
/// over every particle j within h = `kCompressionSupport` of i, itself included, divided by the
/// same sum over an infinite square lattice of spacing s; compression_i = max(rho_i / lattice
/// - 1, 0). Neighbours come from a hashed uniform grid of cells h wide (counting sort), so a
/// measurement is O(N) however far particles fly.
class CompressionMeter {
public:
    /// A meter for particles on a lattice of `spacing` (unit: m; > 0).
    explicit CompressionMeter(double spacing) {
        // Every lattice point (a s, b s) closer than h has |a|, |b| <= ceil(h / s).
        const auto reach = int(std::ceil(kCompressionSupport / spacing));
        for (int a = -reach; a <= reach; ++a) {
            for (int b = -reach; b <= reach; ++b) {
                const double r = spacing * std::sqrt(double(a * a + b * b));
                if (r < kCompressionSupport) {
                    m_lattice += wendland(r);
                }
            }
        }
    }

    /// Measures the particles at `x`, `y` (unit: m; same length).
    Compression measure(std::span<const float> x, std::span<const float> y) {
        const size_t n = x.size();
        if (n == 0) {
            return {};
        }
        const float minX = *std::min_element(x.begin(), x.end());
        const float minY = *std::min_element(y.begin(), y.end());
        // Hash table of a power of two >= 2 n buckets; a bucket may hold several cells, so a
        // walk keeps only the particles of the cell it asked for.
        const size_t buckets = std::bit_ceil(std::max<size_t>(16, 2 * n));
        const auto cellOf = [&](float v, float lo) {
            return int64_t(std::floor((double(v) - double(lo)) / kCompressionSupport));
        };
        const auto bucketOf = [&](int64_t cx, int64_t cy) {
            const uint64_t key = (uint64_t(cx) * 0x9E3779B97F4A7C15ull) ^ uint64_t(cy);
            return size_t((key * 0xBF58476D1CE4E5B9ull) >> 32) & (buckets - 1);
        };
        m_cellX.resize(n);
        m_cellY.resize(n);
        m_bucket.resize(n);
        m_start.assign(buckets + 1, 0);
        for (size_t i = 0; i < n; ++i) {
            m_cellX[i] = cellOf(x[i], minX);
            m_cellY[i] = cellOf(y[i], minY);
            m_bucket[i] = bucketOf(m_cellX[i], m_cellY[i]);
            ++m_start[m_bucket[i] + 1];
        }
        std::partial_sum(m_start.begin(), m_start.end(), m_start.begin());
        // Counting sort: particle data in bucket order.
        m_sx.resize(n);
        m_sy.resize(n);
        m_scx.resize(n);
        m_scy.resize(n);
        m_fill.assign(m_start.begin(), m_start.end() - 1);
        for (size_t i = 0; i < n; ++i) {
            const size_t k = m_fill[m_bucket[i]]++;
            m_sx[k] = x[i];
            m_sy[k] = y[i];
            m_scx[k] = m_cellX[i];
            m_scy[k] = m_cellY[i];
        }
        const double h2 = kCompressionSupport * kCompressionSupport;
        m_value.resize(n);
        double sum = 0.0, largest = 0.0;
        for (size_t i = 0; i < n; ++i) {
            double rho = 0.0;
            for (int64_t cy = m_scy[i] - 1; cy <= m_scy[i] + 1; ++cy) {
                for (int64_t cx = m_scx[i] - 1; cx <= m_scx[i] + 1; ++cx) {
                    const size_t b = bucketOf(cx, cy);
                    for (size_t j = m_start[b]; j < m_start[b + 1]; ++j) {
                        if (m_scx[j] != cx || m_scy[j] != cy) {
                            continue;
                        }
                        const double dx = double(m_sx[j]) - double(m_sx[i]);
                        const double dy = double(m_sy[j]) - double(m_sy[i]);
                        const double r2 = dx * dx + dy * dy;
                        if (r2 < h2) {
                            rho += wendland(std::sqrt(r2));
                        }
                    }
                }
            }
            const double c = std::max(rho / m_lattice - 1.0, 0.0);
            m_value[i] = c;
            sum += c;
            largest = std::max(largest, c);
        }
        Compression result;
        result.mean = sum / double(n);
        result.max = largest;
        result.p99 = nearestRank(m_value, 0.99);
        return result;
    }

private:
    /// The kernel sum over the infinite lattice (unit: 1).
    double m_lattice = 0.0;
    /// Per particle, in input order: grid cell (unit: cells of h from the lowest particle) and
    /// hash bucket (unit: index).
    std::vector<int64_t> m_cellX, m_cellY;
    /// See `m_cellX`.
    std::vector<size_t> m_bucket;
    /// First sorted slot of each bucket, and one past the last (unit: index).
    std::vector<size_t> m_start;
    /// Next free sorted slot per bucket during the sort (unit: index).
    std::vector<size_t> m_fill;
    /// Positions (unit: m) and cells in bucket order.
    std::vector<float> m_sx, m_sy;
    /// See `m_sx`.
    std::vector<int64_t> m_scx, m_scy;
    /// Compression per particle in bucket order (unit: 1).
    std::vector<double> m_value;
};

/// The tank's water level (unit: m): the 95th percentile (nearest rank) of particle y plus half
/// a spacing `s` (a particle stands for an s x s cell). `scratch` is reused.
inline double surfaceLevel(std::span<const float> y, double s, std::vector<double>& scratch) {
    scratch.assign(y.begin(), y.end());
    return scratch.empty() ? 0.0 : nearestRank(scratch, 0.95) + 0.5 * s;
}

/// Indices of the particles at exactly the position of another (unit: indices into x and y,
/// ascending; a stack of k particles gives k of them). The pair terms have no direction
/// between particles on one point, so a stack that outlives a sub-step is a solver fault.
inline std::vector<uint32_t> stackedIndices(std::span<const float> x, std::span<const float> y) {
    std::vector<uint32_t> order(x.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(),
              [&](uint32_t a, uint32_t b) { return x[a] < x[b] || (x[a] == x[b] && y[a] < y[b]); });
    std::vector<uint32_t> out;
    for (size_t i = 0; i < order.size();) {
        size_t j = i + 1;
        while (j < order.size() && x[order[j]] == x[order[i]] && y[order[j]] == y[order[i]]) {
            ++j;
        }
        if (j - i > 1) {
            out.insert(out.end(), order.begin() + std::ptrdiff_t(i),
                       order.begin() + std::ptrdiff_t(j));
        }
        i = j;
    }
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace fluid::bench

// fluid — a multigrid preconditioner for the coarse correction's potential solve (pbf_coarse.cpp).
//
// The unknowns are fluid nodes of a lattice with a 5-point symmetric operator: per unknown a
// diagonal and up to four neighbours (left, right, below, above), each face with a coefficient.
// Each level aggregates the 2 x 2 nodes of a cell of the lattice into one unknown (P: the
// piecewise-constant prolongation), and each coarser operator is the Galerkin product P^T A P,
// which keeps the 5-point shape, the symmetry and the positive definiteness exactly, whatever
// the free surface's and the bodies' coefficients. The preconditioner is one V-cycle from zero:
// red-black Gauss-Seidel (red then black before the coarse correction, black then red after
// it), the coarse correction over-weighted by kOverCorrection (a piecewise-constant
// prolongation under-corrects smooth errors), the coarsest level solved exactly (dense
// Cholesky). With the weight below 2 every level's correction contracts the error in A's norm,
// so the cycle is symmetric positive definite and conjugate gradients may use it [McAdams,
// Sifakis and Teran 2010 precondition the same solve by a multigrid V-cycle]. Every loop runs
// serially in a fixed order: the result depends on nothing but the operator and the input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fluid::detail {

/// The V-cycle preconditioner of a 5-point lattice operator (see the file comment). Built and
/// applied on one thread at a time (the coarse solve's).
class CoarseMultigrid {
public:
    /// Builds the levels from the finest operator: `count` unknowns, per unknown a its node
    /// node[a] on a lattice of rows `width` nodes long (column node % width, row node / width;
    /// two unknowns never share one), its diagonal (> 0), its four neighbours nb[4a..4a+3]
    /// (left, right, below, above, each at lattice distance 1; `count` for none) and their
    /// faces' coefficients w[4a..4a+3] (>= 0, symmetric: a's face to b is b's to a; null: every
    /// face 1). The operator must be symmetric positive definite.
    void build(size_t count, const uint32_t* node, uint32_t width, const float* diagonal,
               const int32_t* nb, const float* w);
    /// z = B r, B one V-cycle from zero for A z = r over the unknowns of the last build (r and
    /// z hold `count` values; they may not overlap).
    void apply(const float* r, float* z);
    /// Levels of the last build, the finest included (0 before the first).
    size_t levels() const { return m_levels.size(); }

private:
    struct Level {
        size_t count = 0;
        bool unit = false; // every face's coefficient is 1 (the finest level without bodies)
        std::vector<float> diagonal, invDiagonal;
        std::vector<int32_t> nb;          // 4 per unknown; `count` for none
        std::vector<float> w;             // 4 per unknown (0 for none)
        std::vector<uint32_t> red, black; // the unknowns by the parity of i + j, in order
        std::vector<uint32_t> ci, cj;     // lattice coordinates
        std::vector<uint32_t> parent;     // this level's unknown -> the next level's
        std::vector<float> f, e;          // right-hand side and solution (count + 1: e keeps
                                          // slot `count` at 0 for the missing neighbours)
    };
    void smooth(Level& l, const std::vector<uint32_t>& colour);
    void cycle(size_t level);
    void coarsen(Level& fine, Level& coarse);
    void factorCoarsest();
    void solveCoarsest();

    std::vector<Level> m_levels;
    std::vector<double> m_chol; // the coarsest operator's Cholesky factor, row-major (lower)
    std::vector<double> m_work; // the coarsest solve's vector
    std::vector<int32_t> m_map; // lattice cell -> coarse unknown, while coarsening
    std::vector<double> m_sumDiagonal, m_sumW; // the Galerkin sums, while coarsening
};

} // namespace fluid::detail

// fluid — the branch-free lane loop the neighbour passes share, with the kernels' constants
// (kernel_constants.h; kernels.h has the reference formulas and their derivations).
#pragma once

#include "kernel_constants.h"

#include <cstddef>
#include <cstdint>

namespace fluid::detail {

inline constexpr int kLanes = 8;
inline constexpr uint32_t kPairGrain = 256; // smallest particle range per worker task
using kernel::kC;
using kernel::kG;
using kernel::kL;
using kernel::kW;

/// Sum of the lane accumulators as a fixed tree (lanes l and l + 4, then l and l + 2, then the
/// last two): the same result every run, without a chain of dependent adds.
template <class T> T laneSum(const T (&acc)[kLanes]) {
    static_assert(kLanes == 8);
    const T a = acc[0] + acc[4], b = acc[1] + acc[5], c = acc[2] + acc[6], d = acc[3] + acc[7];
    return (a + c) + (b + d);
}

/// Runs body(j, lane) over [b, e) in blocks of kLanes (the tail uses the first lanes). The index
/// is a size_t: with a 32-bit index g++ cannot prove that j + l are consecutive addresses (the
/// sum could wrap) and assembles every vector from scalar loads.
template <class Body> inline void lanes(uint32_t b, uint32_t e, Body&& body) {
    size_t j = b;
    for (; j + kLanes <= e; j += kLanes) {
        for (int l = 0; l < kLanes; ++l) {
            body(j + size_t(l), l);
        }
    }
    for (int l = 0; j < e; ++j, ++l) {
        body(j, l);
    }
}

} // namespace fluid::detail

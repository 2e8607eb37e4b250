// fluid — the position-based pair passes for avx2 (see pbf_pairs.inc; flags in
// fluid/CMakeLists.txt).
#define FLUID_SIMD_AVX2
#define FLUID_PAIRS_NS kPbfPairsAvx2
#define FLUID_PAIRS_NAME "avx2"
#include "pbf_pairs.inc"

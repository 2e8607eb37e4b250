// fluid — the position-based pair passes for avx512 (see pbf_pairs.inc; flags in
// fluid/CMakeLists.txt).
#define FLUID_SIMD_AVX512
#define FLUID_PAIRS_NS kPbfPairsAvx512
#define FLUID_PAIRS_NAME "avx512"
#include "pbf_pairs.inc"

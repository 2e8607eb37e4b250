// fluid — the position-based pair passes for sse2 (see pbf_pairs.inc; flags in
// fluid/CMakeLists.txt).

#define FLUID_PAIRS_NS kPbfPairsSse2
#define FLUID_PAIRS_NAME "sse2"
#include "pbf_pairs.inc"

// fluid — picks the pair passes for the instruction set this machine runs.
#include "pair_view.h"

#include <fluid/world.h>

#include <cstdlib>
#include <cstring>

namespace fluid::detail {
namespace {

bool runs(const char* name) {
#if defined(FLUID_HAVE_X86_PAIRS)
    if (std::strcmp(name, "avx512") == 0) {
        return __builtin_cpu_supports("avx512f") != 0;
    }
    if (std::strcmp(name, "avx2") == 0) {
        return __builtin_cpu_supports("avx2") != 0;
    }
#endif
    return std::strcmp(name, "sse2") == 0;
}

const PbfPairs& choose() {
#if defined(FLUID_HAVE_X86_PAIRS)
    const PbfPairs* all[] = {&kPbfPairsAvx512, &kPbfPairsAvx2, &kPbfPairsSse2};
#else
    const PbfPairs* all[] = {&kPbfPairsSse2};
#endif
    // FLUID_SIMD names a narrower set to use (results are the same on every set; this is for
    // tests and for measuring). An unknown name or one the machine cannot run is ignored.
    const char* wanted = std::getenv("FLUID_SIMD");
    if (wanted != nullptr) {
        for (const PbfPairs* p : all) {
            if (std::strcmp(p->name, wanted) == 0 && runs(p->name)) {
                return *p;
            }
        }
    }
    for (const PbfPairs* p : all) {
        if (runs(p->name)) {
            return *p;
        }
    }
    return kPbfPairsSse2;
}

} // namespace

const PbfPairs& pbfPairs() {
    static const PbfPairs& chosen = choose();
    return chosen;
}

} // namespace fluid::detail

namespace fluid {

const char* instructionSet() {
    return detail::pbfPairs().name;
}

} // namespace fluid

#!/usr/bin/env bash
# Fuzz the level loader with libFuzzer (clang-14, AddressSanitizer + UndefinedBehaviorSanitizer).
#
#   bash scripts/fuzz.sh            # 60 s
#   bash scripts/fuzz.sh 600        # 10 minutes
#   bash scripts/fuzz.sh -runs=200000 [more libFuzzer flags]
#
# Builds tests/fuzz in build/fuzz (its own CMake project), seeds it with levels/*.json,
# tests/fuzz/seeds/*.json and tests/level/data/*.json, and runs fluid-fuzz-level over the corpus
# in build/fuzz/corpus (kept between runs). A crash, sanitizer report, timeout (10 s per input)
# or running out of memory (2 GB) stops the run, leaves the input in build/fuzz/artifacts/ and
# exits non-zero; reproduce it with
#   build/fuzz/fluid-fuzz-level build/fuzz/artifacts/crash-...
# Installs clang-14 and libclang-rt-14-dev when missing (as root), through scripts/deps.sh.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

limit="${1:-60}"
shift || true
if [[ "$limit" == -runs=* ]]; then
    budget=("$limit")
elif [[ "$limit" =~ ^[0-9]+$ ]]; then
    budget=("-max_total_time=$limit")
else
    echo "usage: scripts/fuzz.sh [seconds | -runs=N] [libFuzzer flags...]" >&2
    exit 2
fi

bash scripts/deps.sh clang-14 libclang-rt-14-dev

# FLUID_FUZZ_BUILD names a configured tree that already has the fuzz target (the asan preset's
# build/asan: FLUID_BUILD_FUZZ); without it the fuzzer gets a project of its own in build/fuzz.
build="${FLUID_FUZZ_BUILD:-build/fuzz}"
if [[ -z "${FLUID_FUZZ_BUILD:-}" ]]; then
    flags="-O1 -g1 -fno-omit-frame-pointer -fsanitize=address,undefined,fuzzer-no-link"
    flags+=" -fno-sanitize-recover=undefined"
    cmake -S tests/fuzz -B "$build" -G Ninja \
        -DCMAKE_BUILD_TYPE=None \
        -DCMAKE_CXX_COMPILER=clang++-14 \
        -DCMAKE_CXX_FLAGS="$flags" \
        -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
        -DFLUID_WARNINGS_AS_ERRORS=OFF >"$build.configure.log" 2>&1 ||
        { cat "$build.configure.log" >&2; exit 1; }
elif [[ ! -f "$build/CMakeCache.txt" ]]; then
    echo "fuzz.sh: FLUID_FUZZ_BUILD=$build is not a configured build tree" >&2
    exit 1
fi
cmake --build "$build" --target fluid-fuzz-level -j2 >"$build.build.log" 2>&1 ||
    { cat "$build.build.log" >&2; exit 1; }

seeds="$build/seeds"
rm -rf "$seeds"
mkdir -p "$seeds" "$build/corpus" "$build/artifacts"
cp levels/*.json tests/fuzz/seeds/*.json "$seeds"/
cp tests/level/data/*.json "$seeds"/ 2>/dev/null || true
# A level save (Level::save) of a tiny level with bodies and a joint, written by this build, so
# that the save reader is fuzzed too (inputs starting with FLUIDLVL; see level_fuzz.cpp).
FLUID_FUZZ_WRITE_SAVE="tests/fuzz/seeds/save_seed.json=$seeds/save_seed.level" \
    "$build/fluid-fuzz-level" -runs=0 >"$build/seed.log" 2>&1 ||
    { cat "$build/seed.log" >&2; exit 1; }

log="$build/fuzz.log"
echo "fuzz.sh: running fluid-fuzz-level (${budget[*]}); log in $log"
set +e
ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" \
UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
"$build/fluid-fuzz-level" \
    -dict=tests/fuzz/level.dict \
    -max_len=8192 \
    -timeout=10 \
    -rss_limit_mb=2048 \
    -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/" \
    "${budget[@]}" "$@" \
    "$build/corpus" "$seeds" >"$log" 2>&1
status=$?
set -e

runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
if [[ $status -ne 0 ]]; then
    tail -n 60 "$log" >&2
    echo "fuzz.sh: FAILED after ${runs:-?} inputs (exit $status); the input is in $build/artifacts/" >&2
    exit "$status"
fi
echo "fuzz.sh: ${runs:-?} inputs, no crash, hang, leak or sanitizer report; corpus $(ls "$build/corpus" | wc -l) files"

#!/usr/bin/env bash
# Runs the benchmark rows of bench/*.md one after the other and prints them as markdown
# table rows (scene, particles, threads, solver, ms per frame, sub-steps, iterations, largest
# compression, ns per particle per sub-step, peak memory, command).
# Usage: bench/table.sh [path/to/fluid-bench] [all|crates]
#   all     (default) the rows of the main table; about ten minutes on 2 cores.
#   crates  the Box2D crates table: the 16k dam and the crates scene with and without coupling,
#           1 and 2 threads (scene, particles, threads, ms per frame median / mean / p90, CPU ms
#           per frame, sub-steps, ns per particle per sub-step, largest compression, peak
#           memory, command); about two minutes.
#   scaling the performance table: the dam from 4,000 to 256,000 particles on 2 threads, 16,000
#           on 1, and 16,000 on each instruction set the pair passes have (FLUID_SIMD); scene,
#           particles, threads, instruction set, ms per frame, sub-steps, iterations, largest
#           compression, ns per particle per sub-step, peak memory and bytes per particle (peak
#           resident set over particles, the program's own 4 MB included), command; about two
#           minutes.
#   liquidfun
#           the side-by-side table with LiquidFun (bench/liquidfun.md): for the
#           968, 4,050, 15,842 and 64,082 dams, LiquidFun's lf_dam (its path: third argument,
#           default ../shared/anchors/liquidfun/lf_dam) and fluid-bench's game and precise
#           presets on 1 and 2 threads, 30 warm-up and 120 timed frames (64k: 10 and 20), each
#           run three times in turn (LiquidFun, then each fluid setting, then again) and the
#           median kept; particles, LiquidFun ms, then ms and ratio to LiquidFun for game 1
#           thread, game 2 threads, precise 1 thread, precise 2 threads; about eight minutes.
#   levels  the shipped levels (levels/*.json) on one thread: fluid-run (beside fluid-bench) plays
#           each for 300 frames, three times in turn, and the median time is kept; level,
#           settings (the level's solver preset), bodies, mean particles, ms per frame, ns per
#           particle per frame (the whole frame, Box2D and coupling included, over the mean
#           particle count), goal at the end, command; about two minutes.
# Run it on an otherwise idle machine.
set -euo pipefail
bench=${1:-build/release/bench/fluid-bench}
set=${2:-all}
[[ "$set" == all || "$set" == crates || "$set" == scaling || "$set" == liquidfun || "$set" == levels ]] || { echo "bench/table.sh: unknown set '$set' (expected all, crates, scaling, liquidfun or levels)" >&2; exit 2; }
[[ -x "$bench" ]] || { echo "bench/table.sh: no fluid-bench at $bench (build the release preset first)" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The median of the numbers on standard input, one a line.
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

# A field of the machine-readable last line (matched whole: "ms_per_frame" is not "cpu_ms_per_frame").
field() { tail -1 "$tmp/out" | grep -oE "(^| )$1=[0-9.]+" | cut -d= -f2; }

# Runs fluid-bench with the given arguments into $tmp/out; sets rss (peak memory).
measure() {
    rss="n/a"
    if [[ -x /usr/bin/time ]]; then
        /usr/bin/time -o "$tmp/rss" -f '%M' "$bench" "$@" > "$tmp/out" 2> /dev/null
        rss=$(awk '{ printf "%.1f MB", $1 / 1024 }' "$tmp/rss")
    else
        "$bench" "$@" > "$tmp/out" 2> /dev/null
    fi
}

row() {
    local args="$*" rss
    measure "$@"
    local scene solver eos iterations
    scene=$(grep -o -- '--scene [a-z]*' <<<"$args" | cut -d' ' -f2)
    solver=$(grep -o 'solver=[a-z-]*' "$tmp/out" | tail -1 | cut -d= -f2)
    eos=$(grep -o -- '--eos [a-z]*' <<<"$args" | cut -d' ' -f2 || true)
    iterations=$(field iterations)
    if [[ "$solver" == explicit ]]; then solver="explicit / ${eos:-tait}"; iterations="-"; fi
    printf '| %s | %s | %s | %s | %s | %s | %s | %s%% | %s | %s | `fluid-bench %s` |\n' \
        "$scene" "$(field particles)" "$(field threads)" "$solver" "$(field ms_per_frame)" \
        "$(field substeps_per_frame)" "$iterations" \
        "$(awk -v e="$(field density_error_max)" 'BEGIN { printf "%.2f", 100 * e }')" \
        "$(field ns_per_particle_substep)" "$rss" "$args"
}

# A row of the crates table: "crates" with coupling, "crates, not coupled" with --no-coupling.
crates_row() {
    local args="$*" rss scene
    measure "$@"
    scene=$(grep -o -- '--scene [a-z]*' <<<"$args" | cut -d' ' -f2)
    if [[ "$args" == *--no-coupling* ]]; then scene="$scene, not coupled"; fi
    printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s%% | %s | `fluid-bench %s` |\n' \
        "$scene" "$(field particles)" "$(field threads)" "$(field ms_per_frame)" \
        "$(field ms_per_frame_mean)" "$(field ms_per_frame_p90)" "$(field cpu_ms_per_frame)" \
        "$(field substeps_per_frame)" "$(field ns_per_particle_substep)" \
        "$(awk -v e="$(field density_error_max)" 'BEGIN { printf "%.2f", 100 * e }')" "$rss" "$args"
}

# A row of the scaling table; FLUID_SIMD (if set) picks the instruction set.
scaling_row() {
    local args="$*" rss kb isa
    measure "$@"
    kb=$(cat "$tmp/rss" 2> /dev/null || echo 0)
    isa=$(grep -o 'isa=[a-z0-9]*' "$tmp/out" | head -1 | cut -d= -f2)
    printf '| %s | %s | %s | %s | %s | %s | %s | %s%% | %s | %s | %s | `%sfluid-bench %s` |\n' \
        "$(grep -o -- '--scene [a-z]*' <<<"$args" | cut -d' ' -f2)" "$(field particles)" \
        "$(field threads)" "$isa" "$(field ms_per_frame)" "$(field substeps_per_frame)" \
        "$(field iterations)" \
        "$(awk -v e="$(field density_error_max)" 'BEGIN { printf "%.2f", 100 * e }')" \
        "$(field ns_per_particle_substep)" "$rss" \
        "$(awk -v k="$kb" -v n="$(field particles)" 'BEGIN { printf "%.0f", k * 1024 / n }')" \
        "${FLUID_SIMD:+FLUID_SIMD=$FLUID_SIMD }" "$args"
}

if [[ "$set" == liquidfun ]]; then
    lf=${3:-../shared/anchors/liquidfun/lf_dam}
    [[ -x "$lf" ]] || { echo "bench/table.sh: no lf_dam at $lf" >&2; exit 1; }
    ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2fx", a / b }'; }
    # particles, lattice columns and rows (lf_dam), warm-up and timed frames
    for spec in "968 22 44 30 120" "4050 45 90 30 120" "15842 89 178 30 120" \
                "64082 179 358 10 20"; do
        read -r n nx ny warm frames <<<"$spec"
        settings=("game 1" "game 2" "precise 1" "precise 2")
        : > "$tmp/lf"
        for s in "${settings[@]}"; do : > "$tmp/${s// /_}"; done
        for round in 1 2 3; do
            "$lf" "$nx" "$ny" "$warm" "$frames" - 2> /dev/null | grep -oE 'median_ms=[0-9.]+' |
                cut -d= -f2 >> "$tmp/lf"
            for s in "${settings[@]}"; do
                read -r quality threads <<<"$s"
                "$bench" --scene dam --particles "$n" --threads "$threads" --warmup "$warm" \
                    --frames "$frames" --quality "$quality" > "$tmp/out" 2> /dev/null
                field ms_per_frame >> "$tmp/${s// /_}"
            done
        done
        lfms=$(median < "$tmp/lf")
        line="| $(printf "%'d" "$n") | $lfms ms"
        for s in "${settings[@]}"; do
            ms=$(median < "$tmp/${s// /_}")
            line="$line | $ms ms | $(ratio "$ms" "$lfms")"
        done
        echo "$line |"
    done
    exit 0
fi

if [[ "$set" == scaling ]]; then
    scaling_row --scene dam --particles 4000 --frames 60 --warmup 2 --threads 2
    scaling_row --scene dam --particles 16000 --frames 30 --warmup 2 --threads 1
    scaling_row --scene dam --particles 16000 --frames 30 --warmup 2 --threads 2
    scaling_row --scene dam --particles 64000 --frames 10 --warmup 2 --threads 2
    scaling_row --scene dam --particles 100000 --frames 5 --warmup 2 --threads 2
    scaling_row --scene dam --particles 256000 --frames 3 --warmup 1 --threads 2
    for isa in avx2 sse2; do
        FLUID_SIMD=$isa scaling_row --scene dam --particles 16000 --frames 30 --warmup 2 --threads 2
    done
    exit 0
fi

if [[ "$set" == levels ]]; then
    run=$(dirname "$bench")/fluid-run
    [[ -x "$run" ]] || { echo "bench/table.sh: no fluid-run at $run (build the release preset first)" >&2; exit 1; }
    levels=$(cd "$(dirname "$0")/.." && pwd)/levels
    for level in "$levels"/*.json; do
        # The level's settings as its file states them: a `quality` preset, else WorldDef's
        # default (the game preset).
        settings=$(grep -oE '"quality"[^,}]*' "$level" | grep -oE 'game|precise' || true)
        if grep -q '"solver": *"explicit"' "$level"; then settings=explicit; fi
        ms=() ns=()
        for round in 1 2 3; do
            "$run" "$level" --frames 300 --threads 1 > "$tmp/out" 2> /dev/null
            ms+=("$(grep -oE '[0-9.]+ ms per frame' "$tmp/out" | cut -d' ' -f1)")
            ns+=("$(grep -oE '[0-9]+ ns per particle per frame' "$tmp/out" | cut -d' ' -f1)")
        done
        printf '| %s | %s | %s | %s | %s | %s | %s | `fluid-run levels/%s --frames 300 --threads 1` |\n' \
            "$(grep -oE '^fluid-run: [^:]*' "$tmp/out" | cut -d' ' -f2-)" "${settings:-game}" \
            "$(grep -oE '[0-9]+ bodies' "$tmp/out" | cut -d' ' -f1 || echo 0)" \
            "$(grep -oE 'mean [0-9]+ particles' "$tmp/out" | cut -d' ' -f2)" \
            "$(printf '%s\n' "${ms[@]}" | median)" "$(printf '%s\n' "${ns[@]}" | median)" \
            "$(grep -oE 'goal [a-z]+' "$tmp/out" | cut -d' ' -f2 || echo -)" "$(basename "$level")"
    done
    exit 0
fi

if [[ "$set" == crates ]]; then
    for threads in 1 2; do
        crates_row --scene dam --particles 16000 --frames 60 --warmup 2 --threads $threads
        crates_row --scene crates --particles 16000 --frames 60 --warmup 2 --threads $threads --no-coupling
        crates_row --scene crates --particles 16000 --frames 60 --warmup 2 --threads $threads
    done
    exit 0
fi

for particles in 4000 16000; do
    for threads in 1 2; do
        row --scene dam --particles $particles --frames 60 --warmup 2 --threads $threads
    done
done
for particles in 4000 16000; do
    for threads in 1 2; do
        row --scene dam --particles $particles --frames 5 --warmup 1 --threads $threads --solver explicit
    done
done
row --scene dam --particles 1000 --frames 120 --warmup 2 --threads 2
row --scene dam --particles 64000 --frames 20 --warmup 2 --threads 2
row --scene dam --particles 16000 --frames 60 --warmup 2 --threads 2 --substeps 2 --iterations 4
row --scene blob --particles 4000 --frames 60 --warmup 10 --threads 2
row --scene blob --particles 4000 --frames 60 --warmup 10 --threads 2 --solver explicit

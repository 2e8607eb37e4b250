#!/usr/bin/env bash
# Runs the benchmark rows of bench/README.md one after the other and prints them as markdown
# table rows (scene, particles, threads, solver / EOS, ms per frame, sub-steps, ns per particle
# per sub-step, peak memory, command). Usage: bench/table.sh [path/to/fluid-bench]
# Run it on an otherwise idle machine: it takes about ten minutes on 2 cores.
set -euo pipefail
bench=${1:-build/release/bench/fluid-bench}
[[ -x "$bench" ]] || { echo "bench/table.sh: no fluid-bench at $bench (build the release preset first)" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

field() { grep -o "$1=[0-9.]*" "$tmp/out" | cut -d= -f2; }

row() {
    local args="$*" rss="n/a"
    if [[ -x /usr/bin/time ]]; then
        /usr/bin/time -o "$tmp/rss" -f '%M' "$bench" "$@" > "$tmp/out" 2> /dev/null
        rss=$(awk '{ printf "%.1f MB", $1 / 1024 }' "$tmp/rss")
    else
        "$bench" "$@" > "$tmp/out" 2> /dev/null
    fi
    local scene eos
    scene=$(grep -o -- '--scene [a-z]*' <<<"$args" | cut -d' ' -f2)
    eos=$(grep -o -- '--eos [a-z]*' <<<"$args" | cut -d' ' -f2 || true)
    printf '| %s | %s | %s | explicit / %s | %s | %s | %s | %s | `fluid-bench %s` |\n' \
        "$scene" "$(field particles)" "$(field threads)" "${eos:-tait}" "$(field ms_per_frame)" \
        "$(field substeps_per_frame)" "$(field ns_per_particle_substep)" "$rss" "$args"
}

row --scene dam --particles 1000 --frames 60 --warmup 5 --threads 1
row --scene dam --particles 1000 --frames 60 --warmup 5 --threads 2
row --scene dam --particles 4000 --frames 20 --warmup 2 --threads 1
row --scene dam --particles 4000 --frames 20 --warmup 2 --threads 2
row --scene dam --particles 16000 --frames 5 --warmup 1 --threads 1
row --scene dam --particles 16000 --frames 5 --warmup 1 --threads 2
row --scene dam --particles 64000 --frames 2 --warmup 1 --threads 1
row --scene dam --particles 64000 --frames 2 --warmup 1 --threads 2
row --scene blob --particles 1000 --frames 120 --warmup 10 --threads 1
row --scene blob --particles 1000 --frames 120 --warmup 10 --threads 2
row --scene blob --particles 4000 --frames 60 --warmup 10 --threads 1
row --scene blob --particles 4000 --frames 60 --warmup 10 --threads 2
row --scene blob --particles 16000 --frames 20 --warmup 2 --threads 2

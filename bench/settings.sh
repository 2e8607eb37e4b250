#!/usr/bin/env bash
# The settings sweep of the position-based solver: the resting tank (fluid-bench --scene tank,
# 30 x 50 water particles, 5 s) at every sub-steps x sweeps of a grid, one thread, one run after
# the other. Prints a markdown table (compression at the end, surface change, particles thrown
# off the surface, ms per frame) and plots mean and largest compression against ms per frame
# into a PNG.
# Usage: bench/settings.sh FLUID_BENCH [out.png] [viscosity-interval] [coarse]
#   e.g. bash bench/settings.sh build/release/bench/fluid-bench docs/settings.png
# Needs gnuplot for the plot (Debian package gnuplot-nox; installed here when missing and run as
# root). Nothing in the build or the tests uses it.
set -euo pipefail
bench=${1:?usage: bench/settings.sh FLUID_BENCH [out.png] [viscosity-interval] [coarse]}
out=${2:-docs/settings.png}
interval=${3:-1}
coarse=${4:-0}
[[ -x "$bench" ]] || { echo "bench/settings.sh: '$bench' is not an executable" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
field() { tr ' ' '\n' | awk -F= -v k="$1" '$1 == k { print $2; exit }'; }

echo "| sub-steps x sweeps | mean | p99 | max | surface | thrown | ms per frame (1 thread) |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for substeps in 1 2 3 4 6 8; do
    for sweeps in 1 2 3 4 8; do
        if [[ $sweeps -eq 1 ]] && (($(echo "$coarse <= 0" | bc -l))); then
            # One sweep needs the coarse correction: the world refuses it without.
            printf '| %s x 1 | refused without the coarse correction | | | | | |\n' "$substeps"
            continue
        fi
        line=$("$bench" --scene tank --threads 1 --substeps "$substeps" --iterations "$sweeps" \
            --viscosity-interval "$interval" --coarse "$coarse" 2> /dev/null | tail -1)
        mean=$(echo "$line" | field compression_mean)
        p99=$(echo "$line" | field compression_p99)
        max=$(echo "$line" | field compression_max)
        surface=$(echo "$line" | field surface_change)
        thrown=$(echo "$line" | field thrown)
        ms=$(echo "$line" | field ms_per_frame)
        printf '| %s x %s | %.2f%% | %.2f%% | %.1f%% | %+.1f%% | %s | %.2f |\n' "$substeps" "$sweeps" \
            "$(echo "$mean * 100" | bc -l)" "$(echo "$p99 * 100" | bc -l)" \
            "$(echo "$max * 100" | bc -l)" "$(echo "$surface * 100" | bc -l)" "$thrown" "$ms"
        # Coherent: nothing thrown and the surface no higher than at the start.
        if [[ $thrown -eq 0 ]] && (($(echo "$surface <= 0" | bc -l))); then
            echo "$ms $mean $max ${substeps}x${sweeps}" >> "$tmp/coherent.dat"
        else
            echo "$ms $mean $max ${substeps}x${sweeps}" >> "$tmp/broken.dat"
        fi
    done
done

if ! command -v gnuplot > /dev/null; then
    if [[ $(id -u) -ne 0 ]]; then
        echo "bench/settings.sh: gnuplot is missing; install gnuplot-nox as root" >&2
        exit 1
    fi
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq gnuplot-nox > /dev/null
fi
touch "$tmp/coherent.dat" "$tmp/broken.dat"
gnuplot <<EOF
set terminal pngcairo size 1000,640 font ",11"
set output "$out"
set title "Resting 0.5 m tank, 5 s: compression against cost per sub-steps x sweeps (viscosity every $interval, coarse $coarse)"
set xlabel "ms per frame, 1,500 particles, one thread"
set ylabel "compression at 5 s (fraction)"
set logscale y
set yrange [1e-3:100]
set grid
set key top right
plot "$tmp/coherent.dat" using 1:3 with points pt 7 ps 1.2 lc rgb "#1f77b4" title "largest (resting)", \
     "$tmp/coherent.dat" using 1:2 with points pt 5 ps 1.0 lc rgb "#2ca02c" title "mean (resting)", \
     "$tmp/coherent.dat" using 1:3:4 with labels offset 0,0.8 font ",8" notitle, \
     "$tmp/broken.dat" using 1:3 with points pt 2 ps 1.4 lc rgb "#d62728" title "largest (boils: thrown or surface up)", \
     "$tmp/broken.dat" using 1:3:4 with labels offset 0,-0.8 font ",8" tc rgb "#d62728" notitle, \
     0.93 with lines dt 2 lc rgb "#777777" title "LiquidFun's largest (93%)", \
     0.10 with lines dt 3 lc rgb "#ff7f0e" title "game target, largest (10%)"
EOF
echo "plot: $out" >&2

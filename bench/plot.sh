#!/usr/bin/env bash
# Plots ms per frame against particle count from the scaling table (bench/table.sh ... scaling)
# into a PNG: the 2-thread dam rows of the widest instruction set, with the 60 Hz budget, the
# issue's targets (a third of LiquidFun's frame) and LiquidFun's own figures for reference.
# Usage: bench/plot.sh table.md [out.png]   (default out: docs/scaling.png)
#   table.md  the rows bench/table.sh prints for the scaling set, e.g.
#             bash bench/table.sh build/release/bench/fluid-bench scaling | tee /tmp/scaling.md
# Needs gnuplot (Debian package gnuplot-nox; installed here when missing and run as root). It is
# only for this plot: nothing in the build or the tests uses it.
set -euo pipefail
table=${1:?usage: bench/plot.sh table.md [out.png]}
out=${2:-docs/scaling.png}
[[ -r "$table" ]] || { echo "bench/plot.sh: cannot read '$table'" >&2; exit 1; }

if ! command -v gnuplot > /dev/null; then
    if [[ $(id -u) -ne 0 ]]; then
        echo "bench/plot.sh: gnuplot is missing; install the Debian package gnuplot-nox as root" >&2
        exit 1
    fi
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq gnuplot-nox > /dev/null
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Columns: | scene | particles | threads | isa | ms per frame | ... ; the rows without
# FLUID_SIMD in the command are the machine's widest set.
awk -F'|' '$2 ~ /dam/ && $4 + 0 == 2 && $0 !~ /FLUID_SIMD/ { gsub(/ /, "", $3); gsub(/ /, "", $6); print $3, $6 }' \
    "$table" | sort -n > "$tmp/fluid.dat"
[[ -s "$tmp/fluid.dat" ]] || { echo "bench/plot.sh: no 2-thread dam rows in '$table'" >&2; exit 1; }
isa=$(awk -F'|' '$2 ~ /dam/ && $4 + 0 == 2 && $0 !~ /FLUID_SIMD/ { gsub(/ /, "", $5); print $5; exit }' "$table")

cat > "$tmp/plot.gp" <<EOF
set terminal pngcairo size 900,600 font "sans,11"
set output "$out"
set title "fluid-bench --scene dam, water, 2 threads ($isa), default solver (4 sub-steps x 8 sweeps)"
set xlabel "particles"
set ylabel "ms per frame"
set logscale xy
set xrange [3000:300000]
set yrange [1:3000]
set format x "%.0s%c"
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key top left box opaque
set arrow from 3000,16.7 to 300000,16.7 nohead lc rgb "#cc3333" dt 2 lw 1.5
set label "60 Hz (16.7 ms)" at 3300,20 tc rgb "#cc3333"
\$liquidfun << EOD
16000 9.4
64000 45
EOD
\$target << EOD
16000 3
64000 15
100000 16.7
EOD
plot "$tmp/fluid.dat" using 1:2 with linespoints lw 2 pt 7 lc rgb "#1f77b4" title "fluid (measured)", \
     \$liquidfun using 1:2 with points pt 5 ps 1.5 lc rgb "#888888" title "LiquidFun, 1 thread (issue 7)", \
     \$target using 1:2 with points pt 9 ps 1.8 lc rgb "#2ca02c" title "targets (issue 7)"
EOF
gnuplot "$tmp/plot.gp"
echo "bench/plot.sh: wrote $out ($(wc -l < "$tmp/fluid.dat") points)"

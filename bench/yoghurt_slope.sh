#!/usr/bin/env bash
# Does a layer of the yoghurt preset rest on a slope? levels/sticky_plank.json left alone (a
# rested 4.3 cm layer on a kinematic plank tilted 23 degrees), played 30 s by fluid-run with the
# level's world settings replaced by each case's. Prints, per case: ms per frame, how far the
# layer's centroid moved along x from 1 s to 30 s (down the plank is +x) and its lowest point at
# 30 s (the plank's low end is at 0.39 m). docs/yield_stress.md, "The hold over many sweeps".
#
#   bash bench/yoghurt_slope.sh build/release/bench/fluid-run [CASE...]
#
# A case is NAME:SETTINGS, SETTINGS a JSON fragment for the level's "world" object; without
# cases, the game preset with 1, 2, 4 and 8 sweeps per sub-step and the precise preset. One
# thread, one case after the other; about a minute in all.
set -euo pipefail

run="${1:?usage: bench/yoghurt_slope.sh path/to/fluid-run [NAME:SETTINGS ...]}"
shift
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
level="$root/levels/sticky_plank.json"
cases=("$@")
if [ ${#cases[@]} -eq 0 ]; then
    cases=(
        'game:"quality": "game"'
        'game-2-sweeps:"quality": "game", "iterations": 2'
        'game-4-sweeps:"quality": "game", "iterations": 4'
        'game-8-sweeps:"quality": "game", "iterations": 8'
        'precise:"quality": "precise"'
    )
fi
grep -q '"quality": "game" }' "$level" || {
    echo "bench/yoghurt_slope.sh: $level no longer has the world line this script edits" >&2
    exit 1
}

dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

printf '| case | ms/frame | centroid moved 1-30 s (mm) | lowest point 30 s (m) |\n'
printf '|---|---|---|---|\n'
for c in "${cases[@]}"; do
    name=${c%%:*}
    settings=${c#*:}
    sed "s/\"quality\": \"game\" }/$settings }/" "$level" >"$dir/$name.json"
    out=$("$run" "$dir/$name.json" --frames 1800 --threads 1 --csv "$dir/$name.csv")
    ms=$(sed -n 's/.* \([0-9.]*\) ms per frame.*/\1/p' <<<"$out" | head -n 1)
    awk -F, -v name="$name" -v ms="$ms" '
        NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
        $(col["frame"]) == 60 { x1 = $(col["m_yoghurt_cx"]) }
        { x = $(col["m_yoghurt_cx"]); low = $(col["m_yoghurt_ymin"]) }
        END { printf "| %s | %s | %.1f | %.3f |\n", name, ms, 1000 * (x - x1), low }
    ' "$dir/$name.csv"
done

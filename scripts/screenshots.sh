#!/usr/bin/env bash
# Render the README's pictures into docs/screenshots/: every level of levels/ after 2.5 s
# (metaballs, HUD on), the dam break in the pressure and particle views mid-collapse, and
# "Fill the cup" after the planks were dragged into a slide (scripted input, as a player would),
# the yoghurt dollop pushed onto its table once both spouts have emptied (4 s), and the sticky
# plank carried over the bowl with its yoghurt still on it.
# Usage: bash scripts/screenshots.sh [path/to/fluid-demo]   (build it first; runs under Xvfb
# when there is no display)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

demo=${1:-build/release/demo/fluid-demo}
out=docs/screenshots
size=960x540
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

run() {
    if [[ -n "${DISPLAY:-}" ]]; then "$@"; else xvfb-run -a -s "-screen 0 1280x720x24 -noreset" "$@"; fi
}

run "$demo" --level all --frames 150 --size "$size" --screenshot-dir "$tmp" >/dev/null
for file in "$tmp"/*-metaballs.png; do
    cp "$file" "$out/$(basename "${file%-metaballs.png}").png"
done
run "$demo" --level dam_break --frames 30 --size "$size" --view pressure \
    --screenshot "$out/dam_break-pressure.png" >/dev/null
run "$demo" --level dam_break --frames 30 --size "$size" --view particles \
    --screenshot "$out/dam_break-particles.png" >/dev/null

# Fill the cup: shift + drag the three planks (0.55, 0.8|0.72|0.64) to a slide, then pour.
script="$tmp/cup.script"
frame=1
drag() { # x0 y0 x1 y1
    echo "$frame press left $1 $2 shift"
    for k in $(seq 1 30); do
        awk -v f=$((frame + k)) -v k="$k" -v x0="$1" -v y0="$2" -v x1="$3" -v y1="$4" \
            'BEGIN { t = k / 30; printf "%d move %.4f %.4f\n", f, x0 + t * (x1 - x0), y0 + t * (y1 - y0) }'
    done
    frame=$((frame + 35))
    echo "$frame release left"
    frame=$((frame + 1))
}
{
    drag 0.55 0.8 0.2 0.6
    drag 0.55 0.72 0.44 0.5
    drag 0.55 0.64 0.68 0.4
} >"$script"
run "$demo" --level cup_and_planks --frames 330 --size "$size" --script "$script" \
    --screenshot "$out/cup_and_planks.png" >/dev/null

# Yoghurt dollop: the yoghurt's stream pushed onto its table (left drag held just left of it
# and low while the spouts pour, 3 s); at 4 s the mound stands on the table.
script="$tmp/dollop.script"
printf '1 press left 0.86 0.14\n180 release left\n' >"$script"
run "$demo" --level yoghurt_dollop --frames 240 --size "$size" --script "$script" \
    --screenshot "$out/yoghurt_dollop.png" >/dev/null

# Sticky plank: shift + drag the plank from (0.36, 0.5) to (1.0, 0.34), low over the bowl, in
# 1.5 s (eased, so the yoghurt rides along); the picture is taken before the shake.
script="$tmp/plank.script"
{
    echo "10 press left 0.36 0.5 shift"
    for k in $(seq 1 90); do
        awk -v f=$((10 + k)) -v k="$k" \
            'BEGIN { t = 0.5 - 0.5 * cos(3.14159265 * k / 90);
                     printf "%d move %.4f %.4f\n", f, 0.36 + t * 0.64, 0.5 - t * 0.16 }'
    done
} >"$script"
run "$demo" --level sticky_plank --frames 100 --size "$size" --script "$script" \
    --screenshot "$out/sticky_plank.png" >/dev/null
echo "screenshots.sh: wrote $(ls "$out" | wc -l) pictures to $out/"

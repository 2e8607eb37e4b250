#!/usr/bin/env bash
# Reads the figures that the release tests check at one case each, over several cases, for one
# build or two side by side. A change that moves the solver's bits moves these figures as a
# small change of the case does (a count of pieces at one sweep speed, one particle's
# compression at one impact, whether a crate rests at 5 s): compare two builds here, over
# every case, before reading a test that crosses its bound as the change's own effect.
#
#   bash scripts/readings.sh [--no-demo] BUILD_DIR [OTHER_BUILD_DIR]
#
# e.g. bash scripts/readings.sh /tmp/before/build/release build/release
#
# What it reads (the hidden test cases tagged [.readings], each next to the test it widens):
#   lump/...         the yoghurt lump pushed at nine sweep speeds, 0.2-1.0 m/s: pieces, the
#                    largest piece and how far its centre moved (tests/invariants/
#                    test_yoghurt_lump.cpp, which checks all nine)
#   stiff-block/...  the 1e5 Pa block moved 0-5 mm, both yield models, both presets: its top
#                    after 4 s (tests/invariants/test_yield_stress.cpp)
#   big-tank/...     big_tank.json's column moved 0-3.5 mm: the largest compression over 150
#                    frames (tests/level/test_level_demo_levels.cpp)
#   tank-pressure/...
#                    the game preset's 0.3 m resting tank after 140-170 frames: its pressure at
#                    four depths against rho0 g d (tests/invariants/test_rays_tank.cpp)
#   landing/...      the seven crate landings on yoghurt, the crate at the middle and 7 and
#                    13 mm right of it: its speed and the paste's energy after 5 s
#                    (tests/box2d/physics/test_yoghurt_impact.cpp)
#   bearing/...      a guided box at 0.5, 1 and 1.5 x the paste's density on 0.3 m of 50 and
#                    100 Pa paste, both yield models: what the paste carries beyond buoyancy over
#                    Prandtl's load, and the box's submerged fraction, after 8 s
#                    (tests/box2d/physics/test_yoghurt_bearing.cpp, which checks two of them)
#   set-down/...     a crate of 0.5, 1 and 2 x the paste's density set down on the same layer,
#                    at the middle and 7 mm right of it: its RMS speed and its height's range
#                    over 2-4 s (the same file; its test bounds the 1 and 2 x crates)
#   stirred-game/... a 300 Pa paste at the game preset stirred at 60 to 100 m/s^2: its largest
#                    kinetic energy per kilogram 5-10 s after release against the largest RMS of
#                    its particles' real moves per quarter second, as a speed (m/s)
#                    (tests/invariants/test_shear_constraint.cpp)
#   outline/...      yoghurt_dollop.json's heap poured with its yoghurt spout moved by -6 to +8
#                    mm, at both presets, and 160-particle water and yoghurt drops at rest in
#                    zero-g: the drawn outline's RMS roughness (spacings) and curvature noise
#                    (rad per spacing) after 10 s (tests/level/test_level_dollop_outline.cpp,
#                    which checks the shipped preset's mean); outline/spout/...: the same heap
#                    poured at the game preset by other spouts (lower, a wide slow extruder,
#                    a faster rate), with the particles each poured
#   holes/...        yoghurt_dollop.json poured with its yoghurt spout moved by -6 to +8 mm:
#                    hole pixels in its picture after 240 frames (the demo, under xvfb-run when
#                    there is no display; --no-demo leaves it out)
# Output: one line per figure, "KEY VALUE" for one build, "KEY OLD NEW" for two. About a
# minute per build on an idle two-core machine. Exit status 0, or 2 for bad arguments.
set -euo pipefail

demo=1
if [[ ${1:-} == --no-demo ]]; then
    demo=0
    shift
fi
if [[ $# -lt 1 || $# -gt 2 ]]; then
    echo "usage: $0 [--no-demo] BUILD_DIR [OTHER_BUILD_DIR]" >&2
    exit 2
fi
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The figures of one build, sorted by key, into $2.
read_build() {
    local build=$1 out=$2 binary
    for binary in tests/fluid-tests-physics tests/fluid-tests-level \
                  tests/box2d/fluid-tests-box2d-physics; do
        if [[ ! -x $build/$binary ]]; then
            echo "$0: $build/$binary is missing (build the release preset first)" >&2
            exit 2
        fi
        "$build/$binary" "[readings]" | sed -n 's/^\[reading\] //p'
    done >"$out.raw"
    if [[ $demo == 1 ]]; then
        local demo_bin=$build/demo/fluid-demo holes=$build/tests/demo/fluid-tests-demo-holes
        local run=() dirs=() dx x dir
        if [[ -z ${DISPLAY:-} ]]; then
            run=(xvfb-run -a -s "-screen 0 1280x720x24 -noreset")
        fi
        for dx in -0.006 -0.004 -0.002 0 0.002 0.004 0.006 0.008; do
            x=$(awk -v d="$dx" 'BEGIN { printf "%.3f", 0.93 + d }')
            dir=$work/$(basename "$out")-spout=${dx}m
            mkdir -p "$dir"
            # The level's own name (yoghurt_dollop) would be read from levels/: another name.
            sed "s/\"position\": \[0.93, 0.24\]/\"position\": [$x, 0.24]/" \
                "$root/levels/yoghurt_dollop.json" >"$dir/dollop.json"
            "${run[@]}" "$demo_bin" --level "$dir/dollop.json" --frames 240 --size 960x540 \
                --no-hud --threads 2 --screenshot-dir "$dir" >/dev/null
            dirs+=("$dir")
        done
        (IFS=:; FLUID_READINGS_SHOTS="${dirs[*]}" "${run[@]}" "$holes" "[readings]") |
            sed -n "s/^\[reading\] holes\/$(basename "$out")-/holes\//p" >>"$out.raw"
    fi
    LC_ALL=C sort "$out.raw" >"$out"
}

read_build "$1" "$work/a"
if [[ $# -eq 1 ]]; then
    cat "$work/a"
    exit 0
fi
read_build "$2" "$work/b"
LC_ALL=C join -a 1 -a 2 -e - -o 0,1.2,2.2 "$work/a" "$work/b" |
    awk '{ printf "%-52s %-10s %s\n", $1, $2, $3 }'

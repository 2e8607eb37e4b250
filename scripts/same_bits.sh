#!/usr/bin/env bash
# Checks that two builds step every shipped level to the same bits: each level (as shipped, with
# the explicit solver, and at the precise quality) is played FRAMES frames by both builds' fluid-run
# on THREADS workers, and the saves they write at the end are compared byte for byte. A
# refactoring that promises bit-identical results runs this against the build before it; with
# --web the second build is a WebAssembly one (the `web` preset, scripts/web.sh), its fluid-run
# played by Node.js, the first the native build, both on one worker (a build without threads;
# a save records the worker count, and the results do not depend on it).
#
#   bash scripts/same_bits.sh [--web] OLD_BUILD_DIR NEW_BUILD_DIR [FRAMES] [THREADS]
#
# e.g. bash scripts/same_bits.sh /tmp/before/build/release build/release 90 2
#      bash scripts/same_bits.sh --web build/release build/web 600
# Exit status: 0 when every save matches, 1 when some differ (listed), 2 for bad arguments.
set -euo pipefail

web=0
if [[ ${1:-} == --web ]]; then
    web=1
    shift
fi
if [[ $# -lt 2 ]]; then
    echo "usage: $0 [--web] OLD_BUILD_DIR NEW_BUILD_DIR [FRAMES] [THREADS]" >&2
    exit 2
fi
old=$1/bench/fluid-run
new=$2/bench/fluid-run
frames=${3:-90}
threads=${4:-2}
old_run=("$old")
new_run=("$new")
if [[ $web -eq 1 ]]; then
    new=$2/bench/fluid-run.js
    new_run=(node --no-experimental-fetch "$new")
    threads=1
fi
for tool in "$old" "$new"; do
    if [[ ! -f $tool ]]; then
        echo "$0: no fluid-run at $tool" >&2
        exit 2
    fi
done

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The variants: as shipped (most levels at the game quality, the default), the explicit solver,
# the precise quality (the world's settings line rewritten; levels keep their own other
# settings).
variant() { # level-file variant-name -> writes the variant's level file, prints its path
    local level=$1 name=$2 out
    out="$work/levels/$(basename "$level" .json)-$name.json"
    mkdir -p "$work/levels"
    case $name in
    shipped) cp "$level" "$out" ;;
    explicit) # the explicit solver steps no yield stress: the yoghurt goes Newtonian
        sed -E 's/"world": *\{/"world": { "solver": "explicit",/; s/"solver": "position_based", *//
            s/, *"(yieldStress|consistency)": *[-+0-9.eE]+//g
            s/"preset": "yoghurt"/"preset": "yoghurt", "yieldStress": 0, "consistency": 0/g' \
            "$level" >"$out" ;;
    precise) # a level that names its quality has it replaced, others get one
        if grep -q '"quality"' "$level"; then
            sed -E 's/"quality": *"[a-z]+"/"quality": "precise"/' "$level" >"$out"
        else
            sed -E 's/"world": *\{/"world": { "quality": "precise",/' "$level" >"$out"
        fi ;;
    esac
    echo "$out"
}

failed=0
checked=0
for level in "$root"/levels/*.json; do
    for name in shipped explicit precise; do
        file=$(variant "$level" "$name")
        tag=$(basename "$file" .json)
        for side in old new; do
            run=("${old_run[@]}")
            [[ $side == new ]] && run=("${new_run[@]}")
            if ! "${run[@]}" "$file" --frames "$frames" --threads "$threads" \
                --snapshot-every "$frames" --out "$work/$side/$tag" >"$work/$side-$tag.log" 2>&1; then
                echo "$tag: $side build failed: $(tail -1 "$work/$side-$tag.log")"
                failed=1
                continue 2
            fi
        done
        if diff -rq "$work/old/$tag" "$work/new/$tag" >/dev/null; then
            checked=$((checked + 1))
        else
            echo "$tag: saves differ after $frames frames"
            failed=1
        fi
    done
done
what="on $threads threads"
[[ $web -eq 1 ]] && what="natively and in WebAssembly, one thread"
echo "same_bits: $checked level variants identical after $frames frames $what"
exit "$failed"

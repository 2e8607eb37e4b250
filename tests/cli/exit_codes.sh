#!/usr/bin/env bash
# fluid tests — every program's command-line errors exit with status 2 and say what is wrong
# on standard error; --help exits with 0. Arguments: NAME=PATH pairs of the programs built
# (fluid-run, fluid-bench, fluid-soak, fluid-float, fluid-demo).
set -uo pipefail

failed=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# expect STATUS PROGRAM ARGS...: runs it with no display and no input, checks the status, and
# for a bad command line that standard error names the problem.
expect() {
    local want=$1 name=$2
    shift 2
    local path=${programs[$name]}
    env -u DISPLAY "$path" "$@" </dev/null >"$tmp/out" 2>"$tmp/err"
    local got=$?
    if [[ $got -ne $want ]]; then
        echo "FAIL: $name $* exited with $got, expected $want; stderr: $(head -c 300 "$tmp/err")"
        failed=1
    elif [[ $want -eq 2 && ! -s "$tmp/err" ]]; then
        echo "FAIL: $name $* exited with 2 but printed nothing on standard error"
        failed=1
    else
        echo "ok: $name $* -> $got"
    fi
}

declare -A programs
for pair in "$@"; do
    programs[${pair%%=*}]=${pair#*=}
done

level="$(dirname "${BASH_SOURCE[0]}")/../../levels/dam_break.json"
for name in "${!programs[@]}"; do
    expect 0 "$name" --help
    expect 2 "$name" --bogus
done
if [[ -n "${programs[fluid-run]:-}" ]]; then
    expect 2 fluid-run "$level" --frames abc
    expect 2 fluid-run "$level" --frame 60
    expect 2 fluid-run "$level"                    # --frames is required
    expect 2 fluid-run "$level" --frames 10 --threads 0
fi
if [[ -n "${programs[fluid-bench]:-}" ]]; then
    expect 2 fluid-bench --particles abc
    expect 2 fluid-bench --scene nope
fi
if [[ -n "${programs[fluid-soak]:-}" ]]; then
    expect 2 fluid-soak --seconds abc
fi
if [[ -n "${programs[fluid-float]:-}" ]]; then
    expect 2 fluid-float --ratio 9
    expect 2 fluid-float --shape square
    expect 2 fluid-float --material honey
    expect 2 fluid-float --shear-constraint 2
    expect 2 fluid-float --yield-stress -1
fi
if [[ -n "${programs[fluid-demo]:-}" ]]; then
    expect 2 fluid-demo --frames abc
    expect 2 fluid-demo --size 10x10
    expect 2 fluid-demo --level dam_break --frames 3 --script "$tmp" # a directory
fi
exit $failed

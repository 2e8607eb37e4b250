#!/usr/bin/env bash
# The C API's examples run: hello_c; whirlpool_c prints the same angular momentum, line for line,
# as the C++ whirlpool of examples/custom_force.cpp (the same plugin through C); level_c plays
# crates.json as the demo's player does (pointer, blob, gravity off and on, a crate dropped among
# its bodies), saves and loads it back, and names a missing file in its error.
#   bash tests/c/examples.sh EXAMPLES_DIR LEVELS_DIR
set -euo pipefail
examples=$1 levels=$2
"$examples/hello_c" >/dev/null
diff <("$examples/whirlpool_c" | tail -n +2) <("$examples/custom_force" | tail -n +2)
out=$("$examples/level_c" "$levels/crates.json" 160)
grep -q "a blob of [1-9][0-9]* particles" <<<"$out"
grep -q "body barrel" <<<"$out"
grep -q "body (added)" <<<"$out"
grep -q "loaded back with" <<<"$out"
if err=$("$examples/level_c" /nonexistent/level.json 2>&1); then
    echo "examples.sh: level_c played a missing file" >&2
    exit 1
fi
grep -q "cannot open '/nonexistent/level.json'" <<<"$err"
# rays_c: the laser stops on the surface, the diver is under water at every depth.
out=$("$examples/rays_c")
grep -q "laser: hits the water at y = 0\.[23]" <<<"$out"
[[ $(grep -c "in the water" <<<"$out") == 3 ]]
grep -q "bullet: passes [1-9][0-9]* particles" <<<"$out"
echo "examples.sh: hello_c, whirlpool_c (the C++ whirlpool's numbers), level_c and rays_c ran"

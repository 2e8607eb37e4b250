#!/usr/bin/env bash
# Every documented range at its corners: runs the long test set's corner sweeps (tests/invariants/
# test_corners.cpp: each number of Material, WorldDef and PositionBasedDef at its minimum and
# maximum, the others at the preset's, a 2,000-particle dam break for 5 s on one thread) and
# prints docs/levels.md's "Corners" table: per corner, refused (and why) or the largest energy
# above the start's, the largest mean compression, the fastest particle and ms per frame.
#
#   bash bench/corners.sh build/release/tests/fluid-tests-physics [game|precise|explicit ...]
#
# One sweep after the other (their frame times are this machine's, one thread, nothing else
# running); about 25 minutes with the explicit solver, 4 without.
set -euo pipefail

tests="${1:?usage: bench/corners.sh path/to/fluid-tests-physics [game|precise|explicit ...]}"
shift
sweeps=("$@")
if [ ${#sweeps[@]} -eq 0 ]; then
    sweeps=(game precise explicit)
fi

echo "| setting | corner | result | energy above the start | largest mean compression | fastest particle | ms per frame |"
echo "|---|---|---|---:|---:|---:|---:|"
for sweep in "${sweeps[@]}"; do
    FLUID_CORNER_FRAMES="${FLUID_CORNER_FRAMES:-300}" "$tests" "every setting of the $sweep*" --use-colour no 2>&1 | grep '^\[corner\]' |
        awk -F' \\| ' '{
            setting = substr($1, 10); corner = $2;
            if ($3 ~ /^refused: /) {
                reason = substr($3, 10);
                # The reason after the function and material: "mass = ... m; expected ...".
                sub(/^World::addMaterial: material '\''[^'\'']*'\'': /, "", reason);
                sub(/^World::addMaterial: /, "", reason);
                printf "| %s | `%s` | refused: %s | | | | |\n", setting, corner, reason;
                next;
            }
            gain = $4; sub(/^Emax-E0 /, "", gain);
            comp = $6; sub(/^mean compression max /, "", comp);
            speed = $7; sub(/^vmax /, "", speed);
            ms = $8; sub(/ ms\/frame$/, "", ms);
            state = $9; lost = $10;
            printf "| %s | `%s` | %s, %s | %s | %s | %s | %s |\n", setting, corner, state, lost, gain, comp, speed, ms;
        }'
done

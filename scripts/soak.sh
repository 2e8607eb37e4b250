#!/usr/bin/env bash
# Soak: plays fluid-soak's scripted scene (bench/fluid_soak.cpp) for MINUTES of wall-clock time
# and checks after every frame that no particle is lost or leaks, nothing goes non-finite, every
# body stays in the tank and resident memory stays flat (within 5% of its value after the first
# minute, or a third of a shorter run). Exits non-zero at the first failure, naming the frame.
#
#   bash scripts/soak.sh        # 1 minute
#   bash scripts/soak.sh 0.5    # 30 s (what CI runs)
#   bash scripts/soak.sh 10     # 10 minutes
#   SOAK_QUALITY=precise bash scripts/soak.sh 10   # the same scene with the precise preset
#
# Builds the release preset's fluid-soak first (run scripts/deps.sh once on a fresh machine).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

minutes="${1:-1}"
if ! [[ "$minutes" =~ ^[0-9]+([.][0-9]+)?$ ]]; then
    echo "usage: scripts/soak.sh [MINUTES]" >&2
    exit 2
fi
threads="${SOAK_THREADS:-2}"
quality="${SOAK_QUALITY:-game}"

cmake --preset release > /dev/null
cmake --build --preset release --target fluid-soak
seconds=$(awk -v m="$minutes" 'BEGIN { printf "%.0f", m * 60 }')
./build/release/bench/fluid-soak --seconds "$seconds" --threads "$threads" --quality "$quality"

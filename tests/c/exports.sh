#!/usr/bin/env bash
# libfluid_c.so's dynamic symbol table: every symbol it defines is a fluid_* function, and every
# function fluid/c.h declares (FLUID_C_API ... fluid_name(...)) is among them.
#   bash tests/c/exports.sh LIBRARY HEADER
set -euo pipefail
library=$1 header=$2
defined=$(nm -D --defined-only "$library" | awk '{print $3}' | sed 's/@.*//' | sort -u)
others=$(grep -v '^fluid_' <<<"$defined" || true)
if [[ -n $others ]]; then
    echo "exports.sh: $library exports more than the C API:" >&2
    echo "$others" | head -20 >&2
    exit 1
fi
# The declarations: the name before the first '(' on each FLUID_C_API line (a declaration may
# wrap after its name).
declared=$(grep -o '^FLUID_C_API[^(]*(' "$header" | sed 's/($//' | awk '{print $NF}' |
    tr -d '*' | sort -u)
missing=$(comm -23 <(echo "$declared") <(echo "$defined"))
if [[ -n $missing ]]; then
    echo "exports.sh: $library lacks functions fluid/c.h declares:" >&2
    echo "$missing" >&2
    exit 1
fi
extra=$(comm -13 <(echo "$declared") <(echo "$defined"))
if [[ -n $extra ]]; then
    echo "exports.sh: $library exports fluid_* functions fluid/c.h does not declare:" >&2
    echo "$extra" >&2
    exit 1
fi
echo "exports.sh: $(wc -l <<<"$defined") symbols, all fluid_*, the $(wc -l <<<"$declared") functions of fluid/c.h"

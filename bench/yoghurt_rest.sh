#!/usr/bin/env bash
# Does yoghurt come to rest? A 0.2 x 0.2 m block of the yoghurt preset let go on a 3 m floor
# (issue 34's creep case), played 40 s by fluid-run at several yield stresses and step settings.
# Prints, per case: ms per frame, the block's width (outermost particles) at 10 s and 40 s, its
# growth in between, and the kinetic energy per kilogram at 40 s.
#
#   bash bench/yoghurt_rest.sh build/release/bench/fluid-run [CASE...]
#
# A case is NAME:YIELD:SETTINGS[|MATERIAL], SETTINGS a JSON fragment for the level's "world"
# object and MATERIAL one for the yoghurt's (after its yield stress); without cases, the set in
# docs/notes/stress_pass.md ("Why heaps creep") and docs/yield_stress.md ("The shear
# constraint"). One thread, one case
# after the other; about two minutes in all.
set -euo pipefail

run="${1:?usage: bench/yoghurt_rest.sh path/to/fluid-run [NAME:YIELD:SETTINGS[|MATERIAL] ...]}"
shift
cases=("$@")
if [ ${#cases[@]} -eq 0 ]; then
    cases=(
        'game-30Pa:30:"quality": "game"'
        'game:300:"quality": "game"'
        'precise:300:"quality": "precise"'
        'game-stress-every-substep:300:"quality": "game", "viscosityInterval": 1'
        '8x1-every:300:"quality": "game", "substeps": 8, "viscosityInterval": 1'
        '16x1-every-4th:300:"quality": "game", "substeps": 16, "viscosityInterval": 4'
        '16x1-every:300:"quality": "game", "substeps": 16, "viscosityInterval": 1'
        '12x1-every-1Pas:300:"quality": "game", "substeps": 12, "viscosityInterval": 1|"viscosity": 1'
        '16x1-every-1Pas:300:"quality": "game", "substeps": 16, "viscosityInterval": 1|"viscosity": 1'
        'shear-constraint:300:"quality": "game", "shearConstraint": 1|"surfaceTension": 0'
        'shear-constraint-30Pa:30:"quality": "game", "shearConstraint": 1|"surfaceTension": 0'
        'shear-constraint-100Pa:100:"quality": "game", "shearConstraint": 1|"surfaceTension": 0'
        'shear-constraint-surface-tension:300:"quality": "game", "shearConstraint": 1'
        'shear-constraint-precise:300:"quality": "precise", "shearConstraint": 1|"surfaceTension": 0'
    )
fi

dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mass=0.014 # the yoghurt preset's particle mass (kg)

printf '| case | yield stress (Pa) | ms/frame | width 10 s (mm) | width 40 s (mm) | growth (mm) | KE 40 s (J/kg) |\n'
printf '|---|---|---|---|---|---|---|\n'
for c in "${cases[@]}"; do
    name=${c%%:*}
    rest=${c#*:}
    tau=${rest%%:*}
    settings=${rest#*:}
    material=""
    if [[ $settings == *'|'* ]]; then
        material=", ${settings#*|}"
        settings=${settings%%|*}
    fi
    level="$dir/$name.json"
    cat >"$level" <<EOF
{
  "version": 1, "name": "yoghurt block",
  "world": { "gravity": [0, -9.81], "frameRate": 60, "maxParticles": 5000, $settings },
  "materials": [ { "name": "yoghurt", "preset": "yoghurt", "yieldStress": $tau$material } ],
  "plugins": [ { "type": "boundary.box", "name": "floor",
      "params": { "minX": -1.5, "minY": 0, "maxX": 1.5, "maxY": 1, "openTop": 1, "friction": 1 } } ],
  "blobs": [ { "material": "yoghurt", "shape": "box", "min": [-0.1, 0], "max": [0.1, 0.2] } ]
}
EOF
    summary=$("$run" "$level" --frames 2400 --threads 1 --csv "$dir/$name.csv" 2>&1 | tail -1)
    ms=$(sed -n 's/.* particles, \([0-9.]*\) ms per frame.*/\1/p' <<<"$summary")
    awk -F, -v name="$name" -v tau="$tau" -v ms="$ms" -v mass="$mass" '
        NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
        $1 == 600 { w10 = $(col["m_yoghurt_xmax"]) - $(col["m_yoghurt_xmin"]) }
        $1 == 2400 {
            w40 = $(col["m_yoghurt_xmax"]) - $(col["m_yoghurt_xmin"])
            ke = $(col["kinetic_energy"]) / ($(col["particles"]) * mass)
        }
        END {
            printf "| %s | %s | %s | %.1f | %.1f | %.1f | %.2g |\n", name, tau, ms,
                   w10 * 1000, w40 * 1000, (w40 - w10) * 1000, ke
        }' "$dir/$name.csv"
done

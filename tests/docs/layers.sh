#!/usr/bin/env bash
# The layers of docs/architecture.md, checked against every #include of the source tree: a
# folder may include headers from its own folder and from the layers below it, never from a
# layer above it nor from another folder of its own layer (the top layer's programs and tests
# excepted). Each #include is resolved as the compiler would find it (the including file's
# folder first, then the project's include folders); headers outside the project (the standard
# library, glm, Box2D, ...) are not checked.
# Usage: bash tests/docs/layers.sh [project root]   (ctest: docs.layers)
set -euo pipefail
root=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
cd "$root"

# Sets `layer` (1 = bottom) and `unit` (the folder, or the folders built into one library) of a
# project path. Keep in step with the table at the top of docs/architecture.md.
layer_of() {
    case "$1" in
        plugins/box2d/*) layer=2 unit="plugins/box2d/" ;;
        fluid/* | plugins/*) layer=1 unit="fluid/ and plugins/" ;;
        gl/* | shaders/*) layer=2 unit="gl/" ;;
        level/*) layer=3 unit="level/" ;;
        c/*) layer=4 unit="c/" ;;
        demo/*) layer=5 unit="demo/" ;;
        bench/*) layer=5 unit="bench/" ;;
        examples/*) layer=5 unit="examples/" ;;
        tests/*) layer=5 unit="tests/" ;;
        *) layer=0 unit="?" ;;
    esac
}
top=5

# Where the build looks for headers, after the including file's own folder.
include_dirs=(fluid/include fluid/internal/include fluid/src plugins/include
    plugins/box2d/include plugins/box2d/src gl/include gl/src level/include level/src
    c/include c/src bench demo tests/support .)

# A path without "./" and "dir/.." parts.
normalize() {
    local path=${1#./} out=()
    local IFS=/
    for part in $path; do
        case "$part" in
            . | "") ;;
            ..) unset 'out[${#out[@]}-1]' ;;
            *) out+=("$part") ;;
        esac
    done
    echo "${out[*]}"
}

failures=0
checked=0
while IFS= read -r hit; do
    file=${hit%%:*}
    rest=${hit#*:}
    line=${rest%%:*}
    text=${rest#*:}
    [[ $text =~ ^[[:space:]]*#[[:space:]]*include[[:space:]]*[\<\"]([^\>\"]+)[\>\"] ]] || continue
    header=${BASH_REMATCH[1]}
    found=""
    for dir in "${file%/*}" "${include_dirs[@]}"; do
        if [[ -f "$dir/$header" ]]; then
            found=$(normalize "$dir/$header")
            break
        fi
    done
    [[ -n $found ]] || continue
    checked=$((checked + 1))
    layer_of "$file"
    from_layer=$layer from_unit=$unit
    layer_of "$found"
    if [[ $from_unit == "$unit" || $from_layer -eq $top || $layer -lt $from_layer ]]; then
        continue
    fi
    if [[ $layer -eq $from_layer ]]; then
        why="another folder of its layer ($unit, layer $layer)"
    else
        why="a layer above it ($unit, layer $layer)"
    fi
    echo "$file:$line: $from_unit (layer $from_layer) includes <$header> ($found) from $why;" \
        "see the layers of docs/architecture.md" >&2
    failures=$((failures + 1))
done < <(grep -rnE --include='*.h' --include='*.hpp' --include='*.cpp' --include='*.c' \
    --include='*.inl' '^[[:space:]]*#[[:space:]]*include' \
    fluid plugins gl shaders level c demo bench examples tests 2>/dev/null | sort)

if ((failures > 0)); then
    echo "tests/docs/layers.sh: $failures #include line(s) break the layers of docs/architecture.md" >&2
    exit 1
fi
echo "tests/docs/layers.sh: $checked project #includes follow the layers of docs/architecture.md"

#!/usr/bin/env bash
# Builds fluid for the web (WebAssembly) with Debian 12's emscripten into build/web (the `web`
# CMake preset): the core, the built-in plugins, fluid::box2d, fluid::level, fluid::gl (WebGL2)
# and the headless programs for Node.js, and the demo as a page (build/web/demo/page/).
# What Debian ships only as native builds comes from Debian's source packages, compiled here by
# emscripten: Box2D 2.4.1 and Dear ImGui 1.86 (`apt-get source`, with a deb-src line for
# bookworm added when the machine has none). Header-only packages (glm, nlohmann-json, CLI11,
# stb) are Debian's own,
# copied into a prefix of the build's (build/web-deps/prefix) so that the compiler never sees
# the system's whole include folder. Nothing is downloaded from anywhere but Debian.
#
#   bash scripts/web.sh              install what is missing (as root), build build/web
#   bash scripts/web.sh --deps-only  only the packages and build/web-deps
#   bash scripts/web.sh --test       build, then the browser checks: Debian's chromium and
#                                    puppeteer-core (npm ci in tests/web) installed, the desktop
#                                    demo built (build/release), the same game on both
#                                    (tests/web/same_game.sh) and the same saves for every
#                                    level (scripts/same_bits.sh --web)
#
# The programs run in Node.js (`node --no-experimental-fetch build/web/bench/fluid-run.js`, the
# file system of the machine reachable as it is natively). Same bits as the native build:
# bash scripts/same_bits.sh --web build/release build/web. docs/web.md tells the rest.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
deps="$root/build/web-deps"
prefix="$deps/prefix"
deps_only=0
test=0
for arg in "$@"; do
    case $arg in
    --deps-only) deps_only=1 ;;
    --test) test=1 ;;
    *)
        echo "usage: $0 [--deps-only | --test]" >&2
        exit 2
        ;;
    esac
done

# Debian packages: emscripten (and the Node.js it runs with), the header-only libraries, the
# tools that unpack a source package.
PACKAGES=(emscripten nodejs cmake ninja-build dpkg-dev libglm-dev nlohmann-json3-dev libcli11-dev
    libstb-dev fonts-dejavu-core)
# The browser checks: Debian's Chromium (software WebGL2 through SwiftShader), npm for
# puppeteer-core, which drives it.
if [[ $test -eq 1 ]]; then
    PACKAGES+=(chromium python3 xvfb xauth)
    # Debian's npm, unless the machine's Node.js brought its own.
    command -v npm >/dev/null || PACKAGES+=(npm)
fi
bash "$root/scripts/deps.sh" "${PACKAGES[@]}"

# The header-only libraries, each with Debian's CMake package files, under the prefix (their
# package files find the headers relative to themselves).
mkdir -p "$prefix/include" "$prefix/share/cmake"
for pair in glm:glm nlohmann:nlohmann_json CLI:CLI11; do
    headers=${pair%%:*} package=${pair##*:}
    rm -rf "${prefix:?}/include/$headers" "${prefix:?}/share/cmake/$package"
    cp -r "/usr/include/$headers" "$prefix/include/"
    cp -r "/usr/share/cmake/$package" "$prefix/share/cmake/"
done
mkdir -p "$prefix/include/stb"
cp /usr/include/stb/stb_image_write.h "$prefix/include/stb/"

# Debian's source package $1 unpacked (Debian's patches applied) in build/web-deps/src once;
# prints its folder.
source_package() {
    local name=$1 src="$deps/src"
    mkdir -p "$src"
    if ! ls -d "$src/$name"-*/ >/dev/null 2>&1; then
        if ! apt-get source --print-uris "$name" >/dev/null 2>&1; then
            if [[ $(id -u) -ne 0 ]]; then
                echo "web.sh: apt has no deb-src line for $name's source (run as root to add one)" >&2
                exit 1
            fi
            echo "web.sh: adding Debian bookworm's source packages (deb-src) to apt" >&2
            cat >/etc/apt/sources.list.d/fluid-web-sources.sources <<'EOF'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
            apt-get update -qq </dev/null >&2
        fi
        (cd "$src" && apt-get source -qq "$name" </dev/null 2>&1 | grep -v '^W: Download is performed unsandboxed' >&2 || true)
    fi
    ls -d "$src/$name"-*/ | head -1
}

# Box2D, built once.
if [[ ! -f "$prefix/lib/cmake/box2d/box2dConfig.cmake" ]]; then
    box2d_src=$(source_package box2d)
    echo "web.sh: building Box2D from $box2d_src"
    emcmake cmake -S "$box2d_src" -B "$deps/box2d-build" -G Ninja \
        -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$prefix" \
        -DBOX2D_BUILD_UNIT_TESTS=OFF -DBOX2D_BUILD_TESTBED=OFF -DBOX2D_BUILD_DOCS=OFF \
        -DBUILD_SHARED_LIBS=OFF -DCMAKE_CXX_FLAGS="-ffp-contract=off -fwasm-exceptions" </dev/null >/dev/null
    cmake --build "$deps/box2d-build" </dev/null >/dev/null
    cmake --install "$deps/box2d-build" </dev/null >/dev/null
fi

# Dear ImGui with its OpenGL3 backend for OpenGL ES 3.0 / WebGL2, built once, laid out as
# Debian's libimgui-dev (headers in include/imgui, the backends in include/imgui/backends).
if [[ ! -f "$prefix/lib/libimgui.a" ]]; then
    imgui_src=$(source_package imgui)
    echo "web.sh: building Dear ImGui from $imgui_src"
    obj="$deps/imgui-build"
    rm -rf "$obj" && mkdir -p "$obj"
    for f in imgui.cpp imgui_draw.cpp imgui_tables.cpp imgui_widgets.cpp \
        backends/imgui_impl_opengl3.cpp; do
        em++ -std=c++17 -O2 -ffp-contract=off -fwasm-exceptions -DIMGUI_IMPL_OPENGL_ES3 \
            -I"$imgui_src" -c "$imgui_src/$f" -o "$obj/$(basename "$f" .cpp).o"
    done
    mkdir -p "$prefix/lib" "$prefix/include/imgui/backends"
    emar rcs "$prefix/lib/libimgui.a" "$obj"/*.o
    cp "$imgui_src"/imgui.h "$imgui_src"/imconfig.h "$imgui_src"/imgui_internal.h \
        "$imgui_src"/imstb_*.h "$prefix/include/imgui/"
    cp "$imgui_src"/backends/imgui_impl_opengl3.h "$imgui_src"/backends/imgui_impl_opengl3_loader.h \
        "$prefix/include/imgui/backends/"
fi
echo "web.sh: dependencies in $prefix (Box2D and Dear ImGui from Debian's source packages)"
[[ $deps_only -eq 1 ]] && exit 0

cd "$root"
cmake --preset web </dev/null
cmake --build --preset web </dev/null
echo "web.sh: built build/web: the page in build/web/demo/page/ (serve it: docs/web.md);"
echo "        node --no-experimental-fetch build/web/bench/fluid-run.js LEVEL --frames N"
[[ $test -eq 1 ]] || exit 0

(cd "$root/tests/web" && npm ci --no-audit --no-fund </dev/null >/dev/null)
if [[ ! -x "$root/build/release/demo/fluid-demo" || ! -x "$root/build/release/bench/fluid-run" ]]; then
    bash "$root/scripts/deps.sh"
    cmake --preset release </dev/null >/dev/null
    cmake --build --preset release --target fluid-demo fluid-run </dev/null >/dev/null
fi
bash "$root/tests/web/same_game.sh" build/release build/web crates crates.script 600
bash "$root/scripts/same_bits.sh" --web build/release build/web 60

#!/usr/bin/env bash
# The same game on the desktop and in a browser: plays LEVEL with tests/web/SCRIPT for FRAMES
# frames in the desktop demo (NATIVE_BUILD/demo/fluid-demo, under Xvfb when there is no
# display) and in the page (WEB_BUILD/demo/page, served from a temporary folder on loopback,
# played by Debian's Chromium headless with software WebGL2 through tests/web/play.mjs), then
# compares the two summary lines (particles, centre of mass, bodies, the state's hash). Saves
# both pictures in OUT (default /tmp/fluid-same-game). Needs `npm ci` in tests/web once.
#
#   bash tests/web/same_game.sh NATIVE_BUILD WEB_BUILD [LEVEL] [SCRIPT] [FRAMES] [OUT]
#   e.g. bash tests/web/same_game.sh build/release build/web crates crates.script 600
# Exit status: 0 when the lines are the same, 1 when they differ or a side failed, 2 for bad
# arguments.
set -euo pipefail

if [[ $# -lt 2 ]]; then
    echo "usage: $0 NATIVE_BUILD WEB_BUILD [LEVEL] [SCRIPT] [FRAMES] [OUT]" >&2
    exit 2
fi
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
native=$1/demo/fluid-demo
page=$2/demo/page
level=${3:-crates}
script=${4:-crates.script}
frames=${5:-600}
out=${6:-/tmp/fluid-same-game}
for need in "$native" "$page/index.html" "$page/fluid-demo.wasm" "$here/$script"; do
    if [[ ! -e $need ]]; then
        echo "$0: missing $need" >&2
        exit 2
    fi
done
if [[ ! -d $here/node_modules/puppeteer-core ]]; then
    echo "$0: run 'npm ci' in $here first (puppeteer-core drives Debian's chromium)" >&2
    exit 2
fi
mkdir -p "$out"

# The desktop: one worker, as the page.
run_native=("$native" --level "$level" --script "$here/$script" --frames "$frames" --threads 1
    --screenshot "$out/native.png")
if [[ -z ${DISPLAY:-} ]]; then
    run_native=(xvfb-run -a -s "-screen 0 1280x720x24" "${run_native[@]}")
fi
"${run_native[@]}" >"$out/native.log" 2>&1 || {
    echo "same_game: the desktop demo failed:" >&2
    tail -5 "$out/native.log" >&2
    exit 1
}
native_line=$(grep '^fluid-demo: level=' "$out/native.log" | tail -1)

# The page, with the script beside it, on a free loopback port.
site=$(mktemp -d)
server=
cleanup() {
    [[ -n $server ]] && kill "$server" 2>/dev/null || true
    rm -rf "$site"
}
trap cleanup EXIT
cp "$page"/* "$site/"
cp "$here/$script" "$site/script.txt"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server "$port" --bind 127.0.0.1 --directory "$site" >"$out/server.log" 2>&1 &
server=$!
for _ in $(seq 50); do
    python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/index.html')" \
        2>/dev/null && break
    sleep 0.1
done
url="http://127.0.0.1:$port/index.html?level=$level&script=script.txt&frames=$frames"
started=$SECONDS
status=0
node "$here/play.mjs" "$url" "$out/web.png" 1200 >"$out/web.log" 2>&1 || status=$?
web_seconds=$((SECONDS - started))
web_line=$(grep '^fluid-demo: level=' "$out/web.log" | tail -1 || true)
if [[ $status -ne 0 || -z $web_line ]]; then
    echo "same_game: the page failed (status $status):" >&2
    grep -v '404' "$out/web.log" | tail -5 >&2
    exit 1
fi

echo "desktop: ${native_line#fluid-demo: }"
echo "browser: ${web_line#fluid-demo: }"
if [[ "$native_line" != "$web_line" ]]; then
    echo "same_game: $level differs after $frames frames (pictures in $out)"
    exit 1
fi
echo "same_game: $level after $frames frames is the same on the desktop and in the browser" \
    "($web_seconds s in the page; pictures in $out)"

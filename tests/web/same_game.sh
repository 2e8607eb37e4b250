#!/usr/bin/env bash
# The same game on the desktop and in a browser. Plays LEVEL in the desktop demo
# (NATIVE_BUILD/demo/fluid-demo, one worker, under Xvfb when there is no display) and in the
# page (WEB_BUILD/demo/page, served from a temporary folder on loopback, played by Debian's
# Chromium headless with software WebGL2 through tests/web/play.mjs), and checks:
#   1. tests/web/SCRIPT for FRAMES frames ends with the same summary line on both (particles,
#      centre of mass, bodies, the hash of every particle's and body's state), and the game's
#      two pictures of the last frame differ in at most 1% of their pixels outside the HUD
#      (two software rasterisers: Mesa's llvmpipe and SwiftShader; tests/web/compare.mjs);
#   2. F5 after 30 frames on each side: the desktop's save, put in the page's saves, loads
#      with F9 and plays on to the same line as on the desktop, and the page's save, copied
#      out of the page, does the same on the desktop, and in the page after a reload;
#   3. a finger dragged on the page (touch events, the canvas scaled down) is recorded
#      (--record) at the pixels it touched, and the recording replays on the desktop to the
#      same line as the page's.
# Pictures, logs and saves stay in OUT (default /tmp/fluid-same-game). Needs `npm ci` in
# tests/web once (scripts/web.sh --test does all of it).
#
#   bash tests/web/same_game.sh NATIVE_BUILD WEB_BUILD [LEVEL] [SCRIPT] [FRAMES] [OUT]
#   e.g. bash tests/web/same_game.sh build/release build/web crates crates.script 600
# Exit status: 0 when all holds, 1 when something differs or a side failed, 2 for bad
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
rm -rf "$out"
mkdir -p "$out/page-saves"

# The page's folder, with what the runs fetch beside it, on a free loopback port.
site=$(mktemp -d)
server=
cleanup() {
    [[ -n $server ]] && kill "$server" 2>/dev/null || true
    rm -rf "$site"
}
trap cleanup EXIT
cp "$page"/* "$site/"
cp "$here/$script" "$site/play.txt"
printf '30 key F5\n' >"$site/save.txt"
printf '1 key F9\n' >"$site/load.txt"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server "$port" --bind 127.0.0.1 --directory "$site" >"$out/server.log" 2>&1 &
server=$!
for _ in $(seq 50); do
    python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/index.html')" \
        2>/dev/null && break
    sleep 0.1
done

failed=0
fail() {
    echo "same_game: $*"
    failed=1
}

# desktop NAME SCRIPT FRAMES [ARGS...]: prints the summary line; log in OUT/NAME.log.
desktop() {
    local name=$1 file=$2 count=$3
    shift 3
    local run=("$native" --level "$level" --script "$file" --frames "$count" --threads 1 "$@")
    [[ -z ${DISPLAY:-} ]] && run=(xvfb-run -a -s "-screen 0 1280x720x24 -noreset" "${run[@]}")
    if ! "${run[@]}" >"$out/$name.log" 2>&1; then
        echo "same_game: the desktop demo failed ($name):" >&2
        tail -5 "$out/$name.log" >&2
        exit 1
    fi
    grep '^fluid-demo: level=' "$out/$name.log" | tail -1
}

# browser NAME [play.mjs options] -- QUERY [QUERY...]: plays the page once per QUERY (the
# address's query after the level), one after the other in the same browser (a reload, with
# the browser's storage kept); prints the last one's summary line; log in OUT/NAME.log.
browser() {
    local name=$1
    shift
    local options=()
    while [[ $1 != -- ]]; do
        options+=("$1")
        shift
    done
    shift
    local urls=()
    for query in "$@"; do
        urls+=("http://127.0.0.1:$port/index.html?level=$level&$query")
    done
    local status=0
    node "$here/play.mjs" --timeout 1200 "${options[@]}" "$out/$name-page.png" "${urls[@]}" \
        >"$out/$name.log" 2>&1 || status=$?
    local line
    line=$(grep '^fluid-demo: level=' "$out/$name.log" | tail -1 || true)
    if [[ $status -ne 0 || -z $line ]]; then
        echo "same_game: the page failed ($name, status $status):" >&2
        grep -v '404' "$out/$name.log" | tail -5 >&2
        exit 1
    fi
    echo "$line"
}

# 1. The script, and the pictures of its last frame.
started=$SECONDS
native_line=$(desktop native "$here/$script" "$frames" --screenshot "$out/native.png")
web_line=$(browser web --copy "/screenshots/end.png:$out/web.png" -- \
    "script=play.txt&frames=$frames&screenshot=/screenshots/end.png")
echo "desktop: ${native_line#fluid-demo: }"
echo "browser: ${web_line#fluid-demo: }"
if [[ "$native_line" == "$web_line" ]]; then
    echo "same_game: $level after $frames frames is the same on the desktop and in the browser"
else
    fail "$level differs after $frames frames"
fi
node "$here/compare.mjs" "$out/native.png" "$out/web.png" 0.01 48 || fail "the pictures differ"

# 2. F5 after 30 frames on each side, each save loaded with F9 on the other and played on
#    60 frames: the same line as the side that made it. (The saves differ only in the level
#    file's path, which they record: the page's levels sit in /levels.)
desktop save-desktop "$site/save.txt" 30 --save-dir "$out/desktop-saves" >/dev/null
# The page's save is also loaded after a reload, from the browser's storage.
web_reloaded=$(browser save-page --copy "/saves/$level.level:$out/page-saves/$level.level" -- \
    "script=save.txt&frames=30" "script=load.txt&frames=60")
cp "$out/desktop-saves/$level.level" "$site/desktop.level"
native_own=$(desktop load-desktop "$site/load.txt" 60 --save-dir "$out/desktop-saves")
web_from_desktop=$(browser load-desktop-save -- "script=load.txt&frames=60&save=desktop.level")
if [[ "$native_own" == "$web_from_desktop" ]]; then
    echo "same_game: the desktop's save loads in the page and plays on to the same line"
else
    echo "desktop: ${native_own#fluid-demo: }"
    echo "browser: ${web_from_desktop#fluid-demo: }"
    fail "the desktop's save played on in the page differs"
fi
cp "$out/page-saves/$level.level" "$site/page.level"
web_own=$(browser load-page -- "script=load.txt&frames=60&save=page.level")
native_from_page=$(desktop load-page-save "$site/load.txt" 60 --save-dir "$out/page-saves")
if [[ "$web_own" == "$native_from_page" && "$web_own" == "$native_own" ]]; then
    echo "same_game: the page's save loads on the desktop and plays on to the same line"
else
    echo "browser: ${web_own#fluid-demo: }"
    echo "desktop: ${native_from_page#fluid-demo: }"
    fail "the page's save played on on the desktop differs"
fi
if [[ "$web_reloaded" == "$native_own" ]]; then
    echo "same_game: the page's save is there after a reload and plays on to the same line"
else
    echo "browser: ${web_reloaded#fluid-demo: }"
    fail "the page's save after a reload differs"
fi

# 3. Touch: one finger dragged across the water of TOUCH_LEVEL in a page smaller than the game's
#    picture (the canvas scaled down), the input recorded: every recorded pointer position is
#    where the finger was, in the game's pixels; the recording played on the desktop ends on
#    the same line as the page; and the finger moved the water (the line differs from a run
#    without it).
touch_level=dam_break
touch_frames=240
level=$touch_level
touch_line=$(browser touch --viewport 1000x640 --touch "0.1,0.85 0.3,0.85 0.5,0.85 0.5,0.6" \
    --copy "/screenshots/touch.txt:$out/touch.txt" -- \
    "frames=$touch_frames&record=/screenshots/touch.txt")
if ! python3 - "$out/touch.log" "$out/touch.txt" <<'CHECK'; then
import re, sys
touched = [tuple(map(float, m.groups())) for m in
           re.finditer(r"play\.mjs: touch (\S+) (\S+)", open(sys.argv[1]).read())]
lines = [l for l in open(sys.argv[2]) if not l.startswith("#")]
recorded = [(l.split()[1], tuple(map(int, l.split("# pixel")[1].split())))
            for l in lines if "# pixel" in l]
verbs = [verb for verb, _ in recorded if verb != "move"]
ok = verbs.count("press") == 1 and lines[-1].split()[1:] == ["release", "left"]
for verb, (x, y) in recorded:
    if not any(abs(x - tx) <= 1 and abs(y - ty) <= 1 for tx, ty in touched):
        ok = False
        print(f"same_game: the recording's {verb} at pixel {x} {y} is not where the finger was")
if not ok or len(touched) != 4:
    print(f"same_game: touches {touched}, recorded {recorded}")
sys.exit(0 if ok and len(touched) == 4 else 1)
CHECK
    fail "the recorded touch is not the finger's"
fi
touch_native=$(desktop touch-replay "$out/touch.txt" "$touch_frames")
untouched=$(desktop untouched /dev/null "$touch_frames")
if [[ "$touch_line" == "$touch_native" && "$touch_line" != "$untouched" ]]; then
    echo "same_game: a finger on the page is recorded where it was and replays on the desktop" \
        "to the same line"
else
    echo "browser:   ${touch_line#fluid-demo: }"
    echo "desktop:   ${touch_native#fluid-demo: }"
    echo "untouched: ${untouched#fluid-demo: }"
    fail "the touch run differs from its replay, or did not move the water"
fi
echo "same_game: $((SECONDS - started)) s; pictures, logs and saves in $out"
exit "$failed"

#!/usr/bin/env bash
# Tests the visualiser's web page in a real browser: builds it
# (scripts/build-web.sh, unless WEB_SKIP_BUILD=1), serves web/dist on
# 127.0.0.1 and checks it in headless Chromium (scripts/web_check.py): the
# app draws with no console error, a `tirecontact share` link opens its
# scene (the page's title), Play advances the time, at phone sizes
# (390x844, 360x740, touch) a swipe logs no error, and the link cut short
# is refused.
#
#   scripts/test-web.sh [TIRECONTACT_BIN]     (default target/debug/tirecontact)
#
# WEB_SHOTS=DIR also saves screenshots (1280x720, 412x915, 390x844,
# 360x740, the cut link) there;
# WEB_SPEED=1 also measures the paper preset's steps per second in the page
# at the fastest speed, and the real-time factor it plays at when it opens
# at 1x.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
bin=${1:-target/debug/tirecontact}
dist=${WEB_DIST:-$repo/web/dist}

if [ "${WEB_SKIP_BUILD:-0}" != 1 ]; then
    scripts/build-web.sh
fi
[ -f "$dist/index.html" ] || { echo "test-web: no page in $dist: run scripts/build-web.sh" >&2; exit 2; }
[ -x "$bin" ] || { echo "test-web: no $bin: build it with cargo build" >&2; exit 2; }
need=()
command -v chromium >/dev/null 2>&1 || need+=(chromium)
command -v python3 >/dev/null 2>&1 || need+=(python3)
if [ ${#need[@]} -gt 0 ]; then
    [ "$(id -u)" = 0 ] || { echo "test-web: needs ${need[*]} (sudo apt-get install -y ${need[*]})" >&2; exit 2; }
    echo "test-web: installing ${need[*]}"
    DEBIAN_FRONTEND=noninteractive apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}"
fi

port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server --bind 127.0.0.1 --directory "$dist" "$port" >/dev/null 2>&1 &
server=$!
tmp=$(mktemp -d)
trap 'kill $server 2>/dev/null || true; rm -rf "$tmp"' EXIT

link=$("$bin" share presets/three_points.ron)
name=$(sed -n 's/^ *name: *"\(.*\)",$/\1/p' presets/three_points.ron | head -1)
args=("http://127.0.0.1:$port/index.html" "$link" "$name")
# a second link, pasted into the open page's address bar
name2=$(sed -n 's/^ *name: *"\(.*\)",$/\1/p' presets/single_mode.ron | head -1)
args+=(--hash-link "$("$bin" share presets/single_mode.ron)" "$name2")
[ -n "${WEB_SHOTS:-}" ] && args+=(--shots "$WEB_SHOTS")
if [ "${WEB_SPEED:-0}" = 1 ]; then
    # the paper preset, long enough to time 10 s of it, at the fastest speed
    sed 's/^    duration_s: .*/    duration_s: 100.0,/' presets/paper.ron >"$tmp/paper_long.ron"
    args+=(--speed-link "$("$bin" share "$tmp/paper_long.ron")&speed=max")
    args+=(--realtime-link "$("$bin" share "$tmp/paper_long.ron")")
fi
for _ in $(seq 50); do
    python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/index.html')" 2>/dev/null && break
    sleep 0.1
done
python3 scripts/web_check.py "${args[@]}"

#!/usr/bin/env bash
# The demo: install what is missing, build, and run the box program on the
# simulator board. It replays the real Kinect frames in
# ../shared/data/depth/skeltrack through fakenect when they are there (a
# built-in empty scene otherwise), presses START from a timeline, and runs
# headless (PNG frames + the event log) unless a display exists.
#   scripts/demo.sh [SECONDS]      default 8 seconds
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-8}
scripts/setup.sh --host
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target cubdance

out="$PWD/out/demo"
rm -rf "$out"
mkdir -p "$out"
args=(--buttons scripts/demo.buttons --log "$out/events.log" --seconds "$seconds")

dump="${CUB_DATA_DIR:-$PWD/../shared/data}/depth/skeltrack"
if [ -f "$dump/INDEX.txt" ]; then
    echo "demo: replaying the real Kinect frames in $dump through fakenect"
    args+=(--replay "$dump")
else
    echo "demo: no recorded frames at $dump; using the built-in empty scene"
    args+=(--depth empty)
fi
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
    echo "demo: a display exists: opening a window (Space = START, Escape = STOP)"
    args+=(--window)
else
    echo "demo: no display: running headless"
    export EGL_PLATFORM=surfaceless
    args+=(--headless --size 960x540 --frames "$out/frames" --frame-every 15)
fi
export SDL_AUDIODRIVER="${SDL_AUDIODRIVER:-dummy}"
./build/release/app/cubdance/cubdance "${args[@]}"
echo
echo "demo: event log: $out/events.log ($(wc -l < "$out/events.log") lines)"
if [ -d "$out/frames" ]; then
    echo "demo: frames:    $out/frames ($(ls "$out/frames" | wc -l) PNG files)"
fi

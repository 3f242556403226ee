#!/usr/bin/env bash
# The demo: install what is missing, build, and run the box's main job on
# the simulator board: the bear leads a whole song (Twinkle Twinkle Little
# Star). START is pressed from a timeline (scripts/demo.buttons) and a
# scripted judge (scripts/demo.timeline) says right and wrong until the
# tracker gives real verdicts. It replays the real Kinect frames in
# ../shared/data/depth/skeltrack through fakenect for the depth inset when
# they are there (a built-in empty scene otherwise), and runs headless (PNG
# frames + the event log) unless a display exists.
#   scripts/demo.sh [SECONDS]      default 115 (the song, the cheer, a doze)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-115}
scripts/setup.sh --host
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target cubdance

out="$PWD/out/demo"
rm -rf "$out"
mkdir -p "$out"
args=(--song assets/songs/twinkle.song.xml --timeline scripts/demo.timeline
      --buttons scripts/demo.buttons --log "$out/events.log" --seconds "$seconds")

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
    args+=(--headless --size 960x540 --frames "$out/frames" --frame-every 90)
fi
export SDL_AUDIODRIVER="${SDL_AUDIODRIVER:-dummy}"
./build/release/app/cubdance/cubdance "${args[@]}"
echo
echo "demo: event log: $out/events.log ($(wc -l < "$out/events.log") lines)"
if [ -d "$out/frames" ]; then
    echo "demo: frames:    $out/frames ($(ls "$out/frames" | wc -l) PNG files)"
fi

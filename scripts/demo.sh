#!/usr/bin/env bash
# The demo: install what is missing, build, and run the box's main job on
# the simulator board: the bear leads a whole song (Twinkle Twinkle Little
# Star) for a child it watches through a replayed Kinect recording.
#
# The child is synthetic (scripts/make_child.py, scripts/child/twinkle.*):
# a child-sized body driven by motion capture follows the bear, rendered as
# Kinect v1 depth into a fakenect dump (cubtool synth-depth; ~2 GB in a
# temporary folder, deleted at the end). It gets five repetitions wrong on
# purpose (the wrong arm, no clap, no jump, standing still); the box tracks
# it, judges every repetition and corrects. START is pressed from
# scripts/demo.buttons. At the end the demo prints, per repetition, what
# was planted, the verdict and whether the coach corrected, then per
# planted mistake the latency from the mistake showing to the correcting
# clip's first frame (make_child.py score), and the counts.
#
# Headless (PNG frames + the event log, under the virtual clock: the run
# is exact and takes about a minute) unless a display exists (a window,
# real time). Without the motion capture in ../shared/data the judge is
# scripted instead (scripts/demo.timeline) over the real Skeltrack frames.
#   scripts/demo.sh [SECONDS]      default 110 (the song and the cheer)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-110}
scripts/setup.sh --host
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target cubdance cubtool

out="$PWD/out/demo"
rm -rf "$out"
mkdir -p "$out"
data="${CUB_DATA_DIR:-$PWD/../shared/data}"
song=assets/songs/twinkle.song.xml
args=(--song "$song" --buttons scripts/demo.buttons --log "$out/events.log"
      --seconds "$seconds")
work=""
cleanup() { if [ -n "$work" ]; then rm -rf "$work"; fi; }
trap cleanup EXIT INT TERM

if [ -d "$data/mocap" ]; then
    work=$(mktemp -d "${TMPDIR:-/tmp}/cubdance_demo.XXXXXX")
    echo "demo: making the child (scripts/child/twinkle.plan, following scripts/child/twinkle.cues)"
    python3 scripts/make_child.py sequence "$song" scripts/child/twinkle.plan "$work" \
        scripts/child/twinkle.cues
    echo "demo: rendering it as Kinect depth into $work/dump (about 2 GB, half a minute)"
    ./build/release/app/cubtool/cubtool synth-depth --sequence "$work/child.seq" \
        --data "$data" --out "$work/dump" 2>/dev/null | tail -n 1
    export FAKENECT_PATH="$work/dump"
    args+=(--replay "$work/dump")
else
    dump="$data/depth/skeltrack"
    echo "demo: no motion capture under $data: a scripted judge (scripts/demo.timeline)"
    args+=(--timeline scripts/demo.timeline)
    if [ -f "$dump/INDEX.txt" ]; then
        export FAKENECT_PATH="$dump"
        args+=(--replay "$dump")
    else
        args+=(--depth empty)
    fi
fi
if [ -n "${FAKENECT_PATH:-}" ]; then
    fakenect=$(ls -d /usr/lib/*/fakenect | head -n 1)
    export LD_LIBRARY_PATH="$fakenect${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
    echo "demo: a display exists: opening a window (Space = START, Escape = STOP)"
    args+=(--window)
else
    echo "demo: no display: running headless under the virtual clock"
    export EGL_PLATFORM=surfaceless
    args+=(--headless --clock virtual --size 960x540 --frames "$out/frames" --frame-every 90)
fi
export SDL_AUDIODRIVER="${SDL_AUDIODRIVER:-dummy}"
./build/release/app/cubdance/cubdance "${args[@]}"
echo
if [ -n "$work" ]; then
    echo "demo: what the coach saw and did, per repetition the child was led through:"
    python3 scripts/make_child.py score "$work/expect.txt" "$out/events.log" || true
    echo
fi
echo "demo: event log: $out/events.log ($(wc -l < "$out/events.log") lines)"
if [ -d "$out/frames" ]; then
    echo "demo: frames:    $out/frames ($(ls "$out/frames" | wc -l) PNG files)"
fi

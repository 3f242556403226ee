#!/usr/bin/env bash
# The README's screenshots of what the child sees, taken from the real
# cubdance binary (headless EGL, the virtual clock, fixed ticks: the same
# pictures on every run) into docs/screenshots/ at 1280x720:
#   idle.png          before START: "Press START!" over the waiting bear
#   dancing.png       the song: the bear leads, the hint, the move icon,
#                     progress, the tracked child (green) in the inset
#   correction.png    the scripted judge says "wrong" (scripts/demo.timeline
#                     at 18 s): the worried bear shakes its head
#   doze.png          nobody pressed START: the sleepy bear
#   distance_cue.png  a child too far from the camera: "Come closer"
# The child in the inset is synthetic (cubtool synth-depth from the MIT and
# CMU motion capture in ../shared/data/mocap), never a real depth frame.
#   scripts/screenshots.sh [BUILD_DIR]
# Without BUILD_DIR: installs what is missing and builds the release preset
# (as scripts/demo.sh does). Needs the motion capture ($CUB_DATA_DIR or
# ../shared/data).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
if [ $# -ge 1 ]; then
    build=$(cd "$1" && pwd)
else
    scripts/setup.sh --host
    cmake --preset release >/dev/null
    build=$root/build/release
fi
cmake --build "$build" -j 2 --target cubdance cubtool >/dev/null
cubdance=$build/app/cubdance/cubdance
cubtool=$build/app/cubtool/cubtool
data="${CUB_DATA_DIR:-$root/../shared/data}"
if [ ! -d "$data/mocap" ]; then
    echo "screenshots: no motion capture under $data/mocap (set CUB_DATA_DIR):" \
         "the child in the inset is made from it" >&2
    exit 1
fi
out=$root/docs/screenshots
mkdir -p "$out"
work=$(mktemp -d "${TMPDIR:-/tmp}/cubdance_shots.XXXXXX")
trap 'rm -rf "$work"' EXIT INT TERM

export EGL_PLATFORM=surfaceless SDL_AUDIODRIVER=dummy
fakenect=$(ls -d /usr/lib/*/fakenect | head -n 1)
export LD_LIBRARY_PATH="$fakenect${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
song=$root/assets/songs/twinkle.song.xml

# One headless run; ticks are 1/30 s. Only every EVERY-th tick is drawn
# (the event log, so what happens, is the same: the renderer decides
# nothing), so each wanted tick must be a multiple of EVERY.
#   run NAME EVERY SECONDS [cubdance options...]
run() {
    local name=$1 every=$2 seconds=$3
    shift 3
    mkdir -p "$work/$name"
    "$cubdance" --headless --clock virtual --size 1280x720 --song "$song" \
        --draw-every "$every" --frame-every "$every" --seconds "$seconds" \
        --frames "$work/$name" --log "$work/$name/events.log" "$@" >/dev/null
}
# Copy tick TICK of run NAME to docs/screenshots/SHOT.png.
shot() {
    local src
    src=$(printf '%s/%s/frame_%06d.png' "$work" "$1" "$2")
    cp "$src" "$out/$3.png"
    echo "screenshots: $3.png (tick $2 = $(awk "BEGIN { print $2 / 30 }") s)"
}

# Nobody comes: waiting at 2 s, dozing at 8 s (attract after 3 s, doze
# after 5 s instead of the box's 20 s and 60 s, to keep the run short).
run waiting 60 8.1 --depth empty --attract-after 3 --doze-after 5
shot waiting 60 idle
shot waiting 240 doze

# A child who does jumping jacks, then stands still (the synthesizer's
# sequence format: clip from_s to_s), 2.2 m from the camera, in the middle.
{
    for _ in 1 2 3 4 5 6 7 8 9; do echo "jumping_jacks 0.4 2.4"; done
    for _ in 1 2 3; do echo "wave_hello 5.0 6.9"; done
} > "$work/child.seq"
"$cubtool" synth-depth --sequence "$work/child.seq" --data "$data" \
    --out "$work/child" >/dev/null 2>&1
# START at 0.5 s (scripts/demo.buttons); the scripted judge's first "wrong"
# comes at 18 s (scripts/demo.timeline): 12 s is the first move (stretch),
# 18.5 s the head shake of the correction.
FAKENECT_PATH="$work/child" run song 15 18.6 --buttons scripts/demo.buttons \
    --timeline scripts/demo.timeline --replay "$work/child"
grep -q "t=18.000 coach state from=dance to=correct" "$work/song/events.log" || {
    echo "screenshots: the coach no longer corrects at 18 s: pick new ticks" >&2
    exit 1
}
shot song 360 dancing
shot song 555 correction

# A child waving 3.8 m away: beyond the range the Kinect reads well.
"$cubtool" synth-depth --clip wave_hello --from 0 --to 4 --distance 3800 \
    --data "$data" --out "$work/far" >/dev/null 2>&1
FAKENECT_PATH="$work/far" run far 105 3.6 --buttons scripts/demo.buttons \
    --replay "$work/far"
grep -q "track status from=none to=too_far" "$work/far/events.log" || {
    echo "screenshots: the far child is not seen as too far" >&2
    exit 1
}
shot far 105 distance_cue
ls -l "$out"

#!/usr/bin/env bash
# Run the real cubdance binary on a recorded fakenect dump, headless, with a
# button timeline, for a replay (hardware-in-loop) test. The clock is
# virtual, so the event log is the same on every machine and every run.
#   run_cubdance.sh EMULATOR|"" CUBDANCE DUMP_DIR BUTTONS OUT_DIR SECONDS
# Exits 77 (ctest: skipped) when the dump is not there.
set -euo pipefail
emu=$1 exe=$2 dump=$3 buttons=$4 out=$5 seconds=$6
if [ ! -f "$dump/INDEX.txt" ]; then
    echo "SKIP: no fakenect dump at $dump (../shared/data is absent)"
    exit 77
fi
rm -rf "$out"
mkdir -p "$out/frames"
# fakenect replays through libfreenect's own calls: the environment that the
# `fakenect` wrapper sets. cubdance --replay sees it is already in place.
export FAKENECT_PATH="$dump"
export LD_LIBRARY_PATH="${CUB_FAKENECT_DIR}${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export EGL_PLATFORM=surfaceless SDL_AUDIODRIVER=dummy
# shellcheck disable=SC2086
$emu "$exe" --headless --size 320x240 --replay "$dump" --buttons "$buttons" \
    --frames "$out/frames" --frame-every 5 --log "$out/events.log" --seconds "$seconds" --clock virtual
echo "--- event log ($out/events.log):"
cat "$out/events.log"

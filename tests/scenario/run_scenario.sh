#!/usr/bin/env bash
# Run the real cubdance binary through one scenario: headless, no depth
# camera (the judge is scripted), the virtual clock (so the event log is exact), a song,
# a judge timeline and button presses.
#   run_scenario.sh EMULATOR|"" CUBDANCE OUT_DIR NAME SECONDS [cubdance options...]
# With REPLAY_DUMP set, the depth inset replays that fakenect dump (skipped,
# exit 77, when the dump is absent); else there is no depth camera.
set -euo pipefail
emu=$1 exe=$2 out=$3 name=$4 seconds=$5
shift 5
mkdir -p "$out"
export EGL_PLATFORM=surfaceless SDL_AUDIODRIVER=dummy
depth=(--depth off) preload=()
if [ -n "${REPLAY_DUMP:-}" ]; then
    if [ ! -f "$REPLAY_DUMP/INDEX.txt" ]; then
        echo "SKIP: no fakenect dump at $REPLAY_DUMP"
        exit 77
    fi
    export FAKENECT_PATH="$REPLAY_DUMP"
    export LD_LIBRARY_PATH="${CUB_FAKENECT_DIR}${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    depth=(--replay "$REPLAY_DUMP")
    # fakenect's own sleeps only hold the virtual clock to the wall's
    # (tests/soak/fakenect_nosleep.c); env keeps the preload off bash.
    if [ -n "${CUB_NOSLEEP_LIB:-}" ]; then
        [ -f "$CUB_NOSLEEP_LIB" ] || { echo "run_scenario: no $CUB_NOSLEEP_LIB" >&2; exit 1; }
        preload=(env "LD_PRELOAD=$CUB_NOSLEEP_LIB"
                 "ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0")
    fi
fi
# Under the emulator (the pi preset) the lit bear costs ~100 ms a frame in
# emulated llvmpipe: draw one tick in 15 there. The log must not change
# (the renderer decides nothing), and the expected logs are the host's.
draw=()
[ -n "$emu" ] && draw=(--draw-every 15)
# shellcheck disable=SC2086
"${preload[@]}" $emu "$exe" --headless --size 64x48 "${depth[@]}" "${draw[@]}" --clock virtual \
    --seconds "$seconds" --log "$out/$name.log" "$@"
echo "--- $name: $(wc -l < "$out/$name.log") log lines in $out/$name.log"

#!/usr/bin/env bash
# Run the real cubdance binary through one scenario: headless, no depth
# camera (the judge is scripted), the virtual clock (so the event log is exact), a song,
# a judge timeline and button presses.
#   run_scenario.sh EMULATOR|"" CUBDANCE OUT_DIR NAME SECONDS [cubdance options...]
set -euo pipefail
emu=$1 exe=$2 out=$3 name=$4 seconds=$5
shift 5
mkdir -p "$out"
export EGL_PLATFORM=surfaceless SDL_AUDIODRIVER=dummy
# shellcheck disable=SC2086
$emu "$exe" --headless --size 64x48 --depth off --clock virtual --seconds "$seconds" \
    --log "$out/$name.log" "$@"
echo "--- $name: $(wc -l < "$out/$name.log") log lines in $out/$name.log"

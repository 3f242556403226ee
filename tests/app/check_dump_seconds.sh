#!/usr/bin/env bash
# Recorded seconds that jump far ahead (issue 18): fakenect sleeps the
# difference of two lines' recorded seconds inside freenect_process_events,
# so a jump of 1000 s held the box there — in the loop under --clock
# virtual, at close (joining the reader thread) under --clock real — and
# --seconds never ended the run. The dump check now takes a jump of more
# than 10 s out (one frame's step instead), said once per jump on stderr;
# --seconds ends the run in time under both clocks.
#   check_dump_seconds.sh EMULATOR|"" BUILD_DIR OUT_DIR
set -uo pipefail
emu=$1 build=$2 out=$3
# shellcheck source=box_check_common.sh
. "$(dirname "$0")/box_check_common.sh"

# 90 frames at 30 fps by their names; at 1 s the recorded seconds and the
# Kinect timestamps jump 1000 s ahead.
d="$out/dump"
mkdir -p "$d"
{ printf 'P5 640 480 65535\n'; head -c 614400 /dev/zero; } > "$d/frame.pgm"
for k in $(seq 0 89); do
    s=$((1300000000 + k / 30)) ts=$((1000000 + 2000000 * k))
    ((k >= 30)) && s=$((s + 1000)) ts=$((ts + 60000000 * 1000 % 4294967296))
    n=$(printf 'd-%d.%06d-%d.pgm' "$s" $(((k % 30) * 1000000 / 30)) $((ts % 4294967296)))
    ln -s frame.pgm "$d/$n"
    echo "$n" >> "$d/INDEX.txt"
done

# The jump is 1000 s: a run not ended by --seconds 2.5 would take that long.
limit=$((60 * slow))
for clock in virtual real; do
    start=$(date +%s)
    FAKENECT_PATH="$d" LD_LIBRARY_PATH="$fakenect_libs" \
        timeout "$limit" $emu "$bin" --headless "${view[@]}" --clock "$clock" --seconds 2.5 \
        --replay "$d" --log "$out/$clock.log" >"$out/$clock.out" 2>"$out/$clock.err"
    rc=$? took=$(($(date +%s) - start))
    [ "$rc" != 124 ] || fail "$clock: hung past --seconds 2.5 (killed after $limit s)"
    if [ "$rc" -ge 128 ] || grep -qE "AddressSanitizer|runtime error" "$out/$clock.err"; then
        cat "$out/$clock.err"; fail "$clock crashed (exit $rc)"
    fi
    [ "$rc" = 0 ] || { cat "$out/$clock.err"; fail "$clock exited $rc"; }
    grep -q "app stop reason=seconds" "$out/$clock.log" ||
        { cat "$out/$clock.err"; fail "$clock: the run did not end by --seconds"; }
    grep -q "INDEX.txt:31: .*the recorded time jumps 1000.0 s ahead" "$out/$clock.err" ||
        { cat "$out/$clock.err"; fail "$clock: the jump was not reported at INDEX.txt:31"; }
    echo "ok: --clock $clock: ended in $took s: $(grep -m1 'recorded time jumps' "$out/$clock.err")"
done

#!/usr/bin/env bash
# The event log is the box's memory (issue 18): a log that cannot be
# written must say so on stderr and in the exit code, never "event log
# written"; and a log that cannot be opened must not leak the coach's clip
# (LeakSanitizer on: the early return happens before Mesa is loaded).
#   check_event_log.sh EMULATOR|"" BUILD_DIR OUT_DIR
set -uo pipefail
emu=$1 build=$2 out=$3
# shellcheck source=box_check_common.sh
. "$(dirname "$0")/box_check_common.sh"
crashed() { [ "$1" -ge 128 ] || grep -qE "AddressSanitizer|LeakSanitizer|runtime error" "$2"; }

# /dev/full: every write fails with ENOSPC, as on a full SD card.
[ -w /dev/full ] || { echo "SKIP: no /dev/full"; exit 77; }
ASAN_OPTIONS=detect_leaks=0 timeout 60 $emu "$bin" --headless "${view[@]}" --depth off --clock virtual \
    --seconds 0.5 --log /dev/full >"$out/full.out" 2>"$out/full.err"
rc=$?
cat "$out/full.out" "$out/full.err"
crashed "$rc" "$out/full.err" && fail "--log /dev/full crashed (exit $rc)"
[ "$rc" != 0 ] || fail "--log /dev/full exited 0"
grep -q "event log written" "$out/full.out" && fail "--log /dev/full claims the log was written"
grep -q "^cubdance: cannot write the event log /dev/full: No space left on device" "$out/full.err" ||
    fail "--log /dev/full: no message naming the log and the reason"
grep -qE "^cubdance: the event log /dev/full is incomplete: [0-9]+ lines? lost" "$out/full.err" ||
    fail "--log /dev/full: no count of the lost lines"
echo "ok: --log /dev/full -> exit $rc"

# A good log still ends with exit 0 and its line.
ASAN_OPTIONS=detect_leaks=0 timeout 60 $emu "$bin" --headless "${view[@]}" --depth off --clock virtual \
    --seconds 0.5 --log "$out/good.log" >"$out/good.out" 2>"$out/good.err"
rc=$?
[ "$rc" = 0 ] || { cat "$out/good.err"; fail "a writable log exited $rc"; }
grep -q "event log written to $out/good.log" "$out/good.out" || fail "no 'event log written' line"
[ -s "$out/good.log" ] || fail "the good log is empty"
echo "ok: a writable log -> exit 0"

# An unwritable path: a clear message, exit 1, and no leak.
ASAN_OPTIONS=detect_leaks=1 timeout 60 $emu "$bin" --headless "${view[@]}" --depth off --clock virtual \
    --seconds 0.5 --log "$out/no/such/dir/log.txt" >"$out/nodir.out" 2>"$out/nodir.err"
rc=$?
cat "$out/nodir.err"
crashed "$rc" "$out/nodir.err" && fail "an unwritable --log leaked or crashed (exit $rc)"
[ "$rc" = 1 ] || fail "an unwritable --log exited $rc, want 1"
grep -q "^cubdance: cannot write the event log $out/no/such/dir/log.txt: No such file or directory" \
    "$out/nodir.err" || fail "an unwritable --log: no message"
echo "ok: an unwritable --log -> exit 1, no leak"

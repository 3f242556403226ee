#!/usr/bin/env bash
# Replay pacing under --clock virtual with bad recorded timestamps (issue
# 18): a timestamp that steps back was taken modulo 2^32 as a 71.5 s wait
# per step, and one that jumps far ahead as that long a pause, so the box
# called the camera lost. Both are now taken as one frame's step, said once
# on stderr; the camera stays.
#   check_dump_time.sh EMULATOR|"" BUILD_DIR OUT_DIR
set -uo pipefail
emu=$1 build=$2 out=$3
# shellcheck source=box_check_common.sh
. "$(dirname "$0")/box_check_common.sh"

# make_dump DIR KIND: 90 frames at 30 fps by their names; the Kinect
# timestamps step back to the start (back) or jump 30 s ahead (jump) at 1 s.
make_dump() {
    local d=$1 kind=$2 k ts n
    mkdir -p "$d"
    { printf 'P5 640 480 65535\n'; head -c 614400 /dev/zero; } > "$d/frame.pgm"
    for k in $(seq 0 89); do
        ts=$((1000000 + 2000000 * k))
        if ((k >= 30)); then
            [ "$kind" = back ] && ts=$((1000000 + 2000000 * (k - 30)))
            [ "$kind" = jump ] && ts=$((ts + 1800000000))
        fi
        n=$(printf 'd-%d.%06d-%d.pgm' $((1300000000 + k / 30)) $(((k % 30) * 1000000 / 30)) "$ts")
        ln -s frame.pgm "$d/$n"
        echo "$n" >> "$d/INDEX.txt"
    done
}

for kind in back jump; do
    make_dump "$out/$kind" "$kind"
    FAKENECT_PATH="$out/$kind" LD_LIBRARY_PATH="$fakenect_libs" \
        timeout $((60 * slow)) $emu "$bin" --headless "${view[@]}" --clock virtual --seconds 2.5 \
        --replay "$out/$kind" \
        --log "$out/$kind.log" >"$out/$kind.out" 2>"$out/$kind.err"
    rc=$?
    [ "$rc" != 124 ] || fail "$kind: hung"
    if [ "$rc" -ge 128 ] || grep -qE "AddressSanitizer|runtime error" "$out/$kind.err"; then
        cat "$out/$kind.err"; fail "$kind crashed (exit $rc)"
    fi
    [ "$rc" = 0 ] || { cat "$out/$kind.err"; fail "$kind exited $rc"; }
    grep -q "camera state=lost" "$out/$kind.log" &&
        fail "$kind: the camera was called lost: $(grep -m1 'camera state=lost' "$out/$kind.log")"
    grep -q "depth: replay: the frame timestamp .*taken as one frame's step" "$out/$kind.err" ||
        { cat "$out/$kind.err"; fail "$kind: not reported on stderr"; }
    echo "ok: timestamps that $kind: $(grep -m1 'depth: replay' "$out/$kind.err")"
done

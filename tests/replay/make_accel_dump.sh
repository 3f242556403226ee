#!/usr/bin/env bash
# Make a fakenect dump shaped like one fakenect-record writes from a live
# Kinect: the 8 real Skeltrack frames cycled at 30 fps for FRAMES frames,
# each depth frame followed by accelerometer lines and a colour frame, in
# the order fakenect-record writes them (it snapshots the accelerometer
# after every libusb event, so a- lines come several per frame, named with
# the last frame's timestamp):
#   d-t  a-t+1ms  a-t+9ms  r-t+12ms  a-t+13ms  a-t+21ms  a-t+29ms
# An a- file is libfreenect's freenect_raw_tilt_state (12 bytes: int16 x y
# z little-endian, int8 tilt angle, a pad byte, int32 tilt status): here a
# level camera, 0 819 0 (1 g up on y), angle 0, stopped. Depth frames are
# symbolic links to the real files; the one colour frame and the one
# accelerometer file are written once and linked.
#   make_accel_dump.sh SRC_DUMP OUT_DIR [FRAMES]
# Exits 77 (skip) when the source dump is absent.
set -euo pipefail
src=$1 out=$2 count=${3:-98}
. "$(dirname "$0")/../scenario/dump_common.sh"
read_source_frames "$src"
rm -rf "$out"
mkdir -p "$out/once"
{ printf 'P6 640 480 255\n'; head -c 921600 /dev/zero; } > "$out/once/colour.ppm"
printf '\x00\x00\x33\x03\x00\x00\x00\x00\x00\x00\x00\x00' > "$out/once/level.dump"
real_src=$(cd "$src" && pwd)
# name KIND MS_AFTER_FRAME K TIMESTAMP EXT: a fakenect name MS_AFTER_FRAME
# milliseconds after frame K's time.
name_at() {
    local us=$((($4 % 30) * 1000000 / 30 + $2 * 1000))
    printf '%s-%d.%06d-%d.%s' "$1" $((1300000000 + $4 / 30 + us / 1000000)) $((us % 1000000)) \
        "$3" "$5"
}
: > "$out/INDEX.txt"
for ((k = 0; k < count; k++)); do
    depth=$(frame_name "$k")
    ts=$((1000000 + 2000000 * k)) rgb_ts=$((1000000 + 2000000 * k + 700000))
    lines=("$depth" "$(name_at a 1 "$ts" "$k" dump)" "$(name_at a 9 "$ts" "$k" dump)"
        "$(name_at r 12 "$rgb_ts" "$k" ppm)" "$(name_at a 13 "$rgb_ts" "$k" dump)"
        "$(name_at a 21 "$rgb_ts" "$k" dump)" "$(name_at a 29 "$rgb_ts" "$k" dump)")
    ln -s "$real_src/${frames[k % ${#frames[@]}]}" "$out/$depth"
    for name in "${lines[@]:1}"; do
        case $name in
        a-*) ln -s once/level.dump "$out/$name" ;;
        r-*) ln -s once/colour.ppm "$out/$name" ;;
        esac
    done
    printf '%s\n' "${lines[@]}" >> "$out/INDEX.txt"
done
echo "accel dump: $count depth frames, $(grep -c '^a-' "$out/INDEX.txt") accelerometer and" \
    "$(grep -c '^r-' "$out/INDEX.txt") colour lines in $out"

#!/usr/bin/env bash
# Make a fakenect dump of a camera that stops mid-song and comes back: the 8
# real Skeltrack frames, cycled at 30 fps from 0 to GAP_FROM s, nothing
# until GAP_TO s, then again until END s. The frames are symbolic links to
# the real files (nothing is copied); the names carry the new times, which
# fakenect and the board's replay pacing read.
#   make_gap_dump.sh SRC_DUMP OUT_DIR [GAP_FROM GAP_TO END]
# Exits 77 (skip) when the source dump is absent.
set -euo pipefail
src=$1 out=$2 gap_from=${3:-7} gap_to=${4:-10} end=${5:-13}
if [ ! -f "$src/INDEX.txt" ]; then
    echo "SKIP: no fakenect dump at $src"
    exit 77
fi
mapfile -t frames < <(grep '^d-' "$src/INDEX.txt")
rm -rf "$out"
mkdir -p "$out"
: > "$out/INDEX.txt"
k=0
# frame k at k/30 s; the Kinect's 60 MHz timestamp is 2,000,000 a frame
for ((k = 0; k < end * 30; k++)); do
    if ((k >= gap_from * 30 && k < gap_to * 30)); then continue; fi
    t=$(printf '%d.%06d' $((1300000000 + k / 30)) $(((k % 30) * 1000000 / 30)))
    name="d-$t-$((1000000 + 2000000 * k)).pgm"
    ln -s "$(cd "$src" && pwd)/${frames[k % ${#frames[@]}]}" "$out/$name"
    echo "$name" >> "$out/INDEX.txt"
done
echo "gap dump: $(wc -l < "$out/INDEX.txt") frames in $out (no frames from $gap_from s to $gap_to s)"

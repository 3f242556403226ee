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
. "$(dirname "$0")/dump_common.sh"
read_source_frames "$src"
rm -rf "$out"
mkdir -p "$out"
: > "$out/INDEX.txt"
for ((k = 0; k < end * 30; k++)); do
    if ((k >= gap_from * 30 && k < gap_to * 30)); then continue; fi
    name=$(frame_name "$k")
    ln -s "$(cd "$src" && pwd)/${frames[k % ${#frames[@]}]}" "$out/$name"
    echo "$name" >> "$out/INDEX.txt"
done
echo "gap dump: $(wc -l < "$out/INDEX.txt") frames in $out (no frames from $gap_from s to $gap_to s)"

#!/usr/bin/env bash
# Make a fakenect dump with garbage in it: the 8 real Skeltrack frames
# cycled at 30 fps for 2 s, then 1 s of frames with no reading at all
# (2047 everywhere), 1 s of all zeros, 1 s of random values (seeded: the
# same every run), then 3 s of the real frames again, where the frame at
# 6.0 s is truncated (a real frame's first 1234 bytes) and the one at 6.5 s
# is missing (named in INDEX.txt, no file): the box replays both as frames
# without readings. Real frames are symbolic links; the garbage frames are
# written once and linked.
#   make_garbage_dump.sh SRC_DUMP OUT_DIR
# Exits 77 (skip) when the source dump is absent.
set -euo pipefail
src=$1 out=$2
. "$(dirname "$0")/dump_common.sh"
read_source_frames "$src"
rm -rf "$out"
mkdir -p "$out/garbage"
header='P5 640 480 65535\n'
{ printf "$header"; perl -e 'print pack("v", 2047) x 307200'; } > "$out/garbage/none.pgm"
{ printf "$header"; head -c 614400 /dev/zero; } > "$out/garbage/zeros.pgm"
{ printf "$header"; perl -e 'srand(7); print pack("v*", map { int(rand(65536)) } 1 .. 307200)'; } \
    > "$out/garbage/random.pgm"
head -c 1234 "$src/${frames[180 % ${#frames[@]}]}" > "$out/garbage/truncated.pgm"
: > "$out/INDEX.txt"
for ((k = 0; k < 8 * 30; k++)); do
    case $((k / 30)) in
    2) target="$out/garbage/none.pgm" ;;
    3) target="$out/garbage/zeros.pgm" ;;
    4) target="$out/garbage/random.pgm" ;;
    *) target="$(cd "$src" && pwd)/${frames[k % ${#frames[@]}]}" ;;
    esac
    [ "$k" -eq 180 ] && target="$out/garbage/truncated.pgm"
    name=$(frame_name "$k")
    if [ "$k" -ne 195 ]; then
        ln -s "$(cd "$(dirname "$target")" && pwd)/$(basename "$target")" "$out/$name"
    fi
    echo "$name" >> "$out/INDEX.txt"
done
echo "garbage dump: $(wc -l < "$out/INDEX.txt") frames in $out (2-3 s no reading, 3-4 s zeros," \
    "4-5 s random, 6.0 s truncated, 6.5 s missing)"

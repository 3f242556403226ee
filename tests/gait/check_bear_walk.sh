#!/bin/bash
# The bear's walk clip (assets/clips/bear_walk.bvh) is reproducible and
# walks: `cubtool retarget` of CMU 02_01 (the command below, docs/gait.md
# "The bear's walk") gives the committed file byte for byte, and the walker
# plays it over the shipped forest floor, both feet taking planned
# footholds and no step blocked. Host only (the retargeter's doubles go
# through libm); skipped (77) without the data.
set -u
tool=$1 data=$2 src=$3 out=$4
[ -r "$data/mocap/cmu/02_01.bvh" ] || { echo "skipped: no CMU 02_01 under $data"; exit 77; }
mkdir -p "$out"
"$tool" retarget "$data/mocap/cmu/02_01.bvh" --map "$src/assets/retarget/cmu31.map" \
    --out "$out/bear_walk.bvh" 2>/dev/null || exit 1
cmp "$out/bear_walk.bvh" "$src/assets/clips/bear_walk.bvh" ||
    { echo "FAIL: the rebuilt walk differs from assets/clips/bear_walk.bvh"; exit 1; }
"$tool" gait "$src/assets/clips/bear_walk.bvh" --terrain "$src/assets/floor/forest.floor" \
    --frames "$out/frames" --count 180 >"$out/events.txt" || exit 1
left=$(grep -c "left taken" "$out/events.txt") right=$(grep -c "right taken" "$out/events.txt")
echo "bear walk: 180 frames, left taken $left, right taken $right, blocked $(grep -c blocked "$out/events.txt")"
[ "$left" -ge 4 ] && [ "$right" -ge 4 ] || { echo "FAIL: too few steps taken"; exit 1; }
! grep -q blocked "$out/events.txt" || { echo "FAIL: a step was blocked"; exit 1; }
echo "bear walk: identical, walks"

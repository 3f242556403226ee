#!/bin/sh
# A child 0.6-0.7 m from the camera (issue 20 point 9): on renders of a
# child that near (standing, bending toward the box, dancing; an adult
# behind in the room), the tracker never reports the player OK (the judge
# gives verdicts only on OK frames) and says TOO_CLOSE (the judge's "too
# close", the coach's "Step back") in at least 9 frames of 10 (skipped,
# 77, without the clips):
#   check_too_close.sh CUBTOOL DATA_DIR OUT_DIR
set -eu
TOOL=$1 DATA=$2 OUT=$3
for c in cmu/13_29.bvh cmu/05_06.bvh bandai/data/dataset-1_bow_normal_001.bvh; do
    [ -r "$DATA/mocap/$c" ] || { echo "too-close check: no $c under $DATA/mocap, skipped"; exit 77; }
done
rm -rf "$OUT"
mkdir -p "$OUT"
status=0
check() { # name synth-depth args...
    name=$1
    shift
    "$TOOL" synth-depth "$@" --pin --seed 1 --frames 20 --fps 10 --data "$DATA" --out "$OUT/$name" >/dev/null 2>&1 ||
        { echo "too-close check: synth-depth failed for $name" >&2; exit 1; }
    line=$("$TOOL" eval-track "$OUT/$name" | grep '^eval-track: frames=')
    echo "too-close check: $name: $line"
    ok=$(echo "$line" | sed 's/.* ok=\([0-9]*\).*/\1/') close=$(echo "$line" | sed 's/.* too_close=\([0-9]*\).*/\1/')
    [ "$ok" = 0 ] || { echo "too-close check: $name: $ok frames OK (judged)" >&2; status=1; }
    [ $((close * 10)) -ge 180 ] || { echo "too-close check: $name: only $close of 20 frames too close" >&2; status=1; }
}
check standing_adult_behind --clip 13_29 --distance 650 --room --second-person 13_29
check bending_small --clip dataset-1_bow_normal_001 --distance 600 --loose-clothes --height 1000
check dancing_adult_behind --clip 05_06 --distance 700 --room --second-person 13_29
exit $status

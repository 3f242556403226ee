#!/bin/sh
# cubtool eval-track's facing bands and wrong-person count on small real
# renders (skipped, 77, without the CMU clips):
#   check_eval_track.sh CUBTOOL DATA_DIR OUT_DIR
# - a child turned by --yaw 180 scores every frame in band yaw120-180, one
#   turned by 45 in yaw30-60, and the band rows add up to the whole;
# - with a sibling (truth_second.txt), the frames whose player is the wrong
#   person plus those counted with the two truths swapped are exactly the
#   frames with a tracked player: each frame is the one person or the other;
# - the confidence table counts the joints --joints lists as confident.
set -eu
TOOL=$1 DATA=$2 OUT=$3
[ -r "$DATA/mocap/cmu/13_29.bvh" ] || { echo "eval-track check: no CMU clips under $DATA, skipped"; exit 77; }
rm -rf "$OUT"
mkdir -p "$OUT"
fail() { echo "eval-track check: $*" >&2; exit 1; }
row() { # csv kind band joint -> n
    awk -F, -v k="$2" -v b="$3" -v j="$4" '$1 == k && $2 == b && $3 == j { print $4 }' "$1"
}

for case in "180 yaw120-180" "45 yaw30-60"; do
    set -- $case
    "$TOOL" synth-depth --clip 13_29 --frames 6 --fps 10 --clean --yaw "$1" --data "$DATA" --out "$OUT/yaw$1" >/dev/null 2>&1
    "$TOOL" eval-track "$OUT/yaw$1" --csv "$OUT/yaw$1.csv" >"$OUT/yaw$1.txt"
    [ "$(row "$OUT/yaw$1.csv" frames "$2" all)" = 6 ] || fail "yaw $1: not 6 frames in band $2: $(grep ^frames "$OUT/yaw$1.csv" | tr '\n' ' ')"
    grep -q "band $2 " "$OUT/yaw$1.txt" || fail "yaw $1: no band $2 line"
    sum=$(awk -F, '$1 == "joint" && $2 != "all" && $3 == "all" { s += $4 } END { print s }' "$OUT/yaw$1.csv")
    [ "$sum" = "$(row "$OUT/yaw$1.csv" joint all all)" ] || fail "yaw $1: bands hold $sum joints, the whole $(row "$OUT/yaw$1.csv" joint all all)"
    grep -q "wrong person" "$OUT/yaw$1.txt" && fail "yaw $1: a wrong-person count without a second person"
    echo "eval-track check: yaw $1: 6 frames in $2"
done

# the confidence table: the confident joints it counts are those --joints
# lists at confidence >= CUB_TRACK_CONFIDENT (half, 32768), and so are
# their joints within 10 cm; a child facing the camera on the spot has some
d=$OUT/facing
"$TOOL" synth-depth --clip 13_29 --frames 6 --fps 10 --clean --pin --data "$DATA" --out "$d" >/dev/null 2>&1
"$TOOL" eval-track "$d" --csv "$OUT/facing.csv" --joints "$OUT/facing_joints.csv" >"$OUT/facing.txt"
grep "of joints confident" "$OUT/facing.txt" || fail "facing: no confidence line"
cn=$(row "$OUT/facing.csv" confident all all)
cw=$(awk -F, '$1 == "confident" && $2 == "all" && $3 == "all" { print $5 }' "$OUT/facing.csv")
jn=$(awk -F, 'NR > 1 && $4 >= 32768' "$OUT/facing_joints.csv" | wc -l)
jw=$(awk -F, 'NR > 1 && $4 >= 32768 && $7 == 1' "$OUT/facing_joints.csv" | wc -l)
[ "$cn" = "$jn" ] && [ "$cw" = "$jw" ] || fail "facing: confident $cn ($cw within) in the csv, $jn ($jw) in --joints"
[ "$cn" -gt 0 ] || fail "facing: no joint confident"
[ "$(awk -F, 'NR > 1' "$OUT/facing_joints.csv" | wc -l)" = "$(row "$OUT/facing.csv" joint all all)" ] ||
    fail "facing: --joints rows are not the joints scored"

d=$OUT/sibling
"$TOOL" synth-depth --clip 13_29 --frames 12 --fps 10 --clean --second-person 13_29 --second-mode sibling \
    --data "$DATA" --out "$d" >/dev/null 2>&1
[ -f "$d/truth_second.txt" ] || fail "no truth_second.txt beside a second person"
"$TOOL" eval-track "$d" --csv "$OUT/sibling.csv" >"$OUT/sibling.txt"
grep "wrong person" "$OUT/sibling.txt"
# the same frames with the two truths swapped
s=$OUT/swapped
mkdir -p "$s"
for f in "$d"/*; do ln -s "$f" "$s/"; done
rm "$s/truth.txt" "$s/truth_second.txt"
cp "$d/truth_second.txt" "$s/truth.txt"
cp "$d/truth.txt" "$s/truth_second.txt"
"$TOOL" eval-track "$s" --csv "$OUT/swapped.csv" >/dev/null
w=$(row "$OUT/sibling.csv" wrong_person all all)
ws=$(row "$OUT/swapped.csv" wrong_person all all)
n=$(row "$OUT/sibling.csv" second all all)
echo "eval-track check: sibling: wrong person $w of $n frames, swapped truths $ws"
[ "$n" = 12 ] || fail "sibling: $n of 12 frames with a player and a second person"
[ $((w + ws)) = "$n" ] || fail "sibling: wrong $w + swapped $ws is not the $n frames"
[ "$ws" -gt 0 ] || fail "swapped truths counted no wrong person"

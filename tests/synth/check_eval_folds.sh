#!/bin/sh
# The held-out protocol's quick sample (scripts/eval_folds.sh --quick: 3
# folds x 5 scenes x 8 frames) runs end to end and prints every fold, the
# dev and held-out totals, every scene and every joint, each with a share
# within 10 cm, and the confidence tables (skipped, 77, without the shared
# mocap):
#   check_eval_folds.sh SOURCE_DIR BUILD_DIR DATA_DIR
set -eu
SRC=$1 BUILD=$2 DATA=$3
[ -d "$DATA/mocap/bandai" ] && [ -d "$DATA/mocap/cmu" ] || { echo "eval_folds check: no mocap under $DATA, skipped"; exit 77; }
out=$(CUB_DATA_DIR=$DATA sh "$SRC/scripts/eval_folds.sh" "$BUILD" --quick | grep -v '^+ ')
echo "$out"
fail() { echo "eval_folds check: $*" >&2; exit 1; }
for r in "cmu14  *dev  *5  *40 " "animdraw  *dev  *5  *40 " "bandai_childish  *heldout  *5  *40 " \
    "dev folds  *dev  *10  *80 " "held-out folds  *heldout  *5  *40 " "all folds  *15  *120 " \
    "scene facing " "scene turning " "scene travel " "scene second " "scene loose " "joint hand_l " "joint foot_r "; do
    echo "$out" | grep -Eq "^$r.* [0-9]+\.[0-9]%" || fail "no row '$r' with a figure"
done
# the second-person renders: one per fold, 8 frames each with a player
echo "$out" | grep -Eq "^scene second .* [0-9]+/24 *$" || fail "the second-person scene does not count 24 frames"
# the confidence: a table per fold and the summary by fold and set
for f in cmu14 animdraw bandai_childish; do
    echo "$out" | grep -q "^confidence, fold $f " || fail "no confidence table for fold $f"
done
for r in "hand_l" "all" "dev folds" "held-out folds" "all folds"; do
    echo "$out" | grep -Eq "^  $r  *[0-9]+ .*%" || fail "no confidence row '$r'"
done

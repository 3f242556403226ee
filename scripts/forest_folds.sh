#!/bin/sh
# The body-part forest, leave one source out (docs/tracker_eval.md point 3,
# docs/forest.md): for every shippable fold F, a forest trained on the other
# shippable folds (cubtool train-forest --all-but F) is scored on F's clips
# rendered with another seed (other yaws and travel) by cubtool
# eval-forest; every fold's per-part table is printed.
#   scripts/forest_folds.sh BUILD_DIR [OUT_DIR] [train-forest options]
# e.g. scripts/forest_folds.sh build/release /tmp/forest --trees 3 --depth 16
set -eu
[ $# -ge 1 ] || { echo "usage: scripts/forest_folds.sh BUILD_DIR [OUT_DIR] [train-forest options]" >&2; exit 2; }
TOOL=$1/app/cubtool/cubtool
OUT=${2:-/tmp/cub_forest_folds}
[ $# -ge 2 ] && shift 2 || shift 1
mkdir -p "$OUT"
for fold in cmu13 cmu14 cmu_walks cmu_dance_sport animdraw; do
    echo "== fold $fold (trained on the other four, seed 1; scored with seed 2)"
    "$TOOL" train-forest --all-but "$fold" --seed 1 --out "$OUT/$fold.forest" "$@"
    "$TOOL" eval-forest --forest "$OUT/$fold.forest" --fold "$fold" --seed 2
done

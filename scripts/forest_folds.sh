#!/bin/sh
# The body-part forest, leave one source out (docs/tracker_eval.md point 3,
# docs/forest.md): for every shippable fold F, a forest trained on the other
# shippable folds (cubtool train-forest --all-but F) is scored on F's clips
# rendered with another seed (other yaws and travel) by cubtool
# eval-forest; every fold's per-part table is printed.
#   scripts/forest_folds.sh BUILD_DIR [OUT_DIR] [--vs-tracker] [train-forest options]
# With --vs-tracker, every fold's forest is instead scored joint by joint
# against the heuristic tracker on the same renders (eval-forest
# --vs-tracker), and one table adds up all five folds.
# FOREST_REUSE=1 keeps the forests already in OUT_DIR (scoring again only).
# e.g. scripts/forest_folds.sh build/release /tmp/forest --trees 3 --depth 16
set -eu
[ $# -ge 1 ] || { echo "usage: scripts/forest_folds.sh BUILD_DIR [OUT_DIR] [--vs-tracker] [train-forest options]" >&2; exit 2; }
TOOL=$1/app/cubtool/cubtool
OUT=${2:-/tmp/cub_forest_folds}
[ $# -ge 2 ] && shift 2 || shift 1
VS=
if [ "${1:-}" = --vs-tracker ]; then VS=--vs-tracker; shift; fi
mkdir -p "$OUT"
for fold in cmu13 cmu14 cmu_walks cmu_dance_sport animdraw; do
    echo "== fold $fold (trained on the other four, seed 1; scored with seed 2)"
    [ -s "$OUT/$fold.forest" ] && [ -n "${FOREST_REUSE:-}" ] ||
        "$TOOL" train-forest --all-but "$fold" --seed 1 --out "$OUT/$fold.forest" "$@"
    if [ -z "$VS" ]; then
        "$TOOL" eval-forest --forest "$OUT/$fold.forest" --fold "$fold" --seed 2
    else
        "$TOOL" eval-forest --forest "$OUT/$fold.forest" --fold "$fold" --seed 2 --vs-tracker \
            > "$OUT/$fold.vs"
        grep -E "^(joint|forest's|all) " "$OUT/$fold.vs"
    fi
done
[ -n "$VS" ] || exit 0
echo "== all five folds, each scored by the forest that did not train on it"
cat "$OUT"/cmu13.vs "$OUT"/cmu14.vs "$OUT"/cmu_walks.vs "$OUT"/cmu_dance_sport.vs \
    "$OUT"/animdraw.vs | awk '
function pc(a, n) { return n ? sprintf("%6.1f%%", 100 * a / n) : "     -" }
$1 == "vs" {
    j = $2; if (!(j in seen)) { seen[j] = 1; order[++nj] = j }
    for (k = 0; k < 8; k++) c[j, k] += $(k + 3)
}
END {
    printf "%-15s %6s %7s %7s %8s %8s %7s %7s %7s\n", "joint", "n", "tracker", "forest",
        "combined", "override", "guessed", "f.conf", "f.conf+"
    for (i = 1; i <= nj; i++) {
        j = order[i]
        printf "%-15s %6d %7s %7s %8s %8s %7s %7s %7s\n", j, c[j, 0], pc(c[j, 1], c[j, 0]),
            pc(c[j, 2], c[j, 0]), pc(c[j, 3], c[j, 0]), pc(c[j, 4], c[j, 0]),
            pc(c[j, 5], c[j, 0]), pc(c[j, 6], c[j, 0]), pc(c[j, 7], c[j, 6])
        for (k = 0; k < 8; k++) {
            t[k] += c[j, k]
            if (j ~ /^(head|hand_|foot_|elbow_|knee_)/) f[k] += c[j, k]
        }
    }
    printf "%-15s %6d %7s %7s %8s %8s %7s %7s %7s\n", "forest'"'"'s", f[0], pc(f[1], f[0]),
        pc(f[2], f[0]), pc(f[3], f[0]), pc(f[4], f[0]), pc(f[5], f[0]), pc(f[6], f[0]),
        pc(f[7], f[6])
    printf "%-15s %6d %7s %7s %8s %8s %7s %7s %7s\n", "all", t[0], pc(t[1], t[0]),
        pc(t[2], t[0]), pc(t[3], t[0]), pc(t[4], t[0]), pc(t[5], t[0]), pc(t[6], t[0]),
        pc(t[7], t[6])
}'

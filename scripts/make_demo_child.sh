#!/usr/bin/env bash
# The demo's child as a joint track (scripts/child/twinkle.jtrack): what
# scripts/demo.sh renders, so that the demo needs nothing beside the clone.
# Made from ../shared/data's motion capture (CMU and AnimatedDrawings only,
# both shippable) by the same steps as scripts/e2e_child.sh: make_child.py
# cuts the planted child's performance from scripts/child/twinkle.plan,
# following scripts/child/twinkle.cues, and `cubtool synth-depth
# --write-track` writes its points on its default 0.25 mm grid (251 kB).
#
# The grid moves the rendered depth's noise (the Kinect model draws its
# jitter pixel after pixel, so one pixel's change shifts the rest), so the
# box's log from the track need not be e2e_child.sh's from the clips (it
# once resumed boxing 0.17 s sooner; since the slower demonstration is
# watched the requests are the same). What the coach does with the track
# is scripts/child/twinkle_demo.cues, which the demo scores against; after
# a change of the box (and of twinkle.cues: rebuild this file first),
# renew it from a demo run:
#   scripts/demo.sh && grep ' coach request ' out/demo/events.log \
#       > scripts/child/twinkle_demo.cues
#
#   scripts/make_demo_child.sh [--check] [--tool CUBTOOL]
#
# --check: rebuild it in a temporary folder and compare it with the shipped
# file (exit 1 when they differ: re-run without --check and commit);
# exit 77 without the motion capture ($CUB_DATA_DIR or ../shared/data).
# CUBTOOL defaults to build/release/app/cubtool/cubtool.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
check=0 tool=$root/build/release/app/cubtool/cubtool
while [ $# -gt 0 ]; do
    case $1 in
        --check) check=1 ;;
        --tool) [ $# -ge 2 ] || { echo "usage: $0 [--check] [--tool CUBTOOL]" >&2; exit 2; }
                tool=$2; shift ;;
        *) echo "usage: $0 [--check] [--tool CUBTOOL]" >&2; exit 2 ;;
    esac
    shift
done
data=${CUB_DATA_DIR:-$root/../shared/data}
shipped=$here/child/twinkle.jtrack
if [ ! -d "$data/mocap" ]; then
    echo "SKIP: make_demo_child: no motion capture under $data (set CUB_DATA_DIR)"
    exit 77
fi
[ -x "$tool" ] || { echo "make_demo_child: no $tool (build cubtool)" >&2; exit 1; }
work=$(mktemp -d "${TMPDIR:-/tmp}/demo_child.XXXXXX")
trap 'rm -rf "$work"' EXIT INT TERM

python3 "$here/make_child.py" sequence "$root/assets/songs/twinkle.song.xml" \
    "$here/child/twinkle.plan" "$work" "$here/child/twinkle.cues" >/dev/null
"$tool" synth-depth --sequence "$work/child.seq" --data "$data" \
    --write-track "$work/track" >/dev/null
{
    cat <<'HEAD'
# The demo's child (scripts/demo.sh): Twinkle Twinkle Little Star with five
# planted mistakes, as a joint track (format: app/include/cub/synth.h). Made
# by scripts/make_demo_child.sh from scripts/child/twinkle.plan, following
# scripts/child/twinkle.cues, over these motion captures:
# - CMU 13_29, 14_14 (BVH) and 13_17 (ASF/AMC). The data used in this project
#   was obtained from mocap.cs.cmu.edu. The database was created with funding
#   from NSF EIA-0196217.
# - AnimatedDrawings cmu1/jumping_jacks and fair1/wave_hello. Copyright (c)
#   Meta Platforms, Inc. and affiliates; MIT licence, in full in
#   scripts/child/LICENSE.AnimatedDrawings.
HEAD
    grep -v '^#' "$work/track"
} >"$work/twinkle.jtrack"

if [ "$check" = 1 ]; then
    if cmp -s "$work/twinkle.jtrack" "$shipped"; then
        echo "make_demo_child: $shipped is what the plan, the cues and the mocap make" \
             "($(wc -c <"$shipped") bytes)"
        exit 0
    fi
    echo "make_demo_child: $shipped differs from a rebuild (the plan, the cues, the mocap" \
         "or synth-depth changed): re-run scripts/make_demo_child.sh and commit it" >&2
    exit 1
fi
cp "$work/twinkle.jtrack" "$shipped"
echo "make_demo_child: wrote $shipped ($(wc -c <"$shipped") bytes)"

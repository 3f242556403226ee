#!/bin/sh
# The judge's gestures, leave one subject out (docs/gestures_eval.md): one
# fold per person of the shared MSR Action3D and UTKinect skeletons, each
# fold's clap, wave and leg-out precision and recall on that person alone.
#
#   scripts/eval_gestures.sh BUILD_DIR [--only msr|utk] [--check P]
#
# Reads $CUB_DATA_DIR/skeletons (default ../shared/data beside the
# project). Under a second for every fold; ctest runs it as gesture_folds.
set -eu
build=${1:?usage: scripts/eval_gestures.sh BUILD_DIR [--only msr|utk] [--check P]}
shift
here=$(cd "$(dirname "$0")/.." && pwd)
: "${CUB_DATA_DIR:=$here/../shared/data}"
export CUB_DATA_DIR
exec "$build/tests/judge/gesture_folds" "$@"

#!/bin/bash
# cubtool gait-eval on the tuning clip (CMU 02_01) with its sanity bounds
# (--check: penetration, slide, clearance, foot turn, flat error, steps),
# and cubtool gait's refusals of bad input (a terrain file too). Skipped (77)
# without the data.
set -u
tool=$1 data=$2 out=$3
[ -r "$data/mocap/cmu/02_01.bvh" ] || { echo "skipped: no CMU 02_01 under $data"; exit 77; }
"$tool" gait-eval --clips 02_01 --frames 480 --data "$data" --check || exit 1
fail=0
refuse() { # expected exit code, a word the message must hold, the arguments
    local want=$1 word=$2
    shift 2
    local msg
    msg=$("$tool" gait "$@" 2>&1 >/dev/null)
    local rc=$?
    if [ $rc -ne "$want" ] || ! grep -q -- "$word" <<<"$msg"; then
        echo "FAIL: cubtool gait $*: exit $rc, said: $msg"
        fail=1
    fi
}
refuse 1 "no such file" nosuch_clip --data "$data" --frames "$out"
refuse 2 "unknown terrain" 02_01 --data "$data" --terrain lava --frames "$out"
refuse 2 "unknown obstacle" 02_01 --data "$data" --obstacle tree --frames "$out"
refuse 2 "--frames" 02_01 --data "$data"
# A floor file (the box's format): a bad one is refused at its line, a
# good one walked on, the shipped forest floor too.
mkdir -p "$out"
printf 'cubfloor 1\ngrid 2 2 500 -500 0\nrow 0 0\nrow 0 oops\n' >"$out/bad.floor"
refuse 1 "bad.floor:4: height 'oops' is not a whole number" 02_01 --data "$data" --terrain "$out/bad.floor" --frames "$out"
printf 'cubfloor 1\ngrid 2 2 500 -500 0\nrow 0 0\n' >"$out/short.floor"
refuse 1 "1 rows, the grid has NZ = 2" 02_01 --data "$data" --terrain "$out/short.floor" --frames "$out"
printf '# a ramp and a stone\ncubfloor 1\ngrid 2 2 4000 -4000 -2000\nrow 0 0\nrow 300 300\nstone 0 1500 80 80 70\n' >"$out/ramp.floor"
"$tool" gait 02_01 --data "$data" --terrain "$out/ramp.floor" --frames "$out/ramp" --count 3 >/dev/null || fail=1
forest="$(dirname "$0")/../../assets/floor/forest.floor"
"$tool" gait 02_01 --data "$data" --terrain "$forest" --frames "$out/forest" --count 3 >/dev/null || fail=1
[ -s "$out/forest/frame_0002.png" ] || { echo "FAIL: no frames on the forest floor"; fail=1; }
[ -s "$out/ramp/frame_0002.png" ] || { echo "FAIL: no frames from a terrain file"; fail=1; }
exit $fail

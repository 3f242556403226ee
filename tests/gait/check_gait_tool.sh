#!/bin/bash
# cubtool gait-eval on the tuning clip (CMU 02_01) with its sanity bounds
# (--check: penetration, slide, clearance, foot turn, flat error, steps),
# and cubtool gait's refusals of bad input. Skipped (77) without the data.
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
exit $fail

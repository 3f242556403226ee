#!/bin/sh
# The tracker's accuracy protocol (issue 5): share of joints within 10 cm on
# synthetic Kinect depth of clips the tracker was NOT tuned on.
#
#   scripts/eval_tracker.sh BUILD_DIR [--tuning|--heldout2|--heldout3] [--mirror]
#
# --mirror renders every clip of the set with left and right swapped (the
# child does the mirror image; the truth still names the child's own left).
# A tracker with no bias of its own gives the same figure with left and right
# joints exchanged; on the tuning set it doubles what decisions rest on.
#
# Held-out set (default): Bandai Namco Research Motiondataset-1 clips
# (CC BY-NC, ../shared/data/mocap/bandai: for tests and benchmarks only, never
# shipped), motions and styles that keep the child in view, plus one render
# with a furnished room and a second person. NEVER tune on these: change the
# tracker against the tuning set (--tuning: CMU and AnimatedDrawings clips,
# plus Bandai takes and styles that are other files than every held-out
# clip), then run this once to measure.
#
# Figures (firmware/track/tracker.c has the details): tuning set 90.2 %
# over 35 clips after round 8 (89.8 % after round 7, 89.4 % after round 6;
# over round 6's 30 clips 90.1 %, 89.9 % after round 5, 88.5 % after round
# 4, 87.0 % before it), held out 90.8 % of joints within 10 cm after round 8
# (89.6 % after round 7, 89.4 % after rounds 5 and 6, 85.5 % after round 3,
# 84.3 %, 81.1 % and 73.4 % before). --heldout2, a second held-out set
# drawn after round 8 and measured once then: 89.7 %. After round 10 (run
# once, no decision taken after it): held out 91.5 %, --heldout2 90.6 %,
# --heldout3 (drawn before round 10) 96.7 %; tuning 91.7 % over 54 clips,
# 91.8 % mirrored (91.1 % and 90.9 % before round 10).
#
# Every clip is rendered with the same seed, 90 frames at 10 fps, into a
# temporary folder (614 KB a frame) that is deleted at the end; set
# EVAL_DUMPS=DIR to keep the renders there and reuse them on the next run.
# Prints the exact commands, per clip the share within 10 cm, overall, and
# per joint over the whole set.
#
# Since issue 20 the protocol is the leave-one-source-out folds of
# docs/tracker_eval.md: `scripts/eval_tracker.sh BUILD_DIR --folds
# [dev|heldout|all] [--quick] [--fold NAME] [--csv FILE]` runs
# scripts/eval_folds.sh. The sets below are the history of rounds 1-10.
set -eu

usage() { echo "usage: scripts/eval_tracker.sh BUILD_DIR [--tuning|--heldout2|--heldout3] [--mirror] | BUILD_DIR --folds [dev|heldout|all] [--quick] [--identity] [--fold NAME] [--scene NAME] [--csv FILE]" >&2; exit 2; }
[ $# -ge 1 ] || usage
if [ "${2:-}" = "--folds" ]; then
    B=$1
    shift 2
    exec sh "$(dirname "$0")/eval_folds.sh" "$B" "$@"
fi
BUILD=$1
shift
SET=heldout
MIRROR=0
for arg in "$@"; do
    case $arg in
    --tuning) SET=tuning ;;
    --heldout2) SET=heldout2 ;;
    --heldout3) SET=heldout3 ;;
    --mirror) MIRROR=1 ;;
    *) usage ;;
    esac
done
PREFIX=$SET
[ "$MIRROR" = 0 ] || PREFIX=mirror-$SET
TOOL=$BUILD/app/cubtool/cubtool
[ -x "$TOOL" ] || { echo "eval_tracker: no cubtool at $TOOL (build the cubtool target)" >&2; exit 1; }
HERE=$(cd "$(dirname "$0")" && pwd)
DATA=${CUB_DATA_DIR:-$HERE/../../shared/data}
[ -d "$DATA/mocap" ] || { echo "eval_tracker: no mocap under $DATA (set CUB_DATA_DIR)" >&2; exit 1; }

# name | synth-depth arguments (besides --out, --data, --seed, --frames, --fps);
# "--segments CLIP FROM TO;CLIP FROM TO;..." is written to a sequence file
# and rendered with --sequence (segments each turned to face the camera);
# "--derived NAME" is the clip NAME derived by scripts/child/twinkle.plan
# (the box's own moves: a mocap clip with some joints' motion amplified)
# Round 4 added dance-like motion (the held-out set's worst clips are a
# dance, one with a room and a second person): CMU 05_06 modern dance
# while in view (it crosses the room), wave_hello and CMU 13_17 boxing
# with a room and a second person walking past, CMU 10_03 soccer kick.
# Round 7 added five more renders not held out, with what the held-out
# set's weak clips do (arms before a turned body, a childish style, an arm
# pointing at the camera): Bandai bow childish, byebye musical and guide
# happy (other styles than every held-out file), CMU 13_18 boxing and
# AnimatedDrawings zombie: 30 -> 35 clips, 90.1 -> 89.4 % with round 6's
# tracker.
# Round 5's walk-in render is not in the list (the child is beyond the
# play range for half of it): 02_01 as a sequence (faces the camera,
# walks 4.7 -> 2.4 m) with --distance 3600 --second-person
# dataset-1_bow_sad_001 --second-x 900 --second-dz 500 --room; an adult
# at 4.1 m was the player for good before round 5.
heldout_set() {
    cat <<'EOF'
bye_childish|--clip dataset-1_bye_childish_001
bye_happy|--clip dataset-1_bye_happy_001
byebye_active|--clip dataset-1_byebye_active_001
byebye_childish|--clip dataset-1_byebye_childish_001
bow_happy|--clip dataset-1_bow_happy_001
guide_active|--clip dataset-1_guide_active_001
guide_childish|--clip dataset-1_guide_childish_001
call|--clip dataset-1_call_normal_001
respond|--clip dataset-1_respond_normal_001
kick|--clip dataset-1_kick_normal_001
punch|--clip dataset-1_punch_normal_001
dance_short|--clip dataset-1_dance-short_normal_001 --from 10
dance_room_2nd|--clip dataset-1_dance-short_normal_001 --from 30 --room --second-person dataset-1_bye_happy_001
EOF
}
# A second held-out set, drawn after round 8 (the first had been measured
# eight times by then, with every decision taken on the tuning set): Bandai
# styles no other set or second person uses, with the same body and room
# variations as the tuning set. Bows, waves and guides only: the held-out
# set's kick, punch and dance have no other files.
heldout2_set() {
    cat <<'EOF'
bow_giant|--clip dataset-1_bow_giant_001
bow_old_small_slim|--clip dataset-1_bow_old_001 --height 1000 --build slim
bye_sad|--clip dataset-1_bye_sad_001
bye_musical_loose|--clip dataset-1_bye_musical_001 --loose
byebye_proud|--clip dataset-1_byebye_proud_001
byebye_angry_sturdy|--clip dataset-1_byebye_angry_001 --build sturdy
guide_musical|--clip dataset-1_guide_musical_001
guide_tired|--clip dataset-1_guide_tired_001
bye_masculinity_room_2nd|--clip dataset-1_bye_masculinity_001 --room --second-person dataset-1_bow_tired_001
guide_chimpira_room_2nd|--clip dataset-1_guide_chimpira_001 --room --second-person 16_11
EOF
}
# A third held-out set, drawn at random (Python's random.Random(15)) before
# round 10 from the 29 bow/bye/byebye/guide style files no set used: ten
# held out here, the other 19 joined the tuning set.
heldout3_set() {
    cat <<'EOF'
bow_feminine|--clip dataset-1_bow_feminine_001
bye_feminine_small_slim|--clip dataset-1_bye_feminine_001 --height 1000 --build slim
bye_giant|--clip dataset-1_bye_giant_001
bye_proud_loose|--clip dataset-1_bye_proud_001 --loose
bye_tired|--clip dataset-1_bye_tired_001
byebye_chimpira_sturdy|--clip dataset-1_byebye_chimpira_001 --build sturdy
byebye_giant|--clip dataset-1_byebye_giant_001
byebye_sad|--clip dataset-1_byebye_sad_001
byebye_tired_room_2nd|--clip dataset-1_byebye_tired_001 --room --second-person 02_01
guide_old|--clip dataset-1_guide_old_001
EOF
}
tuning_set() {
    cat <<'EOF'
13_29|--clip 13_29
14_14|--clip 14_14
141_16|--clip 141_16
02_01|--clip 02_01
jumping_jacks|--clip jumping_jacks
141_16_room_2nd|--clip 141_16 --room --second-person 13_29
13_29_small_slim|--clip 13_29 --height 1000 --build slim
14_14_tall_loose|--clip 14_14 --height 1300 --loose --from 3
jesse_dance|--clip jesse_dance
dab_sturdy|--clip dab --build sturdy
punch_2|--clip dataset-1_punch_normal_002
slash_1|--clip dataset-1_slash_normal_001
slash_2|--clip dataset-1_slash_normal_002
bow_angry|--clip dataset-1_bow_angry_001
bye_chimpira|--clip dataset-1_bye_chimpira_001
guide_giant|--clip dataset-1_guide_giant_001
byebye_feminine|--clip dataset-1_byebye_feminine_001
call_2|--clip dataset-1_call_normal_002
bye_active_room_2nd|--clip dataset-1_bye_active_001 --room --second-person dataset-1_bow_sad_001
bow_normal_small_slim|--clip dataset-1_bow_normal_001 --height 1000 --build slim
bye_normal_loose|--clip dataset-1_bye_normal_001 --loose
guide_normal|--clip dataset-1_guide_normal_001
byebye_happy_sturdy|--clip dataset-1_byebye_happy_001 --build sturdy
side_stretch|--segments 14_14 30.0 32.0;14_14 32.0 34.2;14_14 34.2 36.2;14_14 36.2 38.7
stretch_both_arms|--derived reach_up --from 0.3 --to 3.8
stretch_one_arm|--derived left_up --from 0.3 --to 3.8
dance_05_06|--clip 05_06 --from 0.6 --to 4.2 --distance 2500
wave_room_2nd|--clip wave_hello --room --second-person 02_01
boxing_room_2nd|--clip 13_17 --from 10 --room --second-person 16_11
kick_10_03|--clip 10_03
bow_childish|--clip dataset-1_bow_childish_001
byebye_musical|--clip dataset-1_byebye_musical_001
guide_happy_loose|--clip dataset-1_guide_happy_001 --loose
boxing_13_18|--clip 13_18 --from 5
zombie_small|--clip zombie --height 1000
bow_active|--clip dataset-1_bow_active_001
bow_chimpira_loose|--clip dataset-1_bow_chimpira_001 --loose
bow_masculinity|--clip dataset-1_bow_masculinity_001
bow_musical_small_slim|--clip dataset-1_bow_musical_001 --height 1000 --build slim
bow_not-confident|--clip dataset-1_bow_not-confident_001
bow_proud|--clip dataset-1_bow_proud_001
bye_angry_sturdy|--clip dataset-1_bye_angry_001 --build sturdy
bye_not-confident|--clip dataset-1_bye_not-confident_001
bye_old_room_2nd|--clip dataset-1_bye_old_001 --room --second-person 13_29
byebye_masculinity|--clip dataset-1_byebye_masculinity_001
byebye_normal_loose|--clip dataset-1_byebye_normal_001 --loose
byebye_not-confident|--clip dataset-1_byebye_not-confident_001
byebye_old|--clip dataset-1_byebye_old_001
guide_angry|--clip dataset-1_guide_angry_001
guide_feminine_sturdy|--clip dataset-1_guide_feminine_001 --build sturdy
guide_masculinity|--clip dataset-1_guide_masculinity_001
guide_not-confident_small_slim|--clip dataset-1_guide_not-confident_001 --height 1000 --build slim
guide_proud|--clip dataset-1_guide_proud_001
guide_sad_room_2nd|--clip dataset-1_guide_sad_001 --room --second-person 16_11
EOF
}

if [ -n "${EVAL_DUMPS:-}" ]; then
    DUMPS=$EVAL_DUMPS
    mkdir -p "$DUMPS"
    KEEP=1
else
    DUMPS=$(mktemp -d "${TMPDIR:-/tmp}/eval_tracker.XXXXXX")
    KEEP=0
fi
# results go to a folder of this run's own: several runs may share the renders
RESULTS=$(mktemp -d "${TMPDIR:-/tmp}/eval_tracker_results.XXXXXX")
cleanup() { rm -rf "$RESULTS"; [ "$KEEP" = 1 ] || rm -rf "$DUMPS"; }
trap cleanup EXIT INT TERM

COMMON="--seed 1 --frames 90 --fps 10"
REPORT=$RESULTS/report
: >"$REPORT"
echo "eval_tracker: $SET set$([ "$MIRROR" = 0 ] || echo ", mirrored"), $COMMON, data $DATA"
${SET}_set | while IFS='|' read -r name args; do
    out=$DUMPS/$PREFIX-$name
    if [ ! -f "$out/truth.txt" ]; then
        case $args in
        --derived\ *)
            rest=${args#--derived }
            python3 "$HERE/make_child.py" derive "$HERE/child/twinkle.plan" "$DUMPS/derived" ||
                { echo "eval_tracker: deriving the clips of scripts/child/twinkle.plan failed" >&2; exit 1; }
            args="--clip $DUMPS/derived/${rest%% *}.bvh ${rest#* }" ;;
        --segments\ *)
            mkdir -p "$out"
            printf '%s\n' "${args#--segments }" | tr ';' '\n' >"$out/sequence.txt"
            args="--sequence $out/sequence.txt" ;;
        esac
        if [ "$MIRROR" = 1 ]; then
            case $args in
            --sequence\ *) sed -i 's/$/ mirror/' "$out/sequence.txt" ;;
            *) args="$args --mirror" ;;
            esac
        fi
        echo "+ $TOOL synth-depth $args $COMMON --data $DATA --out $out"
        # shellcheck disable=SC2086
        "$TOOL" synth-depth $args $COMMON --data "$DATA" --out "$out" >/dev/null 2>&1 ||
            { echo "eval_tracker: synth-depth failed for $name" >&2; exit 1; }
    fi
    echo "+ $TOOL eval-track $out"
    "$TOOL" eval-track "$out" >"$RESULTS/$name.txt"
    # per joint rows: name mean_mm pct n [per facing band...] -> within
    # count (pct has one decimal); the total line, not the bands' lines
    awk -v clip="$name" '
        /^[a-z_]+ +[0-9]+ +[0-9.]+% +[0-9]+( |$)/ { p = $3; sub("%", "", p); printf "J %s %d %d\n", $1, int(p * $4 / 100 + 0.5), $4 }
        /^eval-track: +[0-9.]+% of joints within 10 cm/ { s = $0; sub(/.*\(/, "", s); sub(/\).*/, "", s); split(s, a, " of "); printf "C %s %d %d\n", clip, a[1], a[2] }
    ' "$RESULTS/$name.txt" >>"$REPORT"
done

awk '
    $1 == "C" { printf "clip %-16s %5.1f%%  (%d of %d)\n", $2, 100 * $3 / $4, $3, $4; cw += $3; cn += $4
                if (100 * $3 / $4 < worst || worst == "") { worst = 100 * $3 / $4; wname = $2 } }
    $1 == "J" { if (!($2 in jn)) order[++nj] = $2; jw[$2] += $3; jn[$2] += $4 }
    END {
        printf "overall               %5.1f%%  (%d of %d joints within 10 cm); worst clip %s %.1f%%\n", 100 * cw / cn, cw, cn, wname, worst
        for (k = 1; k <= nj; k++) { j = order[k]; printf "joint %-16s %5.1f%%  (%d of %d)\n", j, 100 * jw[j] / jn[j], jw[j], jn[j] }
    }' "$REPORT"

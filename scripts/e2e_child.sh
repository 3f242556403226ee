#!/usr/bin/env bash
# End to end (issue 5): a synthetic child dances Twinkle with planted
# mistakes, is rendered as Kinect depth, and replayed through fakenect into
# the real cubdance binary, headless; then every verdict is scored.
#
#   scripts/e2e_child.sh BUILD_DIR [--song NAME] [--child planted|late|sloppy|moving] [--remake [--from CUES]] [--keep DIR]
#
# --song: twinkle (default) or old_macdonald (a song held out from the
# early verdicts' tuning: README "Early verdicts"); its plan is
# scripts/child/NAME.plan, its cues NAME.cues (NAME_late.cues, ...).
# --child: planted (default) makes the planted mistakes; late follows the
# bear 0.5 s late all song long and sloppy does every move right at half
# amplitude on the joints that are not the move's keys (neither makes a
# mistake: no repetition of theirs may be corrected). moving (issue 20) is
# the planted child turning and moving about between moves, with an adult
# behind (scripts/make_child.py, MOVE_*: fixed before any run); its frames
# also go through `cubtool eval-track`, which prints the frames where the
# tracker took the adult. Each child has its cues: scripts/child/twinkle.cues,
# twinkle_late.cues, twinkle_sloppy.cues, twinkle_moving.cues.
#
# The child follows the bear (scripts/make_child.py): it does each move the
# coach leads a moment after the bear starts it, watches the corrections,
# and gets planted repetitions wrong (scripts/child/twinkle.plan). What the
# coach leads when is in scripts/child/twinkle.cues (the `coach request`
# lines of the box's own log). The box is deterministic, so a child who
# follows those cues makes the coach lead exactly them again; the score
# fails when it does not (the box changed). --remake then renews the cues:
# starting from the committed cues (or CUES, or the song's own timing when
# there are none) it renders, replays and re-reads the coach until the
# coach does what the child followed. Each round settles the coach's
# requests up to the next one that moved (a correction that ended sooner
# or later), so it takes a few rounds of ~2 minutes, at most 12.
#
# E2E_BOX_ARGS: more options for cubdance (e.g. "--forest
# assets/forest/body.forest": the tracker with the body-part forest).
# Needs BUILD_DIR/app/cubtool/cubtool and BUILD_DIR/app/cubdance/cubdance,
# the mocap under $CUB_DATA_DIR (default ../shared/data) and python3. The
# depth dump is 614 KB a frame (about 2 GB for the song); it is written to
# a temporary folder and deleted at the end, or to DIR/dump with --keep DIR,
# where the last round's dump stays (with its truth.txt) for eval-track.
set -euo pipefail
usage() { echo "usage: scripts/e2e_child.sh BUILD_DIR [--song NAME] [--child planted|late|sloppy|moving] [--remake [--from CUES]] [--keep DIR]" >&2; exit 2; }
[ $# -ge 1 ] || usage
build=$1
shift
remake=0 keep="" from="" child=planted name=twinkle
while [ $# -gt 0 ]; do
    case $1 in
        --child) [ $# -ge 2 ] || usage; child=$2; shift ;;
        --song) [ $# -ge 2 ] || usage; name=$2; shift ;;
        --remake) remake=1 ;;
        --from) [ $# -ge 2 ] || usage; from=$2; shift ;;
        --keep) [ $# -ge 2 ] || usage; keep=$2; shift ;;
        *) usage ;;
    esac
    shift
done
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
data=${CUB_DATA_DIR:-$root/../shared/data}
tool=$build/app/cubtool/cubtool
box=$build/app/cubdance/cubdance
song=$root/assets/songs/$name.song.xml
plan=$here/child/$name.plan
[ -f "$song" ] && [ -f "$plan" ] || { echo "e2e_child: no $song or $plan" >&2; exit 2; }
case $child in
    planted) cues=$here/child/$name.cues ;;
    late | sloppy | moving) cues=$here/child/${name}_$child.cues ;;
    *) usage ;;
esac
for f in "$tool" "$box"; do
    [ -x "$f" ] || { echo "e2e_child: no $f (build cubtool and cubdance)" >&2; exit 1; }
done
if [ ! -d "$data/mocap" ]; then
    echo "SKIP: e2e_child: no motion capture under $data (set CUB_DATA_DIR)"
    exit 77
fi
fakenect=${CUB_FAKENECT_DIR:-$(ls -d /usr/lib/*/fakenect 2>/dev/null | head -n 1)}
[ -f "$fakenect/libfreenect.so.0.5" ] || [ -f "$fakenect/libfreenect.so" ] ||
    { echo "e2e_child: no fakenect library (libfreenect-bin); set CUB_FAKENECT_DIR" >&2; exit 1; }

# fakenect's sleeps only hold the virtual clock to the wall's (the same
# log, three times slower): off when the tree built the preload
# (tests/soak/fakenect_nosleep.c), CUB_NOSLEEP_LIB naming another.
nosleep=${CUB_NOSLEEP_LIB:-$build/tests/soak/libcub_fakenect_nosleep.so}
preload=()
[ -f "$nosleep" ] && preload=(env "LD_PRELOAD=$nosleep"
    "ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0")

if [ -n "$keep" ]; then
    work=$keep
    mkdir -p "$work"
else
    work=$(mktemp -d "${TMPDIR:-/tmp}/e2e_child.XXXXXX")
    trap 'rm -rf "$work"' EXIT INT TERM
fi

# one round: the child follows CUES_IN (or the song's timing when empty)
round() {
    local cues_in=$1
    rm -rf "$work/dump"
    # shellcheck disable=SC2086
    python3 "$here/make_child.py" sequence "$song" "$plan" "$work" $cues_in --child "$child"
    if [ "$child" = moving ]; then
        # the performance as a joint track, turned and carried about
        # (make_child.py: child.moving), rendered with an adult behind
        echo "+ cubtool synth-depth --sequence $work/child.seq --write-track $work/child.jtrack"
        "$tool" synth-depth --sequence "$work/child.seq" --data "$data" \
            --write-track "$work/child.jtrack" >/dev/null
        python3 "$here/make_child.py" move "$work/child.jtrack" "$work/child.moving" \
            "$work/moved.jtrack"
        adult=$(awk '$1 == "adult" { print $2 }' "$work/child.moving")
        echo "+ cubtool synth-depth --track $work/moved.jtrack --second-person $adult --out $work/dump"
        "$tool" synth-depth --track "$work/moved.jtrack" --second-person "$adult" --data "$data" \
            --out "$work/dump" 2>/dev/null | tail -n 1
    else
        echo "+ cubtool synth-depth --sequence $work/child.seq --out $work/dump"
        "$tool" synth-depth --sequence "$work/child.seq" --data "$data" --out "$work/dump" 2>/dev/null |
            tail -n 1
    fi
    echo "+ cubdance --replay $work/dump --clock virtual --song $name --log $work/events.log ${E2E_BOX_ARGS:-}"
    # shellcheck disable=SC2086 # E2E_BOX_ARGS: words
    FAKENECT_PATH="$work/dump" LD_LIBRARY_PATH="$fakenect${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
        EGL_PLATFORM=surfaceless SDL_AUDIODRIVER=dummy \
        "${preload[@]}" "$box" --headless --size 64x48 --replay "$work/dump" --clock virtual \
        --song "$song" --buttons "$here/demo.buttons" --log "$work/events.log" --seconds 110 \
        ${E2E_BOX_ARGS:-} >"$work/cubdance.out" 2>&1 ||
        { cat "$work/cubdance.out" >&2; echo "e2e_child: cubdance failed" >&2; exit 1; }
    if [ "$child" = moving ]; then
        # the tracker alone on the same frames: did it take the adult?
        "$tool" eval-track "$work/dump" --per-frame >"$work/eval_track.txt" 2>&1 ||
            { cat "$work/eval_track.txt" >&2; echo "e2e_child: eval-track failed" >&2; exit 1; }
        grep "wrong person" "$work/eval_track.txt" || true
    fi
    cp "$work/dump/truth.txt" "$work/truth.txt"
    [ ! -f "$work/dump/truth_second.txt" ] || cp "$work/dump/truth_second.txt" "$work/truth_second.txt"
    [ -n "$keep" ] || rm -rf "$work/dump" # --keep: the dump stays for eval-track, the demo
}

if [ "$remake" = 1 ]; then
    prev=$from
    if [ -z "$prev" ] && [ -f "$cues" ]; then
        prev="$work/cues.0"
        cp "$cues" "$prev"
    fi
    for n in 1 2 3 4 5 6 7 8 9 10 11 12; do
        echo "e2e_child: --remake round $n"
        round "$prev"
        grep " coach request " "$work/events.log" >"$work/cues.$n"
        status=0
        python3 "$here/make_child.py" score "$work/expect.txt" "$work/events.log" \
            >"$work/score.txt" || status=$?
        # settled when the coach repeated, request for request, what the
        # child followed: then the next run reproduces it exactly
        if [ -n "$prev" ] && cmp -s "$prev" "$work/cues.$n"; then
            cp "$work/cues.$n" "$cues"
            cat "$work/score.txt"
            echo "e2e_child: the coach repeated the cues the child followed: wrote $cues"
            exit "$status"
        fi
        prev="$work/cues.$n"
    done
    echo "e2e_child: the cues did not settle in 12 rounds (see $work)" >&2
    cat "$work/score.txt" >&2
    exit 1
fi

[ -f "$cues" ] || { echo "e2e_child: no $cues (make it with --remake)" >&2; exit 1; }
round "$cues"
python3 "$here/make_child.py" score "$work/expect.txt" "$work/events.log"

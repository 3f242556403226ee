#!/usr/bin/env bash
# The real box program on the box's failure paths and its opt-in recording
# (issue 6): every case runs the binary and checks its exit code, its
# message and what it left on disk.
#   check_box.sh CASE EMULATOR|"" BUILD_DIR SOURCE_DIR OUT_DIR
# Exits 77 (ctest: skipped) when something this machine lacks is needed.
set -uo pipefail
case=$1 emu=$2 build=$3 src=$4 out=$5
sim="$build/app/cubdance/cubdance" pi="$build/app/cubdance/cubdance-pi"
dump="${CUB_DATA_DIR:-$src/../shared/data}/depth/skeltrack"
export SDL_AUDIODRIVER=dummy EGL_PLATFORM=surfaceless
# Mesa and SDL keep a few bytes until exit; the leaks are theirs.
export ASAN_OPTIONS=detect_leaks=0
rm -rf "$out" && mkdir -p "$out"

fail() { echo "FAIL ($case): $*"; exit 1; }

# run NAME EXE ARGS...: the program's stderr into $out/NAME.err, its exit
# code into $rc. A crash (signal, sanitizer report) always fails.
run() {
    local name=$1 exe=$2; shift 2
    # shellcheck disable=SC2086
    $emu "$exe" "$@" >"$out/$name.out" 2>"$out/$name.err"
    rc=$?
    if [ "$rc" -ge 128 ] || grep -qE "AddressSanitizer|runtime error|Segmentation" "$out/$name.err"; then
        cat "$out/$name.err"; fail "$name crashed (exit $rc)"
    fi
    echo "$name: exit $rc: $(grep -m1 '^cubdance:' "$out/$name.err")"
}

# expect_error NAME PATTERN EXE ARGS...: a non-zero exit and PATTERN on stderr.
expect_error() {
    local name=$1 pattern=$2; shift 2
    run "$name" "$@"
    [ "$rc" -ne 0 ] || fail "$name exited 0"
    grep -qE -- "$pattern" "$out/$name.err" || { cat "$out/$name.err"; fail "$name: no '$pattern'"; }
}

need_dump() { [ -f "$dump/INDEX.txt" ] || { echo "SKIP: no fakenect dump at $dump"; exit 77; }; }

replay_env() {
    export FAKENECT_PATH=$1
    export LD_LIBRARY_PATH="${CUB_FAKENECT_DIR}${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
}

case $case in
no_display)
    # No DRM device here: KMSDRM cannot start, as on a box without its TV.
    [ -e /dev/dri/card0 ] && { echo "SKIP: this machine has a DRM device"; exit 77; }
    unset DISPLAY WAYLAND_DISPLAY SDL_VIDEODRIVER
    expect_error pi_auto '^cubdance: no display: is the TV on.*KMSDRM' "$pi" --depth off \
        --buttons "$src/tests/scenario/wake.buttons" --seconds 1
    printf 'video_driver=kmsdrm\n' >"$out/kms.conf"
    expect_error sim_kmsdrm '^cubdance: no display: .*(KMSDRM|kmsdrm)' "$sim" --config "$out/kms.conf" \
        --window --depth off --seconds 1
    SDL_VIDEODRIVER=kmsdrm expect_error sim_env '^cubdance: no display: .*kmsdrm' "$sim" --window \
        --depth off --seconds 1
    ;;
display_lost)
    # SDL's offscreen driver gives a real SDL window with EGL here; the seam
    # makes it fail the way a pulled HDMI cable does (display_sdl.c).
    export SDL_VIDEODRIVER=offscreen
    run probe "$sim" --window --depth off --seconds 0.2 --clock virtual
    [ "$rc" -eq 0 ] && grep -q "display=window" "$out/probe.err" ||
        { echo "SKIP: no SDL offscreen window here"; exit 77; }
    for fault in swap@5 disconnect@5 unplug@5; do
        CUB_DISPLAY_FAULT=$fault expect_error "lost_$fault" '^cubdance: the display went away: offscreen: ' \
            "$sim" --window --depth off --seconds 20 --clock virtual --log "$out/$fault.log"
        grep -q ' app error what=display error="offscreen: ' "$out/$fault.log" ||
            fail "$fault: no display error in the log"
        grep -q ' app end ' "$out/$fault.log" || fail "$fault: the loop did not end cleanly"
        ! grep -q ' app stop reason=seconds' "$out/$fault.log" || fail "$fault: ran to the end"
    done
    ;;
missing_assets)
    song="$src/assets/songs/twinkle.song.xml"
    expect_error clip "cannot.*$out/none.bvh" "$sim" --headless --depth off --clip "$out/none.bvh"
    printf 'assets_dir=%s/no_assets\n' "$out" >"$out/assets.conf"
    expect_error assets_dir "^cubdance: .*assets.conf: cannot use assets_dir $out/no_assets: No such file" "$sim" --config "$out/assets.conf" \
        --headless --depth off --seconds 1
    expect_error character "$out/none.xml" "$sim" --headless --depth off --song "$song" \
        --character "$out/none.xml" --seconds 1
    expect_error library "$out/none.cubclips" "$sim" --headless --depth off --song "$song" \
        --library "$out/none.cubclips" --seconds 1
    expect_error song "$out/none.song.xml" "$sim" --headless --depth off --song "$out/none.song.xml" \
        --seconds 1
    # A song whose MIDI file is missing: the choreography copied with its
    # fault words but not its music.
    mkdir -p "$out/lonely" && cp "$song" "$src/assets/songs/faults.words" "$out/lonely/"
    expect_error midi "lonely/.*\.mid" "$sim" --headless --depth off \
        --song "$out/lonely/twinkle.song.xml" --seconds 1
    printf 'soundfont=%s/none.sf2\n' "$out" >"$out/sf.conf"
    expect_error soundfont "$out/none.sf2" "$sim" --config "$out/sf.conf" --headless --depth off \
        --song "$song" --seconds 1 --audio-driver dummy
    ;;
no_recording)
    # Without recording=1 or --record nothing but the event log is written.
    need_dump; replay_env "$dump"
    mkdir -p "$out/run" && cd "$out/run" || exit 1
    printf 'recording=0\nrecording_dir=%s/run/rec\n' "$out" >"$out/off.conf"
    run plain "$sim" --config "$out/off.conf" --headless --size 320x240 --replay "$dump" \
        --buttons "$src/tests/replay/start_then_stop.buttons" --log "$out/run/events.log" \
        --seconds 2 --clock virtual
    [ "$rc" -eq 0 ] || fail "the plain run failed"
    files=$(cd "$out/run" && find . -mindepth 1 | sort | tr '\n' ' ')
    [ "$files" = "./events.log " ] || fail "a plain run left more than its log: $files"
    ! grep -q ' record ' "$out/run/events.log" || fail "the log speaks of recording"
    ;;
record_roundtrip)
    # Record a replay, replay the recording: the same depth, tracking and
    # judge lines (the a-/d- files are fakenect's own format).
    need_dump; replay_env "$dump"
    run first "$sim" --headless --size 320x240 --replay "$dump" --log "$out/first.log" \
        --seconds 2 --clock virtual --record "$out/rec"
    [ "$rc" -eq 0 ] || fail "the recording run failed"
    rec=$(find "$out/rec" -mindepth 1 -maxdepth 1 -type d)
    [ "$(echo "$rec" | wc -l)" -eq 1 ] || fail "not one recording folder: $rec"
    [ "$(grep -c '^d-' "$rec/INDEX.txt")" -eq "$(grep -c '^d-' "$dump/INDEX.txt")" ] ||
        fail "the recording has not every frame"
    grep -q " record start dir=$(basename "$rec")" "$out/first.log" || fail "no record start line"
    grep -q " record stop frames=8 reason=exit" "$out/first.log" || fail "no record stop line"
    replay_env "$rec"
    run second "$sim" --headless --size 320x240 --replay "$rec" --log "$out/second.log" \
        --seconds 2 --clock virtual
    [ "$rc" -eq 0 ] || fail "replaying the recording failed"
    pick() { grep -E ' (depth|track|judge|watch) ' "$1"; }
    [ "$(pick "$out/first.log" | grep -c ' track ')" -gt 0 ] || fail "no tracking lines to compare"
    diff <(pick "$out/first.log") <(pick "$out/second.log") || fail "the replayed recording differs"
    echo "round trip: $(pick "$out/first.log" | wc -l) depth/track/judge lines the same"
    ;;
record_config)
    # recording=1 records each dance (START to STOP) into its own folder and
    # stops at the cap: 1 MB holds one 600 kB frame.
    need_dump; replay_env "$dump"
    printf 'recording=1\nrecording_dir=%s/rec\nrecording_max_mb=1\n' "$out" >"$out/rec.conf"
    run capped "$sim" --config "$out/rec.conf" --headless --size 320x240 --replay "$dump" \
        --buttons "$src/tests/replay/start_then_stop.buttons" --log "$out/capped.log" \
        --seconds 2 --clock virtual
    [ "$rc" -eq 0 ] || fail "the recording run failed"
    grep -q ' record start dir=' "$out/capped.log" || fail "no record start"
    grep -q ' record stop frames=1 reason=cap' "$out/capped.log" || fail "the cap did not stop it"
    [ "$(find "$out/rec" -name 'd-*.pgm' | wc -l)" -eq 1 ] || fail "not one frame under the cap"
    ! grep -qE 'seq=|raw=' <(grep ' record ' "$out/capped.log") || fail "image data in the log"
    ;;
log_cap)
    # log_max_kb=1: the log moves to events.log.1 and starts again.
    printf 'log_max_kb=1\n' >"$out/log.conf"
    run capped "$sim" --config "$out/log.conf" --headless --depth off --size 320x240 \
        --song "$src/assets/songs/twinkle.song.xml" --timeline "$src/tests/scenario/correct.timeline" \
        --log "$out/events.log" --seconds 12 --clock virtual --draw-every 30 --frame-every 30
    [ "$rc" -eq 0 ] || fail "the run failed"
    [ -s "$out/events.log.1" ] || fail "no events.log.1"
    for f in events.log events.log.1; do
        [ "$(stat -c %s "$out/$f")" -lt 1500 ] || fail "$f is over the cap"
    done
    tail -1 "$out/events.log" | grep -q ' app end ' || fail "the newest log lacks the end"
    echo "log: $(wc -l <"$out/events.log.1") + $(wc -l <"$out/events.log") lines"
    # A restart (systemd) keeps the run before it: its last lines say why it ended.
    last_end=$(tail -1 "$out/events.log")
    run again "$sim" --config "$out/log.conf" --headless --depth off --size 320x240 \
        --log "$out/events.log" --seconds 0.2 --clock virtual
    [ "$rc" -eq 0 ] || fail "the second run failed"
    [ "$(tail -1 "$out/events.log.1")" = "$last_end" ] || fail "the restart lost the last run's log"
    ;;
*) fail "unknown case" ;;
esac
echo "PASS ($case)"

#!/usr/bin/env bash
# Odd inputs to the real cubdance (issue 18): a directory or a symbolic-link
# loop named as a file got "read failed" or "cannot open the config file"
# with no reason; a config saved with a UTF-8 byte-order mark was refused;
# a character the clip library was not built for was blamed on the library.
# Each refusal within 20 s names the file and the reason in words.
#   check_odd_inputs.sh EMULATOR|"" BUILD_DIR SOURCE_DIR OUT_DIR
set -uo pipefail
emu=$1 build=$2 src=$3 out=$4
# shellcheck source=box_check_common.sh
. "$(dirname "$0")/box_check_common.sh"

# run NAME WANT_RC PATTERN ARGS...: exit WANT_RC ("fail": 1..127) within 20 s,
# PATTERN on stderr or stdout.
run() {
    local name=$1 want=$2 pattern=$3; shift 3
    timeout $((20 * slow)) $emu "$bin" --headless "${view[@]}" --depth off --clock virtual --seconds 0.5 \
        --audio-driver dummy --log "$out/$name.log" "$@" >"$out/$name.out" 2>"$out/$name.err"
    local rc=$?
    [ "$rc" != 124 ] || fail "$name: hung (killed after $((20 * slow)) s)"
    if [ "$rc" -ge 128 ] || grep -qE "AddressSanitizer|runtime error" "$out/$name.err"; then
        cat "$out/$name.err"; fail "$name crashed (exit $rc)"
    fi
    if [ "$want" = fail ]; then [ "$rc" != 0 ] || fail "$name exited 0"
    else [ "$rc" = "$want" ] || { cat "$out/$name.err"; fail "$name exited $rc, not $want"; }; fi
    cat "$out/$name.err" "$out/$name.out" > "$out/$name.all"
    grep -qE -- "$pattern" "$out/$name.all" || { cat "$out/$name.all"; fail "$name: no '$pattern'"; }
    echo "ok: $name: exit $rc: $(grep -m1 -E -- "$pattern" "$out/$name.all")"
}

mkdir "$out/dir.conf" "$out/dir.song.xml"
ln -s loop.conf "$out/loop.conf"
ln -s loop.song.xml "$out/loop.song.xml"
run config_dir fail "dir.conf: cannot read the config file: it is a directory, not a file" \
    --config "$out/dir.conf"
run config_loop fail "loop.conf: cannot open the config file: Too many levels of symbolic links" \
    --config "$out/loop.conf"
run song_dir fail "dir.song.xml: cannot read the song: it is a directory, not a file" \
    --song "$out/dir.song.xml"
run song_loop fail "loop.song.xml: cannot open the song: Too many levels of symbolic links" \
    --song "$out/loop.song.xml"

# A config saved with a byte-order mark (and CRLF, as a Windows editor saves
# it) is read as it says: the run goes on, at the volume it sets.
printf '\xEF\xBB\xBFvolume=30\r\nattract_after_s=20\r\n' > "$out/bom.conf"
run config_bom 0 "event log written" --config "$out/bom.conf"
grep -q "app stop reason=seconds" "$out/config_bom.log" || fail "config_bom: the run did not go on"

# The bear with its head renamed: the library's skeleton lacks the joint,
# and the character file is to blame.
sed 's/"Head"/"Noggin"/g' "$src/assets/bear/bear.xml" > "$out/other.xml"
run character_skeleton fail \
    "other.xml: the character's joint 'Noggin' \(its features read it\) is not in the skeleton of the clip library bear.cubclips" \
    --song "$src/assets/songs/twinkle.song.xml" --character "$out/other.xml"
grep -q "coach clips: bear.cubclips" "$out/character_skeleton.err" &&
    fail "character_skeleton: blamed on the library"
echo "all odd inputs named"

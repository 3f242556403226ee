#!/usr/bin/env bash
# Files that are not files (issue 18): a FIFO, a directory or a device named
# where the box expects a file must be refused at once — never block in
# open(), never read without end — with a message naming the file and what
# it is. Each run has 20 s; a hang is a failure.
#   check_special_files.sh EMULATOR|"" BUILD_DIR SOURCE_DIR OUT_DIR
set -uo pipefail
emu=$1 build=$2 src=$3 out=$4
# shellcheck source=box_check_common.sh
. "$(dirname "$0")/box_check_common.sh"

# refused NAME PATTERN ARGS...: exit 1..127 within 20 s, PATTERN on stderr.
refused() {
    local name=$1 pattern=$2; shift 2
    # shellcheck disable=SC2086
    local depth=(--depth off) envs=() prev="" a
    for a in "$@"; do
        [ "$prev" = --replay ] && depth=() envs=(FAKENECT_PATH="$a" LD_LIBRARY_PATH="$fakenect_libs")
        prev=$a
    done
    timeout $((20 * slow)) env "${envs[@]}" $emu "$bin" --headless "${view[@]}" "${depth[@]}" \
        --clock virtual --seconds 0.5 \
        --audio-driver dummy --log "$out/$name.log" "$@" >"$out/$name.out" 2>"$out/$name.err"
    local rc=$?
    [ "$rc" != 124 ] || fail "$name: hung (killed after $((20 * slow)) s)"
    if [ "$rc" -ge 128 ] || grep -qE "AddressSanitizer|runtime error" "$out/$name.err"; then
        cat "$out/$name.err"; fail "$name crashed (exit $rc)"
    fi
    [ "$rc" != 0 ] || fail "$name exited 0"
    grep -qE -- "$pattern" "$out/$name.err" || { cat "$out/$name.err"; fail "$name: no '$pattern'"; }
    echo "ok: $name: exit $rc: $(head -n 1 "$out/$name.err")"
}

mkfifo "$out/fifo" "$out/fifo.song.xml" "$out/fifo.ttf"
mkdir "$out/dir.conf"
refused config_fifo "$out/fifo: .*it is a FIFO, not a file" --config "$out/fifo"
refused config_dir "$out/dir.conf: .*it is a directory, not a file" --config "$out/dir.conf"
refused song_fifo "$out/fifo.song.xml: .*it is a FIFO, not a file" --song "$out/fifo.song.xml"
refused song_zero "/dev/zero: .*it is a character device, not a file" --song /dev/zero
refused font_fifo "font $out/fifo.ttf: it is a FIFO, not a file" --font "$out/fifo.ttf"
printf 'font=%s\n' "$out/fifo.ttf" > "$out/font.conf"
refused config_font_fifo "font $out/fifo.ttf: it is a FIFO, not a file" --config "$out/font.conf"

# A dump: its INDEX.txt a FIFO; then a FIFO and a device named in it.
frame=d-1300000000.000000-1000000.pgm
mkdir -p "$out/dump_index" "$out/dump_names"
mkfifo "$out/dump_index/INDEX.txt"
refused dump_index_fifo "INDEX.txt: it is a FIFO, not a file" --replay "$out/dump_index"
{ printf 'P5 640 480 65535\n'; head -c 614400 /dev/zero; } > "$out/dump_names/$frame"
mkfifo "$out/dump_names/a-1300000000.000000-0.dump"
printf '%s\na-1300000000.000000-0.dump\n' "$frame" > "$out/dump_names/INDEX.txt"
refused dump_name_fifo "a-1300000000.000000-0.dump: not a regular file \(it is a FIFO" \
    --replay "$out/dump_names"
echo "all special files refused"

#!/usr/bin/env bash
# Huge files (issue 18): a file of a few GB (sparse: made with truncate,
# nothing written) named as any file the box or cubtool reads was read into
# a buffer grown to 1 GB before it was refused (1.2-1.3 GB resident); a
# 2 GB frame file in a dump likewise, and cubtool eval-track read all the
# frames before it looked at the truth file. Each kind now has a size limit
# (cub/text.h) checked before a byte is read, stated in the message: every
# run here must be refused within 20 s, naming the file, its kind and the
# limit, and stay under MAX_RSS_KB resident (the sanitizers' shadow memory
# included).
#   check_huge_files.sh EMULATOR|"" BUILD_DIR SOURCE_DIR OUT_DIR
set -uo pipefail
emu=$1 build=$2 src=$3 out=$4
# shellcheck source=box_check_common.sh
. "$(dirname "$0")/box_check_common.sh"
tool="$build/app/cubtool/cubtool"
# Under qemu the resident size is the emulator's: only the host bounds it.
max_rss_kb=300000
[ -n "$emu" ] && max_rss_kb=0
[ -x /usr/bin/time ] || fail "no /usr/bin/time to measure the resident size (scripts/setup.sh installs it)"

# ran NAME PATTERN CMD...: exit 1..127 within the limit, PATTERN on
# stderr, at most max_rss_kb resident.
ran() {
    local name=$1 pattern=$2; shift 2
    timeout $((20 * slow)) /usr/bin/time -o "$out/$name.rss" -f %M "$@" \
        >"$out/$name.out" 2>"$out/$name.err"
    local rc=$? rss
    rss=$(tail -n 1 "$out/$name.rss" 2>/dev/null)
    [ "$rc" != 124 ] || fail "$name: hung (killed after $((20 * slow)) s)"
    if [ "$rc" -ge 128 ] || grep -qE "AddressSanitizer|runtime error" "$out/$name.err"; then
        cat "$out/$name.err"; fail "$name crashed (exit $rc)"
    fi
    [ "$rc" != 0 ] || { cat "$out/$name.err"; fail "$name exited 0"; }
    grep -qE -- "$pattern" "$out/$name.err" || { cat "$out/$name.err"; fail "$name: no '$pattern'"; }
    [ "$max_rss_kb" = 0 ] || [ "${rss:-0}" -le "$max_rss_kb" ] ||
        fail "$name: $rss kB resident, more than $max_rss_kb kB"
    echo "ok: $name: exit $rc, ${rss:-?} kB resident: $(grep -m1 -E -- "$pattern" "$out/$name.err")"
}
box() {
    local name=$1 pattern=$2; shift 2
    ran "$name" "$pattern" $emu "$bin" --headless "${view[@]}" --depth off --clock virtual --seconds 0.5 \
        --audio-driver dummy --log "$out/$name.log" "$@"
}
huge() { truncate -s 3G "$out/$1"; }
big=3221225472

huge huge.song.xml
box song "huge.song.xml: the song is $big bytes, larger than the 4 MB a song may be" \
    --song "$out/huge.song.xml"
huge huge.mid
sed 's/midi="[^"]*"/midi="huge.mid"/' "$src/assets/songs/twinkle.song.xml" > "$out/midi.song.xml"
cp "$src/assets/songs/faults.words" "$out/" # found beside the song, like its MIDI
box midi "huge.mid: the MIDI file is $big bytes, larger than the 4 MB a MIDI file may be" \
    --song "$out/midi.song.xml"
huge huge.timeline
box timeline "huge.timeline: the timeline is $big bytes, larger than the 1 MB a timeline may be" \
    --timeline "$out/huge.timeline"
# The coach's library, tags and character are loaded for a song.
song="$src/assets/songs/twinkle.song.xml"
huge huge.bear.xml
box character "huge.bear.xml: the character file is $big bytes, larger than the 1 MB a character file may be" \
    --song "$song" --character "$out/huge.bear.xml"
huge huge.tags.xml
box tags "huge.tags.xml: the tag file is $big bytes, larger than the 64 MB a tag file may be" \
    --song "$song" --tags "$out/huge.tags.xml"
huge huge.cubclips
box library "huge.cubclips: the clip pack is $big bytes, larger than the 64 MB a clip pack may be" \
    --song "$song" --library "$out/huge.cubclips"
huge huge.bvh
box clip "huge.bvh: the BVH file is $big bytes, larger than the 64 MB a BVH file may be" \
    --clip "$out/huge.bvh"
huge huge.conf
box config "huge.conf: the config file is $big bytes, larger than the 64 kB a config file may be" \
    --config "$out/huge.conf"
huge huge.ttf
box font "huge.ttf: the font is $big bytes, larger than the 32 MB a font may be" \
    --font "$out/huge.ttf"

# cubtool: a retarget map, a recipe, a BVH to retarget.
huge huge.map
ran map "huge.map: the retarget map is $big bytes, larger than the 1 MB a retarget map may be" \
    $emu "$tool" retarget "$src/assets/clips/hello.bvh" --map "$out/huge.map" --out "$out/map.bvh"
huge huge.recipe
ran recipe "huge.recipe: the recipe is $big bytes, larger than the 1 MB a recipe may be" \
    $emu "$tool" build --recipe "$out/huge.recipe" --out "$out/recipe.cubclips"

# eval-track: a huge truth is refused before the 300 frames (180 MB) are
# read; a 2 GB frame file is refused unread.
d="$out/dump"
mkdir -p "$d"
{ printf 'P5 640 480 65535\n'; head -c 614400 /dev/zero; } > "$d/frame.pgm"
for k in $(seq 0 299); do
    n=$(printf 'd-%d.%06d-%d.pgm' $((1300000000 + k / 30)) $(((k % 30) * 1000000 / 30)) $((2000000 * k)))
    ln -s frame.pgm "$d/$n"
    echo "$n" >> "$d/INDEX.txt"
done
truncate -s 3G "$d/truth.txt"
ran eval_truth "truth.txt: the truth file is $big bytes, larger than the 64 MB a truth file may be" \
    $emu "$tool" eval-track "$d"
f="$out/frame2g"
mkdir -p "$f"
truncate -s 2G "$f/d-1300000000.000000-0.pgm"
echo d-1300000000.000000-0.pgm > "$f/INDEX.txt"
ran eval_frame "d-1300000000.000000-0.pgm: the depth frame is 2147483648 bytes, larger than the 614464 bytes a depth frame may be" \
    $emu "$tool" eval-track "$f"

# The box replays a dump with a 2 GB frame file at INDEX.txt:31: that
# frame replayed without readings, unread.
f="$out/replay2g"
mkdir -p "$f"
cp "$d/frame.pgm" "$f/"
for k in $(seq 0 59); do
    n=$(printf 'd-%d.%06d-%d.pgm' $((1300000000 + k / 30)) $(((k % 30) * 1000000 / 30)) $((2000000 * k)))
    if [ "$k" = 30 ]; then truncate -s 2G "$f/$n"; big_frame=$n; else ln -s frame.pgm "$f/$n"; fi
    echo "$n" >> "$f/INDEX.txt"
done
FAKENECT_PATH="$f" LD_LIBRARY_PATH="$fakenect_libs" \
    timeout $((60 * slow)) /usr/bin/time -o "$out/replay.rss" -f %M $emu "$bin" --headless "${view[@]}" \
    --clock virtual --seconds 2 --replay "$f" --audio-driver dummy --log "$out/replay.log" \
    >"$out/replay.out" 2>"$out/replay.err"
rc=$? rss=$(tail -n 1 "$out/replay.rss")
[ "$rc" = 0 ] || { cat "$out/replay.err"; fail "replay of a 2 GB frame exited $rc"; }
grep -q "INDEX.txt:31: $big_frame: the depth frame is 2147483648 bytes, larger than .*replayed as a frame without readings" "$out/replay.err" ||
    { cat "$out/replay.err"; fail "replay: the 2 GB frame not reported"; }
# A replay itself is ~250 MB resident under the sanitizers (GL, the
# tracker); a frame read whole would add 2 GB.
[ "$max_rss_kb" = 0 ] || [ "$rss" -le 400000 ] || fail "replay: $rss kB resident"
echo "ok: replay with a 2 GB frame: $rss kB resident: $(grep -m1 'larger than' "$out/replay.err")"
echo "all huge files refused unread"

#!/usr/bin/env bash
# A dump's INDEX.txt is read whole (issue 18): an empty line no longer ends
# the check while fakenect reads on past it (a truncated frame after it was
# a heap-buffer-overflow in on_depth, a missing one a bare exit(1)); the
# empty line is dropped, the bad frames after it mended, and an INDEX.txt
# that lists nothing is refused.
#   check_dump_index.sh EMULATOR|"" BUILD_DIR OUT_DIR
set -uo pipefail
emu=$1 build=$2 out=$3
# shellcheck source=box_check_common.sh
. "$(dirname "$0")/box_check_common.sh"

name() { printf 'd-%d.%06d-%d.pgm' $((1300000000 + $1 / 30)) $((($1 % 30) * 1000000 / 30)) \
    $((1000000 + 2000000 * $1)); }
frame() { { printf 'P5 640 480 65535\n'; head -c 614400 /dev/zero; } > "$1"; }

# run NAME DUMP: 30 s at most, no crash; exit code in $rc.
run() {
    FAKENECT_PATH="$2" LD_LIBRARY_PATH="$fakenect_libs" \
        timeout $((30 * slow)) $emu "$bin" --headless "${view[@]}" --clock virtual --seconds 1 --replay "$2" \
        --log "$out/$1.log" >"$out/$1.out" 2>"$out/$1.err"
    rc=$?
    [ "$rc" != 124 ] || fail "$1: hung"
    if [ "$rc" -ge 128 ] || grep -qE "AddressSanitizer|runtime error" "$out/$1.err"; then
        cat "$out/$1.err"; fail "$1 crashed (exit $rc)"
    fi
}

# An empty line first, then good frames around a truncated and a missing one.
d="$out/blank_first"; mkdir -p "$d"
printf '\n' > "$d/INDEX.txt"
for k in $(seq 0 9); do
    n=$(name "$k")
    echo "$n" >> "$d/INDEX.txt"
    [ "$k" = 5 ] && continue # missing
    frame "$d/$n"
done
head -c 1000 "$d/$(name 3)" > "$d/cut" && mv "$d/cut" "$d/$(name 3)"
: > "$d/$(name 7)" # 0 bytes
run blank_first "$d"
cat "$out/blank_first.err"
[ "$rc" = 0 ] || fail "blank_first exited $rc"
grep -q "INDEX.txt:1: an empty line: dropped" "$out/blank_first.err" || fail "the empty line is not reported"
grep -q "INDEX.txt:5: $(name 3): truncated" "$out/blank_first.err" || fail "the truncated frame is not mended"
grep -q "INDEX.txt:7: $(name 5): missing" "$out/blank_first.err" || fail "the missing frame is not mended"
grep -q "INDEX.txt:9: $(name 7): truncated: 0 of" "$out/blank_first.err" || fail "the 0-byte frame is not mended"
grep -q "app end" "$out/blank_first.log" || fail "no 'app end' in the log"
echo "ok: an empty first line: dropped, bad frames after it mended, exit 0"

# An INDEX.txt that lists nothing (empty, or only empty lines).
for kind in empty blanks; do
    d="$out/index_$kind"; mkdir -p "$d"
    if [ "$kind" = empty ]; then : > "$d/INDEX.txt"; else printf '\n\n' > "$d/INDEX.txt"; fi
    run "index_$kind" "$d"
    [ "$rc" != 0 ] || fail "an INDEX.txt ($kind) was accepted"
    grep -q "INDEX.txt lists no files: nothing to replay" "$out/index_$kind.err" ||
        { cat "$out/index_$kind.err"; fail "index_$kind: no message"; }
    echo "ok: an INDEX.txt ($kind): refused, exit $rc"
done

#!/usr/bin/env bash
# cubdance with a font that is not there, and with a file that is not a
# font: it must say "cubdance: cannot load font PATH: why" and exit 1 (not
# crash: a signal or a sanitizer report exits otherwise).
#   missing_font.sh EMULATOR CUBDANCE SCRATCH_DIR
set -u
emu=$1 bin=$2 dir=$3
mkdir -p "$dir"
printf 'not a font' > "$dir/not_a_font.ttf"
check() { # font, expected message
    local out rc
    out=$($emu "$bin" --headless --depth off --seconds 0.2 --log "$dir/log.txt" --font "$1" 2>&1)
    rc=$?
    if [ "$rc" != 1 ]; then echo "FAIL: --font $1 exited $rc, want 1; output: $out"; exit 1; fi
    if ! grep -qxF "$2" <<<"$out"; then echo "FAIL: --font $1 printed: $out; want: $2"; exit 1; fi
    echo "ok: --font $1 -> exit 1, '$2'"
}
check /nonexistent/cub.ttf "cubdance: cannot load font /nonexistent/cub.ttf: No such file or directory"
check "$dir/not_a_font.ttf" "cubdance: cannot load font $dir/not_a_font.ttf: not a TrueType font"

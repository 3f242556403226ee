#!/usr/bin/env bash
# cubdance with a font that is not there, and with a file that is not a
# font: it must say "cubdance: cannot load font PATH: why" and exit 1 (not
# crash: a signal or a sanitizer report exits otherwise). Then fonts cut
# short or corrupted (made here from the default font, issue 18): each must
# be refused as "not a usable TrueType font (why)", never read past its end.
#   missing_font.sh EMULATOR CUBDANCE SCRATCH_DIR
set -u
emu=$1 bin=$2 dir=$3
mkdir -p "$dir"
printf 'not a font' > "$dir/not_a_font.ttf"
check() { # font, expected message (a trailing * matches any end)
    local out rc
    out=$($emu "$bin" --headless --depth off --seconds 0.2 --log "$dir/log.txt" --font "$1" 2>&1)
    rc=$?
    if [ "$rc" != 1 ]; then echo "FAIL: --font $1 exited $rc, want 1; output: $out"; exit 1; fi
    local want=$2 ok
    if [[ $want == *'*' ]]; then # a line starting with the rest
        awk -v p="${want%'*'}" 'index($0, p) == 1 { f = 1 } END { exit !f }' <<<"$out" && ok=1 || ok=0
    else
        grep -qxF -- "$want" <<<"$out" && ok=1 || ok=0
    fi
    if [ "$ok" = 0 ]; then echo "FAIL: --font $1 printed: $out; want: $2"; exit 1; fi
    echo "ok: --font $1 -> exit 1, '$(head -n 1 <<<"$out")'"
}
check /nonexistent/cub.ttf "cubdance: cannot load font /nonexistent/cub.ttf: No such file or directory"
check "$dir/not_a_font.ttf" "cubdance: cannot load font $dir/not_a_font.ttf: not a TrueType font"

font=/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf
if [ ! -r "$font" ]; then echo "skip: no $font to damage"; exit 0; fi
size=$(stat -c %s "$font")
for cut in 11 20 300 4000 $((size / 3)) $((size * 2 / 3)) $((size - 1000)); do
    head -c "$cut" "$font" > "$dir/cut_$cut.ttf"
    check "$dir/cut_$cut.ttf" "cubdance: cannot load font $dir/cut_$cut.ttf: not a usable TrueType font (*"
done
# Corruptions at the offsets stb_truetype follows blindly.
python3 - "$font" "$dir" <<'PY'
import struct, sys
src, out = sys.argv[1], sys.argv[2]
data = open(src, 'rb').read()
n = struct.unpack('>H', data[4:6])[0]
dirs = {data[12 + 16 * i:16 + 16 * i].decode('latin-1'): 12 + 16 * i for i in range(n)}
def put(name, at, fmt, value, base=None):
    d = bytearray(base or data)
    struct.pack_into(fmt, d, at, value)
    open(f'{out}/{name}.ttf', 'wb').write(d)
    return d
def table(tag):
    rec = dirs[tag]
    return struct.unpack('>II', data[rec + 8:rec + 16])
put('tables_past_end', 4, '>H', 4000)
put('glyf_offset', dirs['glyf'] + 8, '>I', 0x7ffffff0)
put('cmap_length', dirs['cmap'] + 12, '>I', 0xfffffff0)
loca, _ = table('loca')
d = bytearray(data)
d[loca:loca + 2000] = b'\xff' * 2000
open(f'{out}/loca_garbage.ttf', 'wb').write(d)
cmap, _ = table('cmap')
subtables = struct.unpack('>H', data[cmap + 2:cmap + 4])[0]
put('cmap_subtable_offset', cmap + 8 * subtables, '>I', 0x10000000)  # the last: stb's pick
maxp, _ = table('maxp')
put('many_glyphs', maxp + 4, '>H', 0xffff)
hhea, _ = table('hhea')
put('hmtx_count', hhea + 34, '>H', 0xffff)
PY
for c in tables_past_end glyf_offset cmap_length loca_garbage cmap_subtable_offset many_glyphs hmtx_count; do
    check "$dir/$c.ttf" "cubdance: cannot load font $dir/$c.ttf: not a usable TrueType font (*"
done

#!/usr/bin/env bash
# check_deb.sh DEB [--release] — what a cubdance package must hold:
#   1. `dpkg-deb -c`: exactly the expected files (the box program, on amd64
#      the simulator too, the runtime assets as in the tree, unit, udev
#      rules, sysusers file, config, copyright), with sane modes;
#   2. `dpkg-deb -I`: Package, Architecture, Version, Depends, conffiles,
#      maintainer scripts;
#   3. unpacked into a scratch root (dpkg -x, no root needed), the binaries
#      print their version (an arm64 one under qemu-aarch64-static if
#      present, else its ELF header must say AArch64), the box program plays
#      a song from the assets under the scratch root, and the unpacked unit
#      passes systemd-analyze verify (verify_unit.sh).
# --release: a package to ship: no sanitizer runtime in Depends, and the
# binary's compiled-in asset paths are the installed ones.
# Exit 77 (ctest: skipped) when dpkg-deb is missing.
set -euo pipefail

deb=${1:?usage: check_deb.sh DEB [--release]}
release=0
[ "${2:-}" = --release ] && release=1
here=$(cd "$(dirname "$0")" && pwd)
src=${CUB_SOURCE_DIR:-$(cd "$here/../.." && pwd)}
fail() { echo "FAIL: $deb: $*"; exit 1; }

for tool in dpkg-deb readelf; do
    command -v "$tool" >/dev/null ||
        { echo "SKIP: $tool is not installed (scripts/setup.sh installs dpkg-dev, binutils)"; exit 77; }
done
[ -f "$deb" ] || fail "no such file"
field() { dpkg-deb -f "$deb" "$1"; }
arch=$(field Architecture)
version=$(field Version)
[ "$(field Package)" = cubdance ] || fail "Package is '$(field Package)', not cubdance"
case "$arch" in amd64 | arm64) ;; *) fail "Architecture is '$arch'" ;; esac
grep -q "^project(cubdance VERSION $version " "$src/CMakeLists.txt" ||
    fail "Version $version is not the project's version"

# 1. Contents: the expected set, no more, no less.
expected=$(mktemp) listed=$(mktemp) scratch=$(mktemp -d)
trap 'rm -rf "$expected" "$listed" "$scratch"' EXIT
{
    echo ./usr/bin/cubdance-pi
    [ "$arch" = amd64 ] && echo ./usr/bin/cubdance
    for d in bear clips songs forest floor; do
        (cd "$src/assets" && find "$d" -type f | sed 's|^|./usr/share/cubdance/|')
    done
    # the bear's spoken words, made by the build (app/voice; docs/speech.md)
    echo ./usr/share/cubdance/voice/bear.cubvoice
    printf '%s\n' ./etc/cubdance/cubdance.conf ./lib/systemd/system/cubdance.service \
        ./lib/udev/rules.d/55-cubdance.rules ./usr/lib/sysusers.d/cubdance.conf \
        ./usr/share/doc/cubdance/copyright
} | sort > "$expected"
dpkg-deb -c "$deb" | awk '$1 !~ /^d/ {print $6}' | sort > "$listed"
if ! diff -u "$expected" "$listed" > "$scratch/contents.diff"; then
    cat "$scratch/contents.diff"
    fail "contents differ from the expected list (- missing, + unexpected)"
fi
dpkg-deb -c "$deb" | awk '$1 !~ /^d/ && $2 != "root/root" {print; bad=1} END {exit bad}' ||
    fail "files not owned by root"
dpkg-deb -c "$deb" | awk '$1 !~ /^d/ && $6 ~ /^\.\/usr\/bin\// && $1 != "-rwxr-xr-x" {print; bad=1}
                         $6 !~ /^\.\/usr\/bin\// && $1 !~ /^d/ && $1 != "-rw-r--r--" {print; bad=1}
                         END {exit bad}' || fail "wrong file modes (binaries 0755, the rest 0644)"
echo "deb: $(basename "$deb"): $(wc -l < "$listed") files, all expected"

# 2. Control fields and files.
depends=$(field Depends)
for lib in libc6 libsdl2-2.0-0 libfreenect0.5 libgpiod2 libfluidsynth3 libtinyxml2-9 libegl1 \
           libgles2 libpng16-16 timgm6mb-soundfont libegl-mesa0 libgl1-mesa-dri systemd; do
    echo "$depends" | tr ',' '\n' | grep -qE "^ *$lib( |$)" || fail "Depends lacks $lib: $depends"
done
if [ "$release" = 1 ] && echo "$depends" | grep -qE 'libasan|libubsan'; then
    fail "a sanitizer build was packaged (Depends: $depends)"
fi
dpkg-deb -e "$deb" "$scratch/DEBIAN"
[ "$(cat "$scratch/DEBIAN/conffiles")" = /etc/cubdance/cubdance.conf ] ||
    fail "conffiles is not exactly /etc/cubdance/cubdance.conf"
grep -q '^ *systemd-sysusers cubdance.conf$' "$scratch/DEBIAN/postinst" ||
    fail "postinst does not make the service user"
for s in postinst prerm postrm; do
    [ -x "$scratch/DEBIAN/$s" ] || fail "$s is missing or not executable"
    sh -n "$scratch/DEBIAN/$s" || fail "$s is not valid sh"
done
echo "deb: Architecture=$arch Version=$version conffiles=/etc/cubdance/cubdance.conf"
echo "deb: Depends=$depends"

# 3. Unpacked into a scratch root.
root="$scratch/root"
dpkg-deb -x "$deb" "$root"
for f in board/pi/cubdance.service:lib/systemd/system/cubdance.service \
         board/pi/55-cubdance.rules:lib/udev/rules.d/55-cubdance.rules \
         board/pi/cubdance.conf:etc/cubdance/cubdance.conf LICENSE:usr/share/doc/cubdance/copyright; do
    cmp -s "$src/${f%%:*}" "$root/${f#*:}" || fail "/${f#*:} is not the tree's ${f%%:*}"
done
host_arch=$(dpkg --print-architecture 2>/dev/null || echo unknown)
run=()
if [ "$arch" != "$host_arch" ]; then
    machine=$(readelf -h "$root/usr/bin/cubdance-pi" | sed -n 's/^ *Machine: *//p')
    want=$([ "$arch" = arm64 ] && echo AArch64 || echo "Advanced Micro Devices X86-64")
    [ "$machine" = "$want" ] || fail "/usr/bin/cubdance-pi is for '$machine', not $want"
    echo "deb: /usr/bin/cubdance-pi is an ELF for $machine"
    if [ "$arch" = arm64 ] && command -v qemu-aarch64-static >/dev/null; then
        run=(qemu-aarch64-static)
    else
        echo "deb: $arch binaries not run here (no emulator)"
    fi
fi
if [ "$arch" = "$host_arch" ] || [ ${#run[@]} -gt 0 ]; then
    for exe in "$root"/usr/bin/*; do
        got=$("${run[@]}" "$exe" --version)
        [ "$got" = "cubdance $version" ] || fail "${exe#"$root"} --version printed '$got'"
        echo "deb: ${exe#"$root"} --version: $got"
    done
    assets="$root/usr/share/cubdance"
    if [ "$release" = 1 ]; then
        # (into a variable first: grep -q leaves at the first match, and a
        # help text longer than one stdio buffer then dies of SIGPIPE,
        # which pipefail would take for a failure)
        help=$("${run[@]}" "$root/usr/bin/cubdance-pi" --help)
        grep -q "(default /usr/share/cubdance/clips/bear.cubclips)" <<<"$help" ||
            fail "the binary's default assets are not /usr/share/cubdance"
    fi
    # The box program plays a song from the unpacked assets: START at 0.5 s,
    # the bear wakes and the song starts (its MIDI read beside the choreography).
    echo "0.5 start" > "$scratch/buttons"
    "${run[@]}" "$root/usr/bin/cubdance-pi" --headless --depth empty --audio-driver dummy \
        --clock virtual --seconds 4 --buttons "$scratch/buttons" --clip "$assets/clips/hello.bvh" \
        --song "$assets/songs/twinkle.song.xml" --library "$assets/clips/bear.cubclips" \
        --tags "$assets/clips/bear.tags.xml" --character "$assets/bear/bear.xml" \
        --voice "$assets/voice/bear.cubvoice" --log "$scratch/events.log" 2> "$scratch/stderr" || {
        cat "$scratch/stderr"; fail "cubdance-pi did not run on the unpacked assets"; }
    grep -q '^t=[0-9.]* music start song="Twinkle Twinkle Little Star"' "$scratch/events.log" ||
        fail "the song did not start from the unpacked assets (log: $(tail -3 "$scratch/events.log"))"
    ! grep -q "speech off" "$scratch/stderr" || fail "the packaged voice pack: $(cat "$scratch/stderr")"
    echo "deb: cubdance-pi played twinkle.song.xml from the scratch root"
fi
"$here/verify_unit.sh" "$root"
echo "deb: $(basename "$deb") passed"

#!/usr/bin/env bash
# Install every Debian package that building, testing and running cubdance
# needs, on a fresh Debian 12 (bookworm) machine. Safe to run again: apt
# skips what is already there. Needs root or sudo.
#
#   scripts/setup.sh          host packages + the aarch64 cross toolchain
#   scripts/setup.sh --host   host packages only (no cross build)
set -euo pipefail

want_cross=1
[ "${1:-}" = "--host" ] && want_cross=0

SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

# Libraries the box links, by their Debian -dev names. Installed for the host
# and, for the `pi` preset, again for arm64 through multiarch.
LIBS="libfreenect-dev libsdl2-dev libegl-dev libgles-dev libgpiod-dev
      libtinyxml2-dev libfluidsynth-dev libcmocka-dev libpng-dev zlib1g-dev
      libegl-mesa0 libgl1-mesa-dri libstb-dev"

# (libstb-dev: stb_truetype for the TV's text, linked from its libstb.so.)
# The font the text is drawn with (the .deb depends on it too).
FONTS="fonts-dejavu-core"

# Tools: compiler and build, libFuzzer (clang), fakenect's replay library
# (libfreenect-bin), the song SoundFont, pictures for golden-image checks,
# python3 for the synthetic child's scripts (scripts/make_child.py);
# packaging and its checks: dpkg-dev (dpkg-shlibdeps for cpack's Depends),
# binutils (readelf: the arm64 binary's ELF header), systemd
# (systemd-analyze verify on the unit).
TOOLS="build-essential cmake ninja-build pkg-config git clang libclang-rt-14-dev
       libfreenect-bin timgm6mb-soundfont espeak-ng ca-certificates python3 time
       dpkg-dev binutils systemd"

CROSS="crossbuild-essential-arm64 qemu-user-static"

apt_install() { $SUDO apt-get install -y --no-install-recommends "$@"; }

# Everything this run wants, so a machine that has it all skips apt entirely.
wanted="$TOOLS $LIBS $FONTS"
if [ "$want_cross" = 1 ]; then
    wanted="$wanted $CROSS"
    for p in $LIBS; do wanted="$wanted $p:arm64"; done
fi
missing=""
for p in $wanted; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
        missing="$missing $p"
done
if [ -z "$missing" ]; then
    echo "setup: every package is already installed"
    exit 0
fi
echo "setup: installing:$missing"

if [ "$want_cross" = 1 ] && ! dpkg --print-foreign-architectures | grep -qx arm64; then
    $SUDO dpkg --add-architecture arm64
fi
$SUDO apt-get update -q
# shellcheck disable=SC2086
apt_install $TOOLS $LIBS $FONTS
if [ "$want_cross" = 1 ]; then
    arm_libs=""
    for p in $LIBS; do arm_libs="$arm_libs $p:arm64"; done
    # shellcheck disable=SC2086
    apt_install $CROSS $arm_libs
fi
echo "setup: done"

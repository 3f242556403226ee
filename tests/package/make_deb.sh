#!/usr/bin/env bash
# make_deb.sh BUILD_DIR OUT_DIR [check_deb.sh options] — make the package of
# a configured and built tree with cpack (the tree's CPackConfig.cmake),
# into OUT_DIR, then check it with check_deb.sh. Exit 77 (ctest: skipped)
# when cpack or dpkg-deb is missing.
set -euo pipefail
build=${1:?usage: make_deb.sh BUILD_DIR OUT_DIR [--release]}
out=${2:?usage: make_deb.sh BUILD_DIR OUT_DIR [--release]}
shift 2
for tool in cpack dpkg-deb dpkg-shlibdeps; do
    command -v "$tool" >/dev/null ||
        { echo "SKIP: $tool is not installed (scripts/setup.sh installs cmake, dpkg-dev)"; exit 77; }
done
rm -rf "$out"
mkdir -p "$out"
cpack --config "$build/CPackConfig.cmake" -B "$out" > "$out/cpack.log" 2>&1 ||
    { cat "$out/cpack.log"; echo "FAIL: cpack in $build"; exit 1; }
debs=("$out"/cubdance_*.deb)
[ ${#debs[@]} = 1 ] && [ -f "${debs[0]}" ] || { echo "FAIL: cpack made no single .deb in $out"; exit 1; }
exec "$(dirname "$0")/check_deb.sh" "${debs[0]}" "$@"

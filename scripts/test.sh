#!/usr/bin/env bash
# The whole test suite, as CI runs it (.ci/run calls exactly this):
#   1. install what is missing (scripts/setup.sh, idempotent)
#   2. host build (x86-64, -Werror, ASan+UBSan) and its ctest
#   3. aarch64 cross build and the same ctest under qemu-aarch64-static
#   4. the .deb packages: amd64 and (unless --host-only) arm64, each from a
#      Release tree built with -DCUB_PACKAGE=ON (a package must not carry a
#      sanitizer build), checked by tests/package/check_deb.sh --release
#   5. the parsers' libFuzzer targets, each for a bounded time
#   6. the end-to-end songs (ctest -L e2e) on a Release tree
#   7. a short soak (scripts/soak.sh: four songs, two minutes of box time) on a Release
#      tree: the heap's high-water and the open descriptors must not grow
# Options: --host-only skips 3 (and the arm64 package); --no-fuzz skips 5.
set -euo pipefail
cd "$(dirname "$0")/.."

host_only=0 fuzz=1
for a in "$@"; do
    case "$a" in
        --host-only) host_only=1 ;;
        --no-fuzz) fuzz=0 ;;
        *) echo "usage: scripts/test.sh [--host-only] [--no-fuzz]" >&2; exit 2 ;;
    esac
done
jobs=$(nproc)
start=$(date +%s)

if [ "$host_only" = 1 ]; then scripts/setup.sh --host; else scripts/setup.sh; fi

stage() { echo; echo "=== $1 ($(( $(date +%s) - start )) s)"; }
# The figures the tests print (error bounds, round trips, replays): ctest
# keeps test output in its log; show the one-line `name: figure` results.
figures() {
    echo "--- figures printed by the tests ($1):"
    grep -hE '^(fx|motion|track|io|replay|firmware [a-z]+|fakenect|depth empty|audio [a-z]+|bench_bvh): ' \
        "build/$1/Testing/Temporary/LastTest.log" |
        grep -vE '^io: ((round trip )?(cmu|animdraw|bandai|dog)/|bad )' | sed 's/^/  /' || true
}

stage "host: configure and build"
cmake --preset host
cmake --build --preset host -j "$jobs"
stage "host: ctest"
ctest --preset host -j "$jobs"
figures host

if [ "$host_only" = 0 ]; then
    stage "pi (aarch64, under qemu): configure and build"
    cmake --preset pi
    cmake --build --preset pi -j "$jobs"
    stage "pi: ctest under qemu-aarch64-static"
    CUB_QUICK=1 ctest --preset pi -j "$jobs"
    figures pi
fi

# Only the packaged programs are built in these trees (cpack does not build
# "all" first: CMAKE_SKIP_INSTALL_ALL_DEPENDENCY), so this stays short.
package() { # package <arch> [cmake options]
    local dir="build/package-$1"
    shift
    cmake --no-warn-unused-cli -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCUB_PACKAGE=ON -DCUB_TESTS=OFF "$@" >/dev/null
    cmake --build "$dir" -j "$jobs" --target cubdance-pi cubdance
    tests/package/make_deb.sh "$dir" "$dir/deb" --release
}
stage "packages: amd64"
package amd64
if [ "$host_only" = 0 ]; then
    stage "packages: arm64 (cross)"
    package arm64 -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake
fi

if [ "$fuzz" = 1 ]; then
    stage "fuzz: libFuzzer on the parsers"
    cmake --preset fuzz
    cmake --build --preset fuzz -j "$jobs"
    ctest --preset fuzz -j "$jobs"
fi
# The end-to-end songs replay whole songs into the box: on the Release tree
# (five times faster than under ASan; the host stage's scenarios run the
# same code under the sanitizers). The allocation counter the soak reads
# cannot load into a sanitizer build either.
stage "end to end: the synthetic children's songs on the Release box (ctest -L e2e)"
cmake --preset release >/dev/null
cmake --build --preset release -j "$jobs" --target cubdance cubtool cub_alloc_count cub_fakenect_nosleep
ctest --test-dir build/release -L e2e -j "$jobs" --output-on-failure
stage "soak: four songs on the Release box (scripts/soak.sh 0.034 --period 30)"
scripts/soak.sh 0.034 --period 30 --build build/release --out build/release/soak-short || [ $? = 77 ] # 77: no data
stage "all tests passed"

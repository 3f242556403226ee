#!/usr/bin/env bash
# The whole test suite, as CI runs it (.ci/run calls exactly this):
#   1. install what is missing (scripts/setup.sh, idempotent)
#   2. host build (x86-64, -Werror, ASan+UBSan) and its ctest
#   3. aarch64 cross build and the same ctest under qemu-aarch64-static
#   4. the parsers' libFuzzer targets, each for a bounded time
# Options: --host-only skips 3 (and the cross packages); --no-fuzz skips 4.
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

if [ "$fuzz" = 1 ]; then
    stage "fuzz: libFuzzer on the parsers"
    cmake --preset fuzz
    cmake --build --preset fuzz -j "$jobs"
    ctest --preset fuzz
fi
stage "all tests passed"

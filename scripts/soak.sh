#!/usr/bin/env bash
# The soak: the real box (cubdance, a Release build, headless, --clock
# virtual) replaying a Kinect recording for HOURS of box time, a song led
# from START to STOP every 90 s, and at each song start the box's own line
# (cubdance --stats: `stats: song n= rss_kb= fds= heap_peak_kb= ...`).
# Fails (exit 1) if, after the first song, the open descriptors grow at
# all, the heap's high-water or its bytes in use by more than HEAP_SLACK_B,
# or resident memory by more than RSS_SLACK_KB (docs/memory.md: why a
# little slack is allowed).
#
#   scripts/soak.sh HOURS [--build DIR] [--out DIR] [--song NAME] [--dump DIR] [--period S]
#
# HOURS may be fractional. --period S (default 90) is the time from one
# START to the next; below 80 every song is stopped mid-song, which is what
# CI runs to keep it short: `soak.sh 0.034 --period 30`, four songs.
# The recording (default the real Skeltrack frames under ../shared/data)
# is looped by scripts/soak_dump.py as long as the soak lasts. Songs
# alternate: the first and every odd one is danced to its end and STOP is
# pressed while the box waits again; every even one is stopped mid-song.
# Needs the build's app/alloc_count/libcub_alloc_count.so (the heap) and
# tests/soak/libcub_fakenect_nosleep.so (fakenect's wall-clock pacing off:
# see tests/soak/fakenect_nosleep.c); `cmake --preset release && cmake
# --build --preset release` makes both.
set -euo pipefail
cd "$(dirname "$0")/.."
usage() { echo "usage: scripts/soak.sh HOURS [--build DIR] [--out DIR] [--song NAME] [--dump DIR] [--period S]" >&2; exit 2; }
[ $# -ge 1 ] || usage
hours=$1
shift
build=build/release out=out/soak song=london_bridge
PERIOD_S=90  # one song: London Bridge is 69 s of music, the box waits again at ~74 s
data="${CUB_DATA_DIR:-$PWD/../shared/data}"
dump="$data/depth/skeltrack"
while [ $# -gt 0 ]; do
    case "$1" in
        --build) build=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        --song) song=$2; shift 2 ;;
        --dump) dump=$2; shift 2 ;;
        --period) PERIOD_S=$2; shift 2 ;;
        *) usage ;;
    esac
done
RSS_SLACK_KB=1024  # resident pages may come and go by this much (docs/memory.md)
HEAP_SLACK_B=256   # the audio thread's blocks move the high-water by a few bytes (docs/memory.md)

build=$(realpath "$build")
exe="$build/app/cubdance/cubdance"
counter="$build/app/alloc_count/libcub_alloc_count.so"
nosleep="$build/tests/soak/libcub_fakenect_nosleep.so"
for f in "$exe" "$counter" "$nosleep"; do
    if [ ! -e "$f" ]; then
        echo "soak: $f is missing: build a Release tree (cmake --preset release && cmake --build --preset release)" >&2
        exit 2
    fi
done
if [ ! -f "$dump/INDEX.txt" ]; then
    echo "SKIP: no recording at $dump (../shared/data is absent)"
    exit 77
fi
seconds=$(python3 -c "print(round($hours * 3600, 3))")
mkdir -p "$out"
rm -rf "$out/dump"
python3 scripts/soak_dump.py "$dump" "$out/dump" "$(python3 -c "print($seconds + 10)")"
python3 - "$seconds" "$PERIOD_S" > "$out/soak.buttons" <<'PY'
import sys
seconds, period = float(sys.argv[1]), float(sys.argv[2])
mid = min(40.0, period / 2)  # an even song's STOP, mid-dance
print("# scripts/soak.sh: START every %g s; odd songs stopped %g s after START, even ones %g s" %
      (period, period - 10, mid))
k, t = 0, 1.0
while t < seconds:
    stop = t + (mid if k % 2 else period - 10)
    print("%.1f start press" % t)
    if stop < seconds:
        print("%.1f stop press" % stop)
    k, t = k + 1, t + period
PY

fakenect=$(ls -d /usr/lib/*/fakenect 2>/dev/null | head -n 1)
echo "soak: $seconds s of box time, $(grep -c start "$out/soak.buttons") songs of $song, replaying $dump in a loop"
real0=$(date +%s)
FAKENECT_PATH="$out/dump" LD_LIBRARY_PATH="$fakenect${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
LD_PRELOAD="$counter $nosleep" EGL_PLATFORM=surfaceless SDL_AUDIODRIVER=dummy \
    "$exe" --headless --size 320x240 --draw-every 30 --frame-every 30 --clock virtual \
    --replay "$out/dump" --song "assets/songs/$song.song.xml" --buttons "$out/soak.buttons" \
    --seconds "$seconds" --log "$out/events.log" --stats > "$out/stats.txt"
real_s=$(( $(date +%s) - real0 ))
echo "soak: the box ran $seconds s of box time in $real_s s of real time"
grep '^stats: song ' "$out/stats.txt" || true
grep '^stats: \(memory\|allocations\)' "$out/stats.txt" || true

# Each song start against the second one's (the first song is where the
# box's pools, caches and shader variants fill up).
python3 - "$out/stats.txt" "$RSS_SLACK_KB" "$HEAP_SLACK_B" <<'PY'
import re, sys
lines = [l for l in open(sys.argv[1]) if l.startswith("stats: song ")]
slack, heap_slack = int(sys.argv[2]), int(sys.argv[3])
songs = [dict(re.findall(r"(\w+)=(\S+)", l)) for l in lines]
if len(songs) < 3:
    sys.exit("soak: FAIL: %d song starts; a soak needs at least 3" % len(songs))
if "heap_peak_b" not in songs[0]:
    sys.exit("soak: FAIL: the box printed no heap figure (was the counter preloaded?)")
base, bad = songs[1], []
for s in songs[2:]:
    for key, allow in (("heap_peak_b", heap_slack), ("heap_b", heap_slack), ("fds", 0), ("rss_kb", slack)):
        if int(s[key]) > int(base[key]) + allow:
            bad.append("song %s: %s=%s, song 2 had %s (allowed +%d)" % (s["n"], key, s[key], base[key], allow))
rss = [int(s["rss_kb"]) for s in songs[1:]]
peak = [int(s["heap_peak_b"]) for s in songs[1:]]
print("soak: %d songs; after the first: heap_peak_b %d..%d, fds %s..%s, rss_kb %d..%d" % (
    len(songs), min(peak), max(peak),
    min(int(s["fds"]) for s in songs[1:]), max(int(s["fds"]) for s in songs[1:]), min(rss), max(rss)))
if bad:
    print("soak: FAIL\n  " + "\n  ".join(bad))
    sys.exit(1)
print("soak: PASS (heap high-water and bytes in use within %d B, descriptors flat, resident memory within %d kB)" % (heap_slack, slack))
PY

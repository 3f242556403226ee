#!/usr/bin/env bash
# The bear says its words (issue 19): the real box, in real time, writes
# its sound through SDL's disk audio driver while it leads Twinkle; a
# scripted judge makes the child leave at 6 s ("Come closer!") and come
# back at 9 s (the disk driver keeps only roughly to
# real time under load, so the next phrase must come well after). speech_pcm then finds the phrase in the written audio: it
# must start within one audio buffer of its `speech say` line, asked for at
# the tick of the `coach hint`, with the music ducked under it. With
# speech=0 in the config: no speech line, no trace of the phrase.
#   check_speech.sh EMULATOR|"" BUILD_DIR SOURCE_DIR OUT_DIR
# Exits 77 (skipped) when the build made no voice pack (no espeak-ng).
set -uo pipefail
emu=$1 build=$2 src=$3 out=$4
pack="$build/assets/voice/bear.cubvoice"
check="$build/tests/app/speech_pcm"
[ -f "$pack" ] || { echo "SKIP: no voice pack at $pack (espeak-ng missing at build time)"; exit 77; }
export EGL_PLATFORM=surfaceless ASAN_OPTIONS=detect_leaks=0
rm -rf "$out" && mkdir -p "$out"
printf '# the scripted child: leaves, comes back\n6.0 nobody\n9.0 player\n' > "$out/leave.timeline"

run() { # NAME SPEECH
    local name=$1 speech=$2 dir="$out/$1"
    mkdir -p "$dir"
    printf 'volume=100\nspeech=%s\n' "$speech" > "$dir/box.conf"
    # The disk driver writes audio.raw where the box runs.
    (cd "$dir" && $emu "$build/app/cubdance/cubdance" --config box.conf --headless --size 64x48 \
        --depth off --audio-driver disk --voice "$pack" --song "$src/assets/songs/twinkle.song.xml" \
        --buttons "$src/scripts/demo.buttons" --timeline "$out/leave.timeline" --seconds 10 \
        --log event.log 2> stderr.txt)
    local rc=$?
    [ "$rc" = 0 ] || { cat "$dir/stderr.txt"; echo "FAIL: the box exited $rc ($name)"; exit 1; }
    [ -s "$dir/audio.raw" ] || { echo "FAIL: no audio.raw ($name)"; exit 1; }
}
run on 1
run off 0
$emu "$check" "$out/on/audio.raw" "$out/on/event.log" "$out/off/audio.raw" "$out/off/event.log" \
    "$pack" "Come closer!" come_closer

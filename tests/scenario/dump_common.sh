# Shared by make_gap_dump.sh and make_garbage_dump.sh (sourced, not run).

# The source dump's depth frame names into the array `frames`; exit 77
# (skip) when the dump is absent.
read_source_frames() {
    local src=$1
    if [ ! -f "$src/INDEX.txt" ]; then
        echo "SKIP: no fakenect dump at $src"
        exit 77
    fi
    mapfile -t frames < <(grep '^d-' "$src/INDEX.txt")
}

# The fakenect file name of frame k at k/30 s: the time in the name, and the
# Kinect's 60 MHz timestamp (2,000,000 a frame), which the board's replay
# pacing reads.
frame_name() {
    local k=$1
    printf 'd-%d.%06d-%d.pgm' $((1300000000 + k / 30)) $(((k % 30) * 1000000 / 30)) \
        $((1000000 + 2000000 * k))
}

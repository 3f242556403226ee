# Shared set-up of the checks that feed the real cubdance bad input
# (check_special_files.sh, check_dump_index.sh, check_dump_time.sh,
# check_dump_seconds.sh, check_huge_files.sh, check_odd_inputs.sh,
# check_event_log.sh):
# sourced once emu, build and out are set.
bin="$build/app/cubdance/cubdance"
export SDL_AUDIODRIVER=dummy EGL_PLATFORM=surfaceless LIBGL_ALWAYS_SOFTWARE=1
export ASAN_OPTIONS=detect_leaks=0
rm -rf "$out" && mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
# fakenect's environment, set the way the `fakenect` wrapper sets it: given
# a replay, cubdance would re-exec itself into it, which qemu-user cannot.
fakenect_libs="${CUB_FAKENECT_DIR:?}${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# A hang is a run past its limit times this: under qemu every frame costs
# many times more.
slow=1
[ -n "$emu" ] && slow=10
# What the box draws decides nothing these checks look at: a small view,
# and under qemu (llvmpipe emulated, ~100 ms a drawn frame) one tick in 15
# drawn, as the scenarios do. "${view[@]}" goes after --headless.
view=(--size 64x48)
[ -n "$emu" ] && view+=(--draw-every 15)

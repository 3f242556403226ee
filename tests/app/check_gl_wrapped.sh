#!/bin/bash
# cubtool bench-render counts time inside GL calls as the driver's through
# link-time wrappers (CUB_BENCH_GL_WRAPPED in app/cubtool/CMakeLists.txt).
# A GL function the renderer calls that is not wrapped would be counted as
# our own work: fail, naming it, when the renderer and the list part ways.
# usage: check_gl_wrapped.sh LIBCUB_RENDER.a glA glB ...
set -euo pipefail
lib=$1; shift
used=$(nm -u "$lib" | awk '$1 == "U" && $2 ~ /^gl[A-Z]/ {print $2}' | sort -u)
[ -n "$used" ] || { echo "FAIL: no GL calls found in $lib"; exit 1; }
missing=$(comm -23 <(echo "$used") <(printf '%s\n' "$@" | sort -u))
if [ -n "$missing" ]; then
    echo "FAIL: the renderer calls GL functions bench-render does not wrap:" $missing
    echo "add them to CUB_BENCH_GL_WRAPPED and app/cubtool/bench_gl.c"
    exit 1
fi
echo "PASS: all $(echo "$used" | wc -l) GL functions the renderer calls are wrapped"

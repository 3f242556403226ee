#!/usr/bin/env bash
# A fresh held-out set of music for the groove's beat alignment (issue 23,
# docs/groove.md "A fresh held-out set"): installs music21 (its corpus
# comes with it) into a venv outside the repository and writes a seeded
# draw of corpus pieces in the shared MIDI files' styles, never one of
# them, as MIDI into a directory outside the repository. Never commit
# the files: they are scored by `cubtool groove-eval DIR [--set b]`.
#
#   scripts/heldout_music.sh [OUT_DIR] [--seed N] [--per-group K]
#
# OUT_DIR: default $XDG_CACHE_HOME/cubdance/heldout_music (~/.cache/...).
# The venv: $MUSIC21_VENV, default $XDG_CACHE_HOME/cubdance/venv-music21.
# music21 is pinned: the corpus (and so the pools and the draw) is the
# version's. The pools, the seed's use and the names: scripts/heldout_music.py.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/.." && pwd)
cache=${XDG_CACHE_HOME:-$HOME/.cache}/cubdance
out=${1:-$cache/heldout_music}
[ $# -gt 0 ] && shift
venv=${MUSIC21_VENV:-$cache/venv-music21}
case "$(realpath -m "$out")/" in
"$repo"/*) echo "heldout_music.sh: $out is inside the repository; the files must stay out of it" >&2
    exit 2 ;;
esac
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import music21' 2>/dev/null; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q 'music21==10.5.1'
fi
exec "$venv/bin/python" "$here/heldout_music.py" "$out" "$@"

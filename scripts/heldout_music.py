#!/usr/bin/env python3
"""A fresh held-out set for the groove's beat alignment (issue 23,
docs/groove.md "A fresh held-out set"): a seeded random draw of pieces of
music21's corpus in the styles of ../shared/data/midi, never one of the
shared files, written as MIDI by music21's own writer (format 1, 10080
ticks per quarter, as the shared files were).

Run through scripts/heldout_music.sh, which makes the venv. Usage:
    heldout_music.py OUT_DIR [--seed N] [--per-group K]

The pools (fixed before any draw, by what the shared files are):
  chorale   bach/*.mxl|xml but BWV 846 (a prelude), BWV 66.6 and 269
  quartet   the string quartet movements of Haydn, Mozart (not K. 545,
            a piano sonata) and Beethoven, but the three shared first
            movements (Haydn op. 74/1, Mozart K. 80, Beethoven op. 18/1)
  fiddle    Ryan's Mammoth Collection's reels and hornpipes (file name
            ending Reel or Hornpipe), but the four shared ones
  essen     the Essen collection's German songbooks (altdeu, ballad,
            boehme, dva, erk, fink, kinder, zuccal: not the test files,
            the Chinese han*, Luxembourg, Lorraine, Irish, Haydn's or the
            variants), every song by its X: number, but altdeu10 #1 and
            kinder0 #1-3
The jazz style has no other piece in the corpus (Joplin's Maple Leaf Rag
and Berlin's lead sheet are the only ragtime): no group.

Each pool is sorted, then random.Random(seed + group index).sample draws
K of it; a piece music21 cannot parse or write is replaced by the next
draw of the same generator (printed). Names: STYLE_..., so that
`cubtool groove-eval DIR` groups them by style (chorales and quartets
are both "classical")."""
import argparse
import os
import random
import re
import sys

GROUPS = ("chorale", "quartet", "fiddle", "essen")
ESSEN_BOOKS = re.compile(r"^(altdeu|ballad|boehme|dva|erk|fink|kinder|zuccal)\d*\.abc$")
SHARED = {
    "bach/bwv66.6.mxl", "bach/bwv269.mxl",
    "haydn/opus74no1/movement1.mxl", "mozart/k80/movement1.mxl",
    "beethoven/opus18no1/movement1.mxl",
    "ryansMammoth/7thRegimentReel.abc", "ryansMammoth/AcrobatsHornpipe.abc",
    "ryansMammoth/AdmiralsHornpipe.abc", "ryansMammoth/AlbemarleHornpipe.abc",
    "essenFolksong/altdeu10.abc#1", "essenFolksong/kinder0.abc#1",
    "essenFolksong/kinder0.abc#2", "essenFolksong/kinder0.abc#3",
}


def corpus_root():
    import music21.corpus
    return os.path.dirname(music21.corpus.__file__)


def files(root, sub, pattern):
    out = []
    for dirpath, _, names in os.walk(os.path.join(root, sub)):
        for name in names:
            if re.search(pattern, name):
                out.append(os.path.relpath(os.path.join(dirpath, name), root))
    return out


def essen_songs(root):
    out = []
    for name in os.listdir(os.path.join(root, "essenFolksong")):
        if not ESSEN_BOOKS.match(name):
            continue
        with open(os.path.join(root, "essenFolksong", name), encoding="latin-1") as f:
            for line in f:
                m = re.match(r"X:\s*(\d+)", line)
                if m:
                    out.append("essenFolksong/%s#%s" % (name, m.group(1)))
    return out


def pool(root, group):
    if group == "chorale":
        got = [p for p in files(root, "bach", r"^bwv[\d.]+(-\w+)?\.(mxl|xml)$")
               if not p.endswith("bwv846.mxl")]
    elif group == "quartet":
        got = files(root, "haydn", r"\.mxl$") + files(root, "beethoven", r"\.mxl$")
        got += [p for p in files(root, "mozart", r"\.mxl$") if "k545" not in p]
    elif group == "fiddle":
        got = files(root, "ryansMammoth", r"(Reel|Hornpipe)\.abc$")
    else:
        got = essen_songs(root)
    return sorted(p for p in got if p not in SHARED)


def out_name(group, piece):
    path, _, number = piece.partition("#")
    stem = os.path.splitext(path)[0]
    if group == "chorale":
        return "classical_bach_" + os.path.basename(stem)
    if group == "quartet":
        return "classical_" + stem.replace("/", "_")
    if group == "fiddle":
        return "country_" + os.path.basename(stem)
    return "folk_essen_%s_%s" % (os.path.basename(stem), number)


def write_midi(root, piece, out_path):
    from music21 import converter
    path, _, number = piece.partition("#")
    full = os.path.join(root, path)
    score = converter.parse(full, number=int(number)) if number else converter.parse(full)
    score.write("midi", fp=out_path)


def draw(root, group, index, seed, k, out_dir):
    rng = random.Random(seed + index)
    candidates = pool(root, group)
    order = rng.sample(candidates, len(candidates))
    taken = []
    for piece in order:
        if len(taken) == k:
            break
        name = out_name(group, piece) + ".mid"
        try:
            write_midi(root, piece, os.path.join(out_dir, name))
        except Exception as e:  # music21 raises many kinds
            print("skipped %s: %s" % (piece, e), file=sys.stderr)
            continue
        taken.append((piece, name))
    print("%s: pool %d, drew %s" % (group, len(candidates), ", ".join(p for p, _ in taken)))
    return taken


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out_dir")
    ap.add_argument("--seed", type=int, default=35)
    ap.add_argument("--per-group", type=int, default=5)
    a = ap.parse_args()
    import music21
    root = corpus_root()
    print("music21 %s, seed %d, %d per group" % (music21.__version__, a.seed, a.per_group))
    os.makedirs(a.out_dir, exist_ok=True)
    for i, g in enumerate(GROUPS):
        for piece, name in draw(root, g, i, a.seed, a.per_group, a.out_dir):
            print("  %-44s <- %s" % (name, piece))


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""make_songs.py - write the box's songs as standard MIDI files.

The tunes are traditional children's songs in the public domain; the
arrangements (instrument, form, variations, drum parts) are the project's
own, written below in a small note notation of ours. The MIDI bytes are
written here too (no third-party library), so the same notation always gives
the same files.

    scripts/make_songs.py                 write assets/songs/*.mid, print each song's length
    scripts/make_songs.py --check         compare with the committed files, exit 1 if different
    scripts/make_songs.py --out DIR       write elsewhere

Notation (melody): blank-separated notes, '|' between bars.
    NOTE  = pitch duration, e.g. C5q, F#4e, Bb4h.   R = a rest (Rq, Rw)
    pitch = C D E F G A B, optional # or b, octave 0..9 (C4 = MIDI 60)
    duration = w h q e s (whole .. sixteenth), '.' after it = dotted
Every bar must hold exactly one bar of the meter (checked).

Notation (drums): a pattern is one bar on a sixteenth-note grid, one string
per instrument: 'X' accent, 'x' normal, 'o' soft, '.' nothing. A section
cycles through a list of patterns, one bar each.

Each song file: format 1, 480 ticks per quarter; track 0 the title, the
tempo and the meter; track 1 the melody on channel 1 (a GM program); track 2
the drums on channel 10. Every track ends exactly at the song's last bar
line, so the file's length is the notation's length.
"""
import argparse
import os
import re
import sys

TPQ = 480  # ticks per quarter note
DURATIONS = {"w": 4.0, "h": 2.0, "q": 1.0, "e": 0.5, "s": 0.25}
STEPS = {"C": 0, "D": 2, "E": 4, "F": 5, "G": 7, "A": 9, "B": 11}
DRUMS = {  # General MIDI percussion keys (channel 10)
    "K": 36,  # bass drum
    "R": 37,  # side stick
    "S": 38,  # snare
    "P": 39,  # hand clap
    "H": 42,  # closed hi-hat
    "O": 46,  # open hi-hat
    "C": 49,  # crash
    "D": 51,  # ride
    "T": 54,  # tambourine
    "B": 56,  # cowbell
    "W": 76,  # wood block
}
DRUM_VELOCITY = {"X": 112, "x": 84, "o": 56}

# ---- the songs ------------------------------------------------------------

TWINKLE_VERSE = """
C5q C5q G5q G5q | A5q A5q G5h | F5q F5q E5q E5q | D5q D5q C5h |
G5q G5q F5q F5q | E5q E5q D5h | G5q G5q F5q F5q | E5q E5q D5h |
C5q C5q G5q G5q | A5q A5q G5h | F5q F5q E5q E5q | D5q D5q C5h |
"""

MACDONALD_VERSE = """
C5q C5q C5q G4q | A4q A4q G4h | E5q E5q D5q D5q | C5h. G4q |
C5q C5q C5q G4q | A4q A4q G4h | E5q E5q D5q D5q | C5h. G4e G4e |
C5q C5q C5q G4e G4e | C5q C5q C5q Rq | C5e C5e C5q C5e C5e C5q | C5e C5e C5e C5e C5q C5q |
C5q C5q C5q G4q | A4q A4q G4h | E5q E5q D5q D5q | C5h. Rq |
"""

LONDON_VERSE = """
G5q. A5e G5q F5q | E5q F5q G5h | D5q E5q F5h | E5q F5q G5h |
G5q. A5e G5q F5q | E5q F5q G5h | D5h G5h | E5q C5h. |
"""

PATTERNS = {
    # the count-in: side stick on every beat
    "count": {"R": "X...x...x...x..."},
    # slow sections (warm-up stretches): half-time, soft
    "soft": {"K": "X...............", "R": "........x.......", "H": "o...o...o...o..."},
    "soft_fill": {"K": "X...............", "R": "........x...x.x.", "H": "o...o...o......."},
    # fast sections (clapping, boxing): a driving groove
    "groove": {"K": "X.......X.x.....", "S": "....X.......X...", "H": "x.x.x.x.x.x.x.x."},
    "fill": {"K": "X.......X.......", "S": "....X...x.x.xXxX", "H": "x.x.x.x........."},
    "crash": {"C": "X...............", "K": "X.......X.x.....", "S": "....X.......X...",
              "H": "..x.x.x.x.x.x.x."},
    # the farm: hand claps on 2 and 4, a cowbell
    "farm": {"K": "X.....x.X.....x.", "P": "....X.......X...", "B": "x...x...x...x...",
             "H": "..x...x...x...x."},
    "farm_fill": {"K": "X.....x.X.......", "P": "....X.......X...", "S": "........x.x.xXxX"},
    # the bridge: tambourine and wood block
    "bridge": {"K": "X.......X.......", "S": "....X.......X...", "T": "x.x.x.x.x.x.x.x.",
               "W": "x..x..x.........", },
    "end": {"C": "X...............", "K": "X..............."},
}

SONGS = [
    {
        "file": "twinkle",
        "title": "Twinkle Twinkle Little Star",
        "bpm": 96, "meter": (4, 4),
        "program": 10,  # Music Box
        "melody": {"verse": TWINKLE_VERSE, "bouncy": "double", "intro": "Rw | Rw |",
                   "outro": "G5h E5h | C5w |"},
        # (melody part, drum patterns cycled bar by bar, bars)
        "form": [
            ("intro", ["count"], 2),
            ("verse", ["soft"] * 11 + ["soft_fill"], 12),     # slow: stretches
            ("bouncy", ["crash"] + ["groove"] * 10 + ["fill"], 12),  # fast: claps, boxing
            ("verse", ["groove"] * 11 + ["fill"], 12),
            ("outro", ["soft", "end"], 2),
        ],
    },
    {
        "file": "old_macdonald",
        "title": "Old MacDonald Had a Farm",
        "bpm": 120, "meter": (4, 4),
        "program": 105,  # Banjo
        "melody": {"verse": MACDONALD_VERSE, "intro": "Rw | Rw |", "outro": "G4h E5h | C5w |"},
        "form": [
            ("intro", ["count"], 2),
            ("verse", ["farm"] * 15 + ["farm_fill"], 16),   # the cow
            ("verse", ["farm"] * 15 + ["farm_fill"], 16),   # the duck
            ("verse", ["groove"] * 15 + ["fill"], 16),      # the pig
            ("outro", ["farm", "end"], 2),
        ],
    },
    {
        "file": "london_bridge",
        "title": "London Bridge Is Falling Down",
        "bpm": 125, "meter": (4, 4),
        "program": 73,  # Flute
        "melody": {"verse": LONDON_VERSE, "intro": "Rw | Rw |", "outro": "G5h E5h | C5w |"},
        "form": [
            ("intro", ["count"], 2),
            ("verse", ["soft"] * 7 + ["soft_fill"], 8),     # slow: falling down, stretching
            ("verse", ["bridge"] * 7 + ["fill"], 8),        # build it up with iron bars
            ("verse", ["bridge"] * 7 + ["fill"], 8),        # iron bars will bend and break
            ("verse", ["crash"] + ["groove"] * 6 + ["fill"], 8),  # gold and silver
            ("outro", ["groove", "end"], 2),
        ],
    },
]

# ---- notation -> events ---------------------------------------------------


def parse_note(tok):
    m = re.fullmatch(r"(R|[A-G][#b]?[0-9])([whqes])(\.?)", tok)
    if not m:
        raise ValueError(f"bad note '{tok}'")
    beats = DURATIONS[m.group(2)] * (1.5 if m.group(3) else 1.0)
    if m.group(1) == "R":
        return None, beats
    p = m.group(1)
    key = 12 * (int(p[-1]) + 1) + STEPS[p[0]] + {"#": 1, "b": -1}.get(p[1:-1], 0)
    return key, beats


def bars_of(text):
    return [b.split() for b in text.split("|") if b.strip()]


def double_time(text):
    """The 'bouncy' variation: every note split in two of half its length."""
    out = []
    for bar in bars_of(text):
        toks = []
        for tok in bar:
            m = re.fullmatch(r"(.*?)([whqes])(\.?)", tok)
            half = {"w": "h", "h": "q", "q": "e", "e": "s"}[m.group(2)]
            toks += [m.group(1) + half + m.group(3)] * 2
        out.append(" ".join(toks))
    return " | ".join(out) + " |"


def melody_events(song, bar_beats):
    """(tick, order, bytes) for the melody, checking every bar's length."""
    events, tick = [], 0
    for part, _, nbars in song["form"]:
        text = song["melody"][part]
        if text == "double":
            text = double_time(song["melody"]["verse"])
        bars = bars_of(text)
        if len(bars) != nbars:
            raise ValueError(f"{song['file']}: part '{part}' has {len(bars)} bars, form says {nbars}")
        for i, bar in enumerate(bars):
            pos = 0.0
            for tok in bar:
                key, beats = parse_note(tok)
                if key is not None:
                    t0 = tick + round(pos * TPQ)
                    gate = round(beats * TPQ * 0.9)  # a little air between notes
                    vel = 100 if pos == 0 else (88 if pos == int(pos) else 76)
                    events.append((t0, 1, bytes([0x90, key, vel])))
                    events.append((t0 + gate, 0, bytes([0x80, key, 0])))
                pos += beats
            if abs(pos - bar_beats) > 1e-9:
                raise ValueError(f"{song['file']}: part '{part}' bar {i + 1} holds {pos} beats, "
                                 f"not {bar_beats}")
            tick += round(bar_beats * TPQ)
    return events, tick


def drum_events(song, bar_beats, steps):
    events, tick = [], 0
    step_ticks = round(bar_beats * TPQ) // steps
    for _, cycle, nbars in song["form"]:
        for b in range(nbars):
            pattern = PATTERNS[cycle[b % len(cycle)]]
            for inst in sorted(pattern):
                line = pattern[inst]
                if len(line) != steps:
                    raise ValueError(f"pattern line '{line}' has {len(line)} steps, not {steps}")
                for s, c in enumerate(line):
                    if c == ".":
                        continue
                    t0 = tick + s * step_ticks
                    key = DRUMS[inst]
                    events.append((t0, 1, bytes([0x99, key, DRUM_VELOCITY[c]])))
                    events.append((t0 + step_ticks // 2, 0, bytes([0x89, key, 0])))
            tick += round(bar_beats * TPQ)
    return events, tick


# ---- MIDI bytes -----------------------------------------------------------


def vlq(n):
    out = [n & 0x7F]
    n >>= 7
    while n:
        out.append(0x80 | (n & 0x7F))
        n >>= 7
    return bytes(reversed(out))


def meta(kind, data):
    return bytes([0xFF, kind]) + vlq(len(data)) + data


def track(events, end_tick):
    """Events sorted by tick (note-offs first), then End of Track at end_tick."""
    out, now = b"", 0
    for tick, _, data in sorted(events, key=lambda e: (e[0], e[1], e[2])):
        if tick > end_tick:
            raise ValueError("an event after the song's end")
        out += vlq(tick - now) + data
        now = tick
    out += vlq(end_tick - now) + meta(0x2F, b"")
    return b"MTrk" + len(out).to_bytes(4, "big") + out


def song_bytes(song):
    num, den = song["meter"]
    bar_beats = num * 4.0 / den
    steps = num * 16 // den
    tempo_us = 60_000_000 // song["bpm"]
    if tempo_us * song["bpm"] != 60_000_000:
        raise ValueError(f"{song['file']}: pick a bpm that divides 60,000,000 (exact MIDI tempo)")
    mel, end = melody_events(song, bar_beats)
    drums, end2 = drum_events(song, bar_beats, steps)
    assert end == end2
    conductor = [
        (0, 0, meta(0x03, song["title"].encode("ascii"))),
        (0, 1, meta(0x01, b"Traditional (public domain); arrangement: the cubdance project")),
        (0, 2, meta(0x51, tempo_us.to_bytes(3, "big"))),
        (0, 3, meta(0x58, bytes([num, den.bit_length() - 1, 24, 8]))),
    ]
    melody = [(0, -2, meta(0x03, b"melody")), (0, -1, bytes([0xC0, song["program"]]))] + mel
    drum = [(0, -1, meta(0x03, b"drums"))] + drums
    header = b"MThd" + (6).to_bytes(4, "big") + (1).to_bytes(2, "big") + (3).to_bytes(2, "big")
    header += TPQ.to_bytes(2, "big")
    data = header + track(conductor, end) + track(melody, end) + track(drum, end)
    bars = sum(f[2] for f in song["form"])
    seconds = end / TPQ * tempo_us / 1e6
    return data, bars, seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap.add_argument("--out", default=os.path.join(root, "assets", "songs"))
    ap.add_argument("--check", action="store_true", help="compare, do not write")
    args = ap.parse_args()
    bad = 0
    for song in SONGS:
        data, bars, seconds = song_bytes(song)
        path = os.path.join(args.out, song["file"] + ".mid")
        if args.check:
            same = os.path.exists(path) and open(path, "rb").read() == data
            bad += not same
            print(f"{os.path.relpath(path)}: {'same' if same else 'DIFFERENT'}")
            continue
        os.makedirs(args.out, exist_ok=True)
        with open(path, "wb") as f:
            f.write(data)
        print(f"{os.path.relpath(path)}: \"{song['title']}\" {song['bpm']} bpm {song['meter'][0]}/{song['meter'][1]} "
              f"{bars} bars {seconds:.3f} s {len(data)} bytes")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Make a fakenect dump that plays a recording over and over for SECONDS:
INDEX.txt names one symbolic link per frame, each to a depth frame of the
recording, with the frame times (in the names, as fakenect-record writes
them) running on at the recording's own frame rate. Nothing is copied.

    scripts/soak_dump.py RECORDING OUT_DIR SECONDS

Only the depth frames are replayed (d-* lines); the Kinect's 60 MHz
timestamp wraps as the real counter does (the box follows the wraps)."""
import os
import re
import sys

NAME = re.compile(r"^d-([0-9.]+)-([0-9]+)\.pgm$")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    src, out, seconds = os.path.abspath(sys.argv[1]), sys.argv[2], float(sys.argv[3])
    frames = []
    for line in open(os.path.join(src, "INDEX.txt")):
        m = NAME.match(line.strip())
        if m:
            frames.append((line.strip(), float(m.group(1)), int(m.group(2))))
    if len(frames) < 2:
        sys.exit("soak_dump: %s: fewer than two depth frames" % src)
    period_s = (frames[-1][1] - frames[0][1]) / (len(frames) - 1)
    ticks = round(period_s * 60e6)  # the Kinect's clock runs at 60 MHz
    t0, ts0 = frames[0][1], frames[0][2]
    os.makedirs(out, exist_ok=True)
    count = int(seconds / period_s) + 1
    with open(os.path.join(out, "INDEX.txt"), "w") as index:
        for k in range(count):
            name = "d-%.6f-%u.pgm" % (t0 + k * period_s, (ts0 + k * ticks) % (1 << 32))
            link = os.path.join(out, name)
            if not os.path.lexists(link):
                os.symlink(os.path.join(src, frames[k % len(frames)][0]), link)
            index.write(name + "\n")
    print("soak_dump: %d frames (%.0f s) looping the %d of %s" % (count, count * period_s,
                                                                  len(frames), src))


if __name__ == "__main__":
    main()

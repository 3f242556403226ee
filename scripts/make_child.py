#!/usr/bin/env python3
"""make_child.py: a synthetic child that dances a whole song, with planted
mistakes, for the box's end-to-end replay (issue 5, "End to end").

    scripts/make_child.py sequence SONG PLAN OUT
        writes OUT/child.seq (a `cubtool synth-depth --sequence` file aligned
        to cubdance's loop time: frame k of the dump is loop time k/30 s) and
        OUT/expect.txt (every (move, rep) of the song: right or planted
        wrong, with the loop-time span the child acts it in).
    scripts/make_child.py check SONG PLAN TRUTH
        the TRUE joints (truth.txt of the rendered sequence) through the
        judge's fuzzy features: per move and repetition, each key's best
        membership over the repetition's window (start .. end + one beat),
        held for 100 ms as the judge needs (the min over 4 frames at 30 fps),
        and `all`: the keys together (the judge needs them in the same frames).
    scripts/make_child.py scan TRUTH KEY... [--from S --to S] [--every S]
        a clip's key memberships over time (KEY like RH=up), to pick segments.
    scripts/make_child.py score EXPECT LOG
        the judge's verdicts and the coach's corrections from a cubdance log
        against expect.txt: the table per repetition and the counts.

The end-to-end run (Twinkle; dumps are 614 KB a frame):
    scripts/make_child.py sequence assets/songs/twinkle.song.xml \
        scripts/child/twinkle.plan /tmp/e2e
    cubtool synth-depth --sequence /tmp/e2e/child.seq --out /tmp/e2e/dump
    cubdance --headless --size 64x48 --replay /tmp/e2e/dump --clock virtual \
        --song assets/songs/twinkle.song.xml --buttons scripts/demo.buttons \
        --log /tmp/e2e/events.log --seconds 110
    scripts/make_child.py score /tmp/e2e/expect.txt /tmp/e2e/events.log

Plan file (scripts/child/<song>.plan), '#' comments, one item a line:
    lead S                  loop time of the music's start (cubdance's
                            `music start` line; START pressed at 0.5 s)
    stand CLIP FROM TO      the segment that stands still (looped to fill)
    derive NAME SOURCE JOINT=K...  a clip of our own: the BVH SOURCE (under
                            the data dir) with each named joint's local
                            rotation's motion away from the first frame
                            scaled K times (axis-angle), e.g. the
                            arms of a jumping jack raised higher (real
                            clips rarely lift the upper arm past 135 deg,
                            where RH=up reaches 0.5); written as
                            OUT/NAME.bvh, usable as NAME in segments
    move CLIP SEG [SEG...]  one repetition of the song's move CLIP done
                            right, SEG = mocap `clip:from:to[:mirror]`; the
                            segments are played back to back and time-scaled
                            to the repetition's song span (cubtool cannot
                            change speed, so instead a segment's length is
                            cut or its end looped: see fit())
    mistake M R KIND [SEG...]  plant a mistake in move M (0-based song
                            order), repetition R (0-based): KIND still
                            (stand), wrong_arm (the right segments mirrored,
                            or SEGs given), no_jump (SEGs required: the move
                            without its jump / arms up)
    after S                 the child keeps doing the corrected move right
                            for S + one repetition after a mistake's late
                            beat (default 4 s: the correcting clip, <= 2.8
                            s, with the route into it and a margin)

What the child does after a planted mistake (the rule): the coach gives a
wrong verdict one beat after the repetition ends (the judge's late
allowance), cancels the open windows, plays a correcting clip (head shake /
watch me, ~2-3 s), then demonstrates the move at 0.7 speed with a window
open, and repeats that until a right verdict; then it resumes where the
music is. So the child
  1. acts the mistake over the repetition's span AND the beat after it (a
     pose reached inside that beat would still credit the late repetition,
     which would hide the mistake): `still` stands through it, the others
     stand for that beat;
  2. then does the corrected move right, back to back at its song tempo,
     for `after` seconds + one repetition (the correcting clip, then the
     slow demonstration's window, in which one repetition of the child
     reaches the keys), even when the song's span of that move has ended;
  3. then rejoins the song at the next repetition boundary of the music
     (whatever move the music is in then).
The repetitions the music passes meanwhile (the one after the mistake, the
coach's own window of which the correction cancels, and any the child
spends recovering) are marked `skip` in expect.txt: not counted.
Planted mistakes must be far enough apart that step 2 ends before the next
planted repetition starts (checked: an error otherwise)."""
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

FPS = 30.0
JOINTS = ("hip_centre spine shoulder_centre head shoulder_l elbow_l wrist_l hand_l "
          "shoulder_r elbow_r wrist_r hand_r hip_l knee_l ankle_l foot_l "
          "hip_r knee_r ankle_r foot_r").split()
J = {n: i for i, n in enumerate(JOINTS)}

# ---- the fuzzy features, as firmware/fuzzy does them (SEEDS.md § 000) ------

FEATURES = ["RH", "RHE", "LH", "LHE", "Posture", "Trunk", "RF", "RFK", "LF", "LFK"]
SETS = {
    "RH": ["down", "mid", "up"], "LH": ["down", "mid", "up"],
    "RHE": ["false", "true"], "LHE": ["false", "true"],
    "Posture": ["lie", "sit", "stand", "jump"], "Trunk": ["true", "false"],
    "RF": ["inward", "outward"], "LF": ["inward", "outward"],
    "RFK": ["true", "false"], "LFK": ["true", "false"],
}


def ramp(x, foot, top):
    if top == foot:
        return 0.0
    v = (x - foot) / (top - foot)
    return min(1.0, max(0.0, v))


def tri(x, lo, peak, hi):
    return ramp(x, lo, peak) if x <= peak else ramp(x, hi, peak)


def membership(feat, s, x):
    if feat in ("RH", "LH"):
        return {"down": ramp(x, 90, 20), "mid": tri(x, 20, 90, 180), "up": ramp(x, 90, 180)}[s]
    if feat in ("RHE", "LHE"):
        return {"false": ramp(x, 90, 0), "true": ramp(x, 20, 90)}[s]
    if feat == "Posture":
        return {"lie": ramp(x, 40, 0), "sit": tri(x, 0, 40, 80), "stand": tri(x, 40, 80, 120),
                "jump": ramp(x, 80, 120)}[s]
    if feat == "Trunk":
        return {"true": ramp(x, 180, 110), "false": ramp(x, 125, 180)}[s]
    if feat in ("RF", "LF"):
        return {"inward": ramp(x, 40, 0), "outward": ramp(x, 0, 40)}[s]
    if feat in ("RFK", "LFK"):
        return {"true": ramp(x, 180, 90), "false": ramp(x, 100, 180)}[s]
    raise ValueError(feat)


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def angle(a, b):
    na = math.sqrt(sum(v * v for v in a))
    nb = math.sqrt(sum(v * v for v in b))
    if na == 0 or nb == 0:
        return 0.0
    c = sum(x * y for x, y in zip(a, b)) / (na * nb)
    return math.degrees(math.acos(max(-1.0, min(1.0, c))))


def cog_y(w):
    seg = [(50, "hip_centre", "shoulder_centre"), (8, "head", "head"),
           (3, "shoulder_l", "elbow_l"), (3, "shoulder_r", "elbow_r"),
           (2, "elbow_l", "wrist_l"), (2, "elbow_r", "wrist_r"),
           (10, "hip_l", "knee_l"), (10, "hip_r", "knee_r"),
           (6, "knee_l", "ankle_l"), (6, "knee_r", "ankle_r")]
    s = sum(k * (w[J[a]][1] + w[J[b]][1]) for k, a, b in seg)
    return s / sum(2 * k for k, _, _ in seg)


def features(w, floor_y, stand_cog):
    """The ten inputs of one frame (w: 20 joints, camera space, y up)."""
    f = {}
    down = sub(w[J["hip_centre"]], w[J["shoulder_centre"]])
    for side, p in (("l", "L"), ("r", "R")):
        up = sub(w[J["elbow_" + side]], w[J["shoulder_" + side]])
        fore = sub(w[J["wrist_" + side]], w[J["elbow_" + side]])
        f[p + "H"] = angle(up, down)
        f[p + "HE"] = angle(up, fore)
        other = "r" if side == "l" else "l"
        out = sub(w[J["hip_" + side]], w[J["hip_" + other]])
        thigh = sub(w[J["knee_" + side]], w[J["hip_" + side]])
        f[p + "F"] = 90 - angle(thigh, out)
        f[p + "FK"] = angle(sub(w[J["hip_" + side]], w[J["knee_" + side]]),
                            sub(w[J["ankle_" + side]], w[J["knee_" + side]]))
    f["Posture"] = 80 * (cog_y(w) - floor_y) / stand_cog
    thighs = tuple(a + b for a, b in zip(sub(w[J["knee_l"]], w[J["hip_l"]]),
                                         sub(w[J["knee_r"]], w[J["hip_r"]])))
    f["Trunk"] = angle(sub(w[J["shoulder_centre"]], w[J["hip_centre"]]), thighs)
    return f


def read_truth(path):
    frames = []
    with open(path) as fh:
        for line in fh:
            if line.startswith("#") or line.startswith("gravity"):
                continue
            v = line.split()
            if len(v) < 3 + 80:
                continue
            w = [(float(v[3 + 4 * i]), float(v[4 + 4 * i]), float(v[5 + 4 * i])) for i in range(20)]
            frames.append(w)
    return frames


def truth_memberships(frames):
    """Per frame {feature: x} with the judge's online calibration: the floor
    follows the lower foot, the standing CoG starts at the first frame and
    follows at 1/64 a frame."""
    out = []
    floor = stand = None
    for w in frames:
        low = min(w[J["foot_l"]][1], w[J["foot_r"]][1])
        floor = low if floor is None or low < floor else floor + (low - floor) / 128
        cog = max(100.0, cog_y(w) - floor)
        stand = cog if stand is None else stand + (cog - stand) / 64
        out.append(features(w, floor, stand))
    return out


def held(series, n=4):
    """The best membership held over n consecutive frames (the judge's
    100 ms hold at 30 fps spans 4 frames)."""
    best = 0.0
    for i in range(len(series) - n + 1):
        best = max(best, min(series[i:i + n]))
    return best


def parse_key(k):
    f, s = k.split("=")
    if f not in SETS or s not in SETS[f]:
        raise ValueError("unknown key %s" % k)
    return f, s



# ---- derived clips: a BVH with some joints' rotations amplified ----------

def _qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


def _qaxis(axis, deg):
    h = math.radians(deg) / 2
    v = [0.0, 0.0, 0.0]
    v["XYZ".index(axis)] = math.sin(h)
    return (math.cos(h), v[0], v[1], v[2])


def _qmat(q):
    w, x, y, z = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def _euler(q, order):
    """Angles (degrees, in channel order) with R = R(order[0]) R(order[1])
    R(order[2]), for any of the six orders (Tait-Bryan)."""
    R = _qmat(q)
    i, j, k = ("XYZ".index(c) for c in order)
    sign = 1.0 if (j - i) % 3 == 1 else -1.0  # an even permutation of XYZ
    b = math.asin(max(-1.0, min(1.0, sign * R[i][k])))
    a = math.atan2(-sign * R[j][k], R[k][k])
    c = math.atan2(-sign * R[i][j], R[i][i])
    return [math.degrees(v) for v in (a, b, c)]


def _quat(angles, order):
    q = (1.0, 0.0, 0.0, 0.0)
    for ax, deg in zip(order, angles):
        q = _qmul(q, _qaxis(ax, deg))
    return q


def amplify_rotation(angles, order, k, ref=None):
    """The rotation's motion away from ref (angles of a reference frame, the
    clip's first: standing) scaled k times: q' = q0 (q0^-1 q)^k."""
    q = _quat(angles, order)
    q0 = _quat(ref, order) if ref is not None else (1.0, 0.0, 0.0, 0.0)
    q0i = (q0[0], -q0[1], -q0[2], -q0[3])
    q = _qmul(q0i, q)
    if q[0] < 0:
        q = tuple(-v for v in q)
    s = math.sqrt(q[1] ** 2 + q[2] ** 2 + q[3] ** 2)
    if s < 1e-9:
        return list(angles)
    half = math.atan2(s, q[0]) * k
    f = math.sin(half) / s
    q = (math.cos(half), q[1] * f, q[2] * f, q[3] * f)
    return _euler(_qmul(q0, q), order)


def derive_bvh(src, dst, amps):
    text = open(src).read()
    head, sep, motion = text.partition("MOTION")
    if not sep:
        raise ValueError("%s: no MOTION section" % src)
    cols, n = {}, 0
    name = None
    for line in head.splitlines():
        w = line.split()
        if w[:1] in (["ROOT"], ["JOINT"]):
            name = w[1]
        elif w[:1] == ["CHANNELS"]:
            chans = w[2:2 + int(w[1])]
            rot = [c[0] for c in chans if c.endswith("rotation")]
            first = n + next(i for i, c in enumerate(chans) if c.endswith("rotation"))
            cols[name] = (first, "".join(rot))
            n += len(chans)
    for jn, _ in amps:
        if jn not in cols:
            raise ValueError("%s: no joint %s" % (src, jn))
    lines = motion.strip("\n").split("\n")
    out = []
    ref = None
    for line in lines:
        v = line.split()
        if len(v) != n:
            out.append(line)
            continue
        vals = [float(x) for x in v]
        ref = ref or list(vals)
        for jn, k in amps:
            c0, order = cols[jn]
            vals[c0:c0 + 3] = amplify_rotation(vals[c0:c0 + 3], order, k, ref[c0:c0 + 3])
        out.append(" ".join("%.4f" % x for x in vals))
    with open(dst, "w") as fh:
        fh.write(head + "MOTION\n" + "\n".join(out) + "\n")


def data_dir():
    d = os.environ.get("CUB_DATA_DIR")
    if d:
        return d
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "data")


def make_derived(plan, out):
    """Write the plan's derived clips into out; returns {name: path}."""
    paths = {}
    for name, src, amps in plan["derive"]:
        path = os.path.abspath(os.path.join(out, name + ".bvh"))
        derive_bvh(os.path.join(data_dir(), src), path, amps)
        paths[name] = path
    return paths

# ---- the song and the plan --------------------------------------------------

def read_song(path):
    root = ET.parse(path).getroot()
    bpm = int(root.get("bpm"))
    num, den = (int(v) for v in root.get("meter").split("/"))
    bar_s = num * (4.0 / den) * 60.0 / bpm
    moves = []
    for m in root.findall("move"):
        start = (int(m.get("bar")) - 1) * bar_s
        span = int(m.get("bars")) * bar_s
        moves.append({"clip": m.get("clip"), "reps": int(m.get("reps")), "start": start,
                      "end": start + span, "keys": [parse_key(k) for k in m.get("keys").split()]})
    return {"bpm": bpm, "beat": 60.0 / bpm, "bar": bar_s, "length": int(root.get("bars")) * bar_s,
            "moves": moves}


def parse_seg(text, where):
    p = text.split(":")
    if len(p) not in (3, 4) or (len(p) == 4 and p[3] != "mirror"):
        raise ValueError("%s: segment %r is not clip:from:to[:mirror]" % (where, text))
    return (p[0], float(p[1]), float(p[2]), len(p) == 4)


def read_plan(path):
    plan = {"lead": 2.733, "stand": None, "moves": {}, "mistakes": [], "after": 4.0,
            "derive": []}
    for n, raw in enumerate(open(path), 1):
        line = raw.split("#", 1)[0].split()
        where = "%s:%d" % (path, n)
        if not line:
            continue
        kw, args = line[0], line[1:]
        if kw == "lead" and len(args) == 1:
            plan["lead"] = float(args[0])
        elif kw == "after" and len(args) == 1:
            plan["after"] = float(args[0])
        elif kw == "derive" and len(args) >= 3:
            amp = []
            for a in args[2:]:
                jn, _, k = a.partition("=")
                amp.append((jn, float(k)))
            plan["derive"].append((args[0], args[1], amp))
        elif kw == "stand" and len(args) == 3:
            plan["stand"] = (args[0], float(args[1]), float(args[2]), False)
        elif kw == "move" and len(args) >= 2:
            plan["moves"][args[0]] = [parse_seg(s, where) for s in args[1:]]
        elif kw == "mistake" and len(args) >= 3:
            kind = args[2]
            if kind not in ("still", "wrong_arm", "no_jump"):
                raise ValueError("%s: unknown mistake kind %r" % (where, kind))
            segs = [parse_seg(s, where) for s in args[3:]]
            if kind == "no_jump" and not segs:
                raise ValueError("%s: no_jump needs its segments" % where)
            plan["mistakes"].append((int(args[0]), int(args[1]), kind, segs))
        else:
            raise ValueError("%s: cannot read %r" % (where, raw.strip()))
    if not plan["stand"]:
        raise ValueError("%s: no `stand` segment" % path)
    return plan


def fit(segs, dur):
    """Segments that fill exactly dur seconds: the right take cut short when
    longer, its segments looped when shorter (a child repeats the motion)."""
    out, t = [], 0.0
    while t < dur - 1e-6:
        for clip, a, b, mir in segs:
            take = min(b - a, dur - t)
            if take < 0.05:
                t = dur
                break
            out.append((clip, a, a + take, mir))
            t += take
            if t >= dur - 1e-6:
                break
    return out


def build(song, plan):
    """The child's timeline in loop time: a list of (t0, t1, segs, label),
    and the expectations."""
    lead, beat = plan["lead"], song["beat"]
    moves = song["moves"]
    for m in moves:
        if m["clip"] not in plan["moves"]:
            raise ValueError("the plan has no segments for move %r" % m["clip"])
    reps = []  # (music t0, t1, move index, rep)
    for i, m in enumerate(moves):
        d = (m["end"] - m["start"]) / m["reps"]
        for r in range(m["reps"]):
            reps.append((m["start"] + r * d, m["start"] + (r + 1) * d, i, r))
    mist = {(mi, r): (kind, segs) for mi, r, kind, segs in plan["mistakes"]}
    for key in mist:
        if not any((x[2], x[3]) == key for x in reps):
            raise ValueError("mistake at move %d rep %d: no such repetition" % key)
    tl = []  # music-time pieces: (t0, t1, segs, label)
    recover = []  # music time from a mistake's end to the child's rejoining
    t = 0.0
    busy_until = -1.0
    for t0, t1, mi, r in reps:
        if t0 < busy_until - 1e-6:
            if (mi, r) in mist:
                raise ValueError("mistake at move %d rep %d falls inside the recovery of an "
                                 "earlier one (until music %.2f s)" % (mi, r, busy_until))
            continue
        if t0 > t + 1e-6:
            tl.append((t, t0, [plan["stand"]], "gap"))
        name = moves[mi]["clip"]
        if (mi, r) not in mist:
            tl.append((t0, t1, plan["moves"][name], "%d.%d right" % (mi, r)))
            t = t1
            continue
        kind, segs = mist[(mi, r)]
        if kind == "still":
            segs = [plan["stand"]]
        elif kind == "wrong_arm" and not segs:
            segs = [(c, a, b, not mir) for c, a, b, mir in plan["moves"][name]]
        tl.append((t0, t1, segs, "%d.%d %s" % (mi, r, kind)))
        tl.append((t1, t1 + beat, [plan["stand"]], "late beat"))
        # then the move right, back to back at its song tempo, for `after` s
        rep_s = (moves[mi]["end"] - moves[mi]["start"]) / moves[mi]["reps"]
        fix_end = t1 + beat + plan["after"] + rep_s
        u = t1 + beat
        while u < fix_end - 1e-6:
            tl.append((u, min(u + rep_s, fix_end), plan["moves"][name], "%d fix" % mi))
            u = min(u + rep_s, fix_end)
        # rejoin at the next repetition boundary (or gap) of the music
        nxt = [x[0] for x in reps if x[0] >= u - 1e-6]
        ends = [m["end"] for m in moves if m["end"] >= u - 1e-6]
        cands = nxt + ends
        t = u
        busy_until = min(cands) if cands else u
        recover.append((t1, busy_until))
        if busy_until > u + 1e-6:
            tl.append((u, busy_until, [plan["stand"]], "wait"))
            t = busy_until
    if song["length"] + 3 > t:
        tl.append((t, song["length"] + 3, [plan["stand"]], "outro"))
    loop = [(0.0, lead, [plan["stand"]], "lead-in")]
    loop += [(a + lead, b + lead, s, lab) for a, b, s, lab in tl]
    expect = []
    for t0, t1, mi, r in reps:
        tag = "wrong:" + mist[(mi, r)][0] if (mi, r) in mist else "right"
        if tag == "right" and any(t0 < b - 1e-6 and t1 > a + 1e-6 for a, b in recover):
            tag = "skip"
        expect.append((mi, r, moves[mi]["clip"], tag, t0 + lead, t1 + lead))
    return loop, expect


def write_sequence(loop, path, derived):
    """cubtool plays segments back to back (blending over 0.3 s without
    adding time), so the pieces' durations add up to loop time."""
    with open(path, "w") as fh:
        fh.write("# made by scripts/make_child.py: loop time = frame / 30\n")
        for t0, t1, segs, label in loop:
            fh.write("# %.3f .. %.3f %s\n" % (t0, t1, label))
            for clip, a, b, mir in fit(segs, t1 - t0):
                fh.write("%s %.4f %.4f%s\n" % (derived.get(clip, clip), a, b,
                                               " mirror" if mir else ""))


def cmd_sequence(song_path, plan_path, out):
    song, plan = read_song(song_path), read_plan(plan_path)
    loop, expect = build(song, plan)
    os.makedirs(out, exist_ok=True)
    write_sequence(loop, os.path.join(out, "child.seq"), make_derived(plan, out))
    with open(os.path.join(out, "expect.txt"), "w") as fh:
        fh.write("# move rep clip expected loop_from_s loop_to_s\n")
        for mi, r, clip, tag, a, b in expect:
            fh.write("%d %d %s %s %.3f %.3f\n" % (mi, r, clip, tag, a, b))
    print("make_child: %s and %s: %.1f s, %d repetitions, %d planted wrong"
          % (os.path.join(out, "child.seq"), os.path.join(out, "expect.txt"), loop[-1][1],
             len(expect), sum(1 for e in expect if e[3].startswith("wrong"))))


def cmd_scan(truth, keys, t_from, t_to, every):
    feats = truth_memberships(read_truth(truth))
    ts = [float(l.split()[1]) for l in open(truth) if l[:1].isdigit()][:2]
    fps = 1.0 / (ts[1] - ts[0]) if len(ts) == 2 else FPS
    ks = [parse_key(k) for k in keys]
    print("t_s  " + " ".join("%9s" % k for k in keys) + "   inputs")
    step = max(1, int(round(every * fps)))
    for i in range(int(t_from * fps), min(len(feats), int(t_to * fps) + 1), step):
        f = feats[i]
        mus = [membership(a, s, f[a]) for a, s in ks]
        print("%5.2f " % (i / fps) + " ".join("%9.2f" % m for m in mus) + "   " +
              " ".join("%s=%.0f" % (a, f[a]) for a, _ in ks))


def cmd_check(song_path, plan_path, truth):
    song, plan = read_song(song_path), read_plan(plan_path)
    _, expect = build(song, plan)
    feats = truth_memberships(read_truth(truth))
    ok = True
    print("%-14s %4s %-16s %s" % ("move", "rep", "expected", "best held membership per key "
                                   "(window: rep .. +1 beat)"))
    for mi, r, clip, tag, a, b in expect:
        i0, i1 = int(round(a * FPS)), min(len(feats), int(round((b + song["beat"]) * FPS)))
        cols = []
        for f, s in song["moves"][mi]["keys"]:
            v = held([membership(f, s, feats[i][f]) for i in range(i0, i1)])
            cols.append((f + "=" + s, v))
        # the judge needs every key >= 0.5 in the same frames, held 100 ms
        both = held([min(membership(f, s, feats[i][f]) for f, s in song["moves"][mi]["keys"])
                     for i in range(i0, i1)])
        cols.append(("all", both))
        reached = both >= 0.5
        if tag == "skip":
            cols = cols
        good = tag == "skip" or reached == (tag == "right")
        ok &= good
        print("%-14s %4d %-16s %s  %s" % (clip, r, tag, "  ".join("%s %.2f" % c for c in cols),
                                          "" if good else "<-- truth disagrees"))
    return 0 if ok else 1


def cmd_score(expect_path, log_path):
    expect = []
    for line in open(expect_path):
        if line.startswith("#") or not line.strip():
            continue
        v = line.split()
        expect.append((int(v[0]), int(v[1]), v[2], v[3]))
    verdicts = {}
    corrected = {}
    vre = re.compile(r"t=\s*([\d.]+).*judge verdict move=(\d+) rep=(\d+) result=(\w+)(.*)")
    # the coach's state line names its own position (the next repetition):
    # a correction belongs to the wrong verdict logged at the same time
    cre = re.compile(r"t=\s*([\d.]+).*coach state .*to=(correct|worried) reason=(wrong|misses)")
    last_wrong = None
    for line in open(log_path):
        m = vre.search(line)
        if m:
            key = (int(m.group(2)), int(m.group(3)))
            verdicts.setdefault(key, []).append((float(m.group(1)), m.group(4),
                                                 m.group(5).strip()))
            if m.group(4) == "wrong":
                last_wrong = (float(m.group(1)), key)
        m = cre.search(line)
        if m and last_wrong and abs(last_wrong[0] - float(m.group(1))) < 1e-6:
            corrected.setdefault(last_wrong[1], []).append(float(m.group(1)))
    caught = missed = false_fix = right_ok = unjudged = 0
    print("%4s %4s %-14s %-16s %-8s %-9s %s" % ("move", "rep", "clip", "planted", "verdict",
                                                 "corrected", "detail"))
    for mi, r, clip, tag in expect:
        v = verdicts.get((mi, r), [])
        first = v[0][1] if v else "-"
        corr = (mi, r) in corrected
        if tag == "skip":
            pass
        elif tag == "right":
            if corr or first == "wrong":
                false_fix += 1
            elif v:
                right_ok += 1
            else:
                unjudged += 1
        else:
            if corr and first == "wrong":
                caught += 1
            else:
                missed += 1
        detail = "; ".join("t=%.2f %s %s" % x for x in v[:3])
        print("%4d %4d %-14s %-16s %-8s %-9s %s" % (mi, r, clip, tag if tag != "right" else "-",
                                                    first, "yes" if corr else "-", detail))
    planted = sum(1 for e in expect if e[3].startswith("wrong"))
    print("e2e: planted mistakes caught=%d missed=%d of %d; correct repetitions wrongly "
          "corrected=%d, right=%d, without a verdict=%d" % (caught, missed, planted, false_fix,
                                                            right_ok, unjudged))
    return 0 if missed == 0 and false_fix == 0 else 1


def main(argv):
    if len(argv) >= 4 and argv[0] == "sequence":
        cmd_sequence(argv[1], argv[2], argv[3])
        return 0
    if len(argv) >= 4 and argv[0] == "check":
        return cmd_check(argv[1], argv[2], argv[3])
    if len(argv) >= 3 and argv[0] == "score":
        return cmd_score(argv[1], argv[2])
    if len(argv) >= 3 and argv[0] == "scan":
        t_from, t_to, every, keys = 0.0, 1e9, 0.1, []
        it = iter(argv[2:])
        for a in it:
            if a == "--from":
                t_from = float(next(it))
            elif a == "--to":
                t_to = float(next(it))
            elif a == "--every":
                every = float(next(it))
            else:
                keys.append(a)
        cmd_scan(argv[1], keys, t_from, t_to, every)
        return 0
    sys.stderr.write(__doc__)
    return 2


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except (ValueError, OSError) as e:
        sys.stderr.write("make_child: %s\n" % e)
        sys.exit(2)

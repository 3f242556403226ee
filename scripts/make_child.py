#!/usr/bin/env python3
"""make_child.py: a synthetic child that dances a whole song with the bear,
with planted mistakes, for the box's end-to-end replay (issue 5, "End to
end"; scripts/e2e_child.sh runs it all).

    scripts/make_child.py sequence SONG PLAN OUT [CUES]
        writes OUT/child.seq (a `cubtool synth-depth --sequence` file aligned
        to cubdance's loop time: frame k of the dump is loop time k/30 s) and
        OUT/expect.txt (every coach request the child follows, and for each
        move the coach leads the verdict expected: right or planted wrong).
        CUES: the coach's `coach request` lines (a cubdance log, or
        scripts/child/<song>.cues); without, the song's own timing.
    scripts/make_child.py expect SONG PLAN OUT [CUES]
        only OUT/expect.txt (no mocap read): for scoring a child rendered
        from its joint track (scripts/child/twinkle.jtrack, scripts/demo.sh).
    scripts/make_child.py check SONG PLAN TRUTH [CUES]
        the TRUE joints (truth.txt of the rendered sequence) through the
        judge's fuzzy features: per window the coach opens, each key's best
        membership (held for 100 ms, the min over 4 frames at 30 fps), and
        `all`: the keys together (the judge needs them in the same frames).
    scripts/make_child.py scan TRUTH KEY... [--from S --to S] [--every S]
        a clip's key memberships over time (KEY like RH=up), to pick segments.
    scripts/make_child.py derive PLAN OUT
        writes the plan's derived clips (its `derive` lines) as OUT/NAME.bvh
        (scripts/eval_tracker.sh measures the tracker on them).
    scripts/make_child.py move TRACK MOVING OUT
        the moving child (--child moving; sequence writes OUT/child.moving,
        its facing and spot over time): the joint track TRACK (synth-depth
        --write-track of child.seq) turned and carried accordingly, as OUT.
    scripts/make_child.py score EXPECT LOG
        the judge's verdicts and the coach's corrections in a cubdance log
        against expect.txt: the table per window and the counts; fails when
        a planted mistake is not corrected, a move done right is corrected
        or not judged at all, or the coach did not do what the child
        followed (a move done right judged wrong without a correction, the
        coach having moved on, or judged unsure, is counted apart).

The child follows the bear, as a child in front of the TV does: each move
the coach leads (a repetition, a resume, a slow demonstration) it does
right, REACT seconds after the bear starts it, stretched to the bear's
span; while the bear corrects (head shake, "watch me"), idles or cheers, it
stands and watches. A planted mistake replaces the move the first time the
coach leads that repetition and lasts one beat into what follows (a pose
in that beat would still count for the late repetition). What the coach
does depends on the verdicts, so the child's timeline is found by
following the box's own log until it repeats itself (e2e_child.sh
--remake); the result is committed as scripts/child/<song>.cues.

Plan file (scripts/child/<song>.plan), '#' comments, one item a line:
    lead S                  loop time of the music's start (cubdance's
                            `music start` line; START pressed at 0.5 s),
                            for the first guess from the song's timing
    stand CLIP FROM TO      the segment that stands still (looped to fill)
    derive NAME SOURCE JOINT=K...  a clip of our own: the BVH SOURCE (under
                            the data dir) with each named joint's local
                            rotation's motion away from the first frame
                            scaled K times (axis-angle), e.g. the
                            arms of a jumping jack raised higher (real
                            clips rarely lift the upper arm past 135 deg,
                            where RH=up reaches 0.5); written as
                            OUT/NAME.bvh, usable as NAME in segments
    move CLIP SEG [SEG...]  one repetition of the bear's clip CLIP done
                            right, SEG = mocap `clip:from:to[:mirror]`; the
                            segments are played back to back (synth-depth
                            turns each to face the camera) and fitted to
                            the bear's span (cubtool cannot change speed,
                            so a longer take is cut, a shorter one looped:
                            see fit())
    mistake M R KIND [SEG...]  plant a mistake in move M (0-based song
                            order), repetition R (0-based): KIND still
                            (stand), wrong_arm (the right segments mirrored,
                            or SEGs given), no_jump (SEGs required: the move
                            without its jump / arms up)
"""
import math
import os
import random
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


def legs(w):
    """The mean length of the two legs, hip-knee-ankle (the judge's unit of
    a foot's lift)."""
    n = sum(math.dist(w[J[a + s]], w[J[b + s]]) for s in ("_l", "_r")
            for a, b in (("hip", "knee"), ("knee", "ankle")))
    return max(n / 2, 1e-9)


def key_membership(frame, feat, s):
    """A key's membership as the judge reads it: a leg is out only as far
    as its foot is lifted above the other (cub/judge.h, kick_lift 0.10)."""
    m = membership(feat, s, frame[feat])
    if feat in ("RF", "LF") and s == "outward":
        m = min(m, ramp(frame[feat + "_lift"], 0.05, 0.15))
    return m


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
        f[p + "F_lift"] = (w[J["ankle_" + side]][1] - w[J["ankle_" + other]][1]) / legs(w)
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
    plan = {"lead": 2.733, "stand": None, "moves": {}, "mistakes": [],
            "derive": []}
    for n, raw in enumerate(open(path), 1):
        line = raw.split("#", 1)[0].split()
        where = "%s:%d" % (path, n)
        if not line:
            continue
        kw, args = line[0], line[1:]
        if kw == "lead" and len(args) == 1:
            plan["lead"] = float(args[0])
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


REACT = 0.3   # a child starts what the bear shows this long after the bear
LATE = 0.5    # the late child (--child late): follows the bear this long after it
SLOPPY = 0.5  # the sloppy child (--child sloppy): the non-key joints' motion scaled so

# The BVH joints whose rotation moves each feature, under both namings of the
# data (CMU's LeftArm/LeftForeArm/LeftUpLeg, animdraw's LeftShoulder/LeftElbow/
# LeftHip; CMU's LeftShoulder is the collar): a sloppy child does the key
# joints fully and every other of these joints at half amplitude.
_ARM = {"H": ("Collar", "Shoulder", "Arm"), "HE": ("Elbow", "ForeArm")}
_LEG = {"F": ("Hip", "UpLeg", "HipJoint"), "FK": ("Knee", "Leg")}
_TRUNK = ("lowerback", "LowerBack", "Chest", "Chest2", "Spine", "Spine1")


def feature_joints(feat):
    side = {"R": ("Right", "R"), "L": ("Left", "L")}
    if feat == "Trunk":
        return set(_TRUNK)
    if feat == "Posture":  # body height: both legs and the trunk
        return set().union(*(feature_joints(f) for f in ("RF", "RFK", "LF", "LFK", "Trunk")))
    long_, short = side[feat[0]]
    group = _ARM.get(feat[1:]) or _LEG.get(feat[1:])
    return {(short if n == "HipJoint" else long_) + n for n in group}


ALL_FEATURE_JOINTS = set().union(*(feature_joints(f) for f in FEATURES))
DANCE = ("move", "rep", "resume", "demo")   # coach requests that lead a move
CUE = re.compile(r"t=\s*([\d.]+) coach request clip=(\S+) .*?reason=(\w+)"
                 r"(?: move=(\d+) rep=(\d+))?")


def read_cues(path):
    """The coach's requests, (t, clip, reason, move, rep), from a cubdance
    event log or a cues file (the same `coach request` lines)."""
    cues = []
    for n, line in enumerate(open(path), 1):
        m = CUE.search(line)
        if not m:
            continue
        mv = int(m.group(4)) if m.group(4) is not None else -1
        rp = int(m.group(5)) if m.group(5) is not None else -1
        cues.append((float(m.group(1)), m.group(2), m.group(3), mv, rp))
    if not cues:
        raise ValueError("%s: no `coach request` lines" % path)
    return cues


def cues_from_song(song, plan):
    """Cues as if the coach led every repetition on the music's beat, with
    no correction: the first guess the child follows."""
    cues, lead = [], plan["lead"]
    for i, m in enumerate(song["moves"]):
        d = (m["end"] - m["start"]) / m["reps"]
        for r in range(m["reps"]):
            cues.append((lead + m["start"] + r * d, m["clip"], "move" if r == 0 else "rep", i, r))
    cues.append((lead + song["length"], "cheer", "song_end", -1, -1))
    return cues


def build(song, plan, cues, react=REACT):
    """The child's timeline in loop time, (t0, t1, segs, label), following
    the coach: every move the bear leads (a repetition, a resume, a slow
    demonstration) the child does right REACT s later, fitted to the bear's
    span; anything else (a correcting clip, idle, the cheer) it watches,
    standing. A planted mistake replaces the move the first time the coach
    leads that repetition, and lasts one beat into what follows (a pose
    reached in that beat would still count for the late repetition).
    Returns the timeline and the expected windows, (cue index, t0, t1,
    move, rep, expected)."""
    beat, stand = song["beat"], [plan["stand"]]
    for _, clip, reason, _, _ in cues:
        if reason in DANCE and clip not in plan["moves"]:
            raise ValueError("the plan has no segments for move %r" % clip)
    mist = {(mi, r): (kind, segs) for mi, r, kind, segs in plan["mistakes"]}
    end = cues[-1][0] + 3.0
    tl, expect, planted = [(0.0, cues[0][0] + react, stand, "lead-in")], [], set()
    t = tl[0][1]
    for i, (tc, clip, reason, mi, r) in enumerate(cues):
        nxt = cues[i + 1][0] if i + 1 < len(cues) else end - react
        t0, t1 = max(tc + react, t), nxt + react
        wrong = reason in ("move", "rep") and (mi, r) in mist and (mi, r) not in planted
        if wrong:
            planted.add((mi, r))
        if reason in DANCE:
            expect.append((i, tc, nxt, mi, r, "wrong:" + mist[(mi, r)][0] if wrong else "right"))
        if t1 <= t0 + 1e-6:
            continue
        if reason not in DANCE:
            tl.append((t0, t1, stand, "watch " + clip))
        elif wrong:
            kind, segs = mist[(mi, r)]
            if kind == "still":
                segs = stand
            elif kind == "wrong_arm" and not segs:
                segs = [(c, a, b, not mir) for c, a, b, mir in plan["moves"][clip]]
            tl.append((t0, t1, segs, "%d.%d %s" % (mi, r, kind)))
            tl.append((t1, t1 + beat, stand, "late beat"))
            t1 += beat
        else:
            tl.append((t0, t1, plan["moves"][clip], "%d.%d %s" % (mi, r, reason)))
        t = t1
    for key in mist:
        if key not in planted:  # the score counts it missed
            sys.stderr.write("make_child: warning: the mistake at move %d rep %d is not planted: "
                             "the coach never leads that repetition\n" % key)
            expect.append((-1, 0.0, 0.0, key[0], key[1], "unled:" + mist[key][0]))
    return tl, expect


# ---- the moving child (--child moving): turning, moving about, an adult --------
# Fixed before any run (the figures are held out for the tracker and the
# judge). While the child watches (the lead-in, a correction, idle, the
# cheer) it turns to look about the room (at a parent): MOVE_AWAY_DEG
# degrees to a side drawn at random, turned to in the first TURN_S of the
# stretch (a third of it when shorter), and back, to a new facing within
# +-MOVE_FACE_DEG, in its last TURN_S; over the whole stretch it moves to a
# new spot drawn in MOVE_X_MM x MOVE_Z_MM about its first (x: to the
# camera's right, z: farther; it glides, its feet do not step), as far
# towards it as MOVE_SPEED_MM_S takes it in the stretch. It dances
# each move from that spot, facing that way. An adult (MOVE_ADULT, 1.65 m)
# stands behind it all song long: synth-depth's second person, 0.7 m to
# the right of and 0.9 m behind the child's first spot.
MOVE_SEED = 20
MOVE_AWAY_DEG = (30.0, 60.0)
MOVE_FACE_DEG = 15.0
MOVE_X_MM = (-500.0, 500.0)
MOVE_Z_MM = (-250.0, 500.0)   # nearer than about 1.95 m the feet leave the view
TURN_S = 0.5
MOVE_SPEED_MM_S = 600.0
MOVE_ADULT = "dataset-1_call_normal_002"  # a parent calling the child


def watching(label):
    return label == "lead-in" or label.startswith("watch ")


def moving_keys(loop):
    """The moving child's facing and spot over loop time: key lists
    [(t, yaw_deg)] and [(t, x_mm, z_mm)], smoothstepped between keys."""
    rng = random.Random(MOVE_SEED)
    stretches = []
    for t0, t1, _, label in loop:
        if not watching(label):
            continue
        if stretches and abs(stretches[-1][1] - t0) < 1e-6:
            stretches[-1][1] = t1
        else:
            stretches.append([t0, t1])
    yaw, x, z = 0.0, 0.0, 0.0
    yaws, spots = [(0.0, yaw)], [(0.0, x, z)]
    for a, b in stretches:
        r = min(TURN_S, (b - a) / 3)
        away = rng.choice((-1, 1)) * rng.uniform(*MOVE_AWAY_DEG)
        face = rng.uniform(-MOVE_FACE_DEG, MOVE_FACE_DEG)
        nx, nz = rng.uniform(*MOVE_X_MM), rng.uniform(*MOVE_Z_MM)
        go = min(1.0, MOVE_SPEED_MM_S * (b - a) / max(1e-6, math.hypot(nx - x, nz - z)))
        nx, nz = x + (nx - x) * go, z + (nz - z) * go
        yaws += [(a, yaw), (a + r, yaw + away), (b - r, yaw + away), (b, face)]
        spots += [(a, x, z), (b, nx, nz)]
        yaw, x, z = face, nx, nz
    return yaws, spots


def write_moving(loop, path):
    yaws, spots = moving_keys(loop)
    with open(path, "w") as fh:
        fh.write("# made by scripts/make_child.py (--child moving): the child's facing\n"
                 "# (yaw t_s deg, + = to its left) and spot (spot t_s x_mm z_mm) over\n"
                 "# loop time, smoothstepped between keys (`make_child.py move` applies\n"
                 "# them), and the adult behind (synth-depth --second-person)\n")
        for t, v in yaws:
            fh.write("yaw %.3f %.2f\n" % (t, v))
        for t, vx, vz in spots:
            fh.write("spot %.3f %.1f %.1f\n" % (t, vx, vz))
        fh.write("adult %s\n" % MOVE_ADULT)


def read_moving(path):
    yaws, spots = [], []
    for n, line in enumerate(open(path), 1):
        v = line.split("#", 1)[0].split()
        if not v:
            continue
        try:
            if v[0] == "yaw" and len(v) == 3:
                yaws.append((float(v[1]), float(v[2])))
                continue
            if v[0] == "adult" and len(v) == 2:
                continue
            if v[0] == "spot" and len(v) == 4:
                spots.append((float(v[1]), float(v[2]), float(v[3])))
                continue
        except ValueError:
            pass
        raise ValueError("%s:%d: expected 'yaw T DEG' or 'spot T X Z', got %r"
                         % (path, n, line.strip()))
    if not yaws or not spots:
        raise ValueError("%s: no yaw or no spot keys" % path)
    return yaws, spots


def at(keys, t):
    """Keys (t, v...) smoothstepped between, held before the first and
    after the last."""
    if t <= keys[0][0]:
        return keys[0][1:]
    for k0, k1 in zip(keys, keys[1:]):
        if t <= k1[0]:
            d = k1[0] - k0[0]
            w = 1.0 if d <= 1e-9 else (t - k0[0]) / d
            w = w * w * (3 - 2 * w)
            return tuple(a + (b - a) * w for a, b in zip(k0[1:], k1[1:]))
    return keys[-1][1:]


JT_POINTS = 21   # cub/synth.h: the 20 joints, then the top of the head
JT_ZERO = ord("@") + 31
JT_TOKEN = re.compile(r"[@-~]|\((-?\d+)\)")


def read_jtrack(path):
    """A joint track (cub/synth.h): its comment lines, fps, unit and frames
    (lists of 63 values in units)."""
    head, hdr, frames = [], {}, []
    for n, line in enumerate(open(path), 1):
        s = line.strip()
        if not s or s.startswith("#"):
            if not hdr:
                head.append(line)
            continue
        if len(hdr) < 4:
            v = s.split()
            want = ("cub-jtrack", "fps", "unit_mm", "frames")[len(hdr)]
            try:
                if len(v) != 2 or v[0] != want:
                    raise ValueError
                hdr[want] = float(v[1])
            except ValueError:
                raise ValueError("%s:%d: expected '%s VALUE' (a joint track's header), got %r"
                                 % (path, n, want, s[:40])) from None
            continue
        vals, pos = [], 0
        while pos < len(s):
            m = JT_TOKEN.match(s, pos)
            if not m:
                raise ValueError("%s:%d: bad residual at %r" % (path, n, s[pos:pos + 8]))
            vals.append(int(m.group(1)) if m.group(1) else ord(m.group(0)) - JT_ZERO)
            pos = m.end()
        if len(vals) != JT_POINTS * 3:
            raise ValueError("%s:%d: %d values, not %d" % (path, n, len(vals), JT_POINTS * 3))
        pred = jt_predict(frames)
        frames.append([p + r for p, r in zip(pred, vals)])
    if len(hdr) < 4 or not frames:
        raise ValueError("%s: not a joint track (no header or no frames)" % path)
    return head, hdr["fps"], hdr["unit_mm"], frames


def jt_predict(frames):
    """The constant-velocity guess of the next frame from the ones before."""
    if not frames:
        return [0] * (JT_POINTS * 3)
    if len(frames) == 1:
        return frames[0]
    return [2 * a - b for a, b in zip(frames[-1], frames[-2])]


def write_jtrack(path, head, fps, unit, frames):
    def ch(r):
        return chr(JT_ZERO + r) if -31 <= r <= 31 else "(%d)" % r
    with open(path, "w") as fh:
        fh.writelines(head)
        fh.write("cub-jtrack 1\nfps %g\nunit_mm %g\nframes %d\n" % (fps, unit, len(frames)))
        for f, cur in enumerate(frames):
            pred = jt_predict(frames[max(0, f - 2):f])
            fh.write("".join(ch(c - p) for c, p in zip(cur, pred)) + "\n")


def cmd_move(track_in, moving, track_out):
    """The performance turned about its hips and carried to its spot, frame
    by frame, as synth-depth turns one (+ = to the body's left)."""
    yaws, spots = read_moving(moving)
    head, fps, unit, frames = read_jtrack(track_in)
    out = []
    for f, q in enumerate(frames):
        t = f / fps
        (deg,), (dx, dz) = at(yaws, t), at(spots, t)
        th = math.radians(deg)
        c, n = math.cos(th), math.sin(th)
        cx, cz = q[0] * unit, q[2] * unit   # the hip centre is point 0
        p = []
        for j in range(JT_POINTS):
            x, z = q[3 * j] * unit - cx, q[3 * j + 2] * unit - cz
            p += [int(round((cx + x * c + z * n + dx) / unit)), q[3 * j + 1],
                  int(round((cz - x * n + z * c + dz) / unit))]
        out.append(p)
    write_jtrack(track_out, head, fps, unit, out)
    print("make_child: %s: %d frames turned and moved (%s)" % (track_out, len(out), moving))


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


def plan_and_cues(song_path, plan_path, cues_path):
    song, plan = read_song(song_path), read_plan(plan_path)
    cues = read_cues(cues_path) if cues_path else cues_from_song(song, plan)
    return song, plan, cues


def mocap_bvh(clip):
    """A short clip name as cubtool resolves it, when it is a BVH (None for
    an AMC-only take, which cannot be re-scaled here)."""
    for rel in ("cmu/%s.bvh", "cmu/daz43/%s.bvh", "animdraw/fair1/%s.bvh",
                "animdraw/cmu1/%s.bvh", "animdraw/rokoko/%s.bvh", "bandai/data/%s.bvh"):
        path = os.path.join(data_dir(), "mocap", rel % clip)
        if os.path.exists(path):
            return path
    return None


def bvh_joints(path):
    return {l.split()[1] for l in open(path) if l.split()[:1] in (["ROOT"], ["JOINT"])}


def make_sloppy(song, plan, out):
    """The sloppy child: every move's segments re-derived with the joints of
    features that are not the move's keys at SLOPPY of their motion (on top
    of a derived clip's own scaling). Rewrites plan["moves"]; returns the
    derived paths."""
    derives = {name: (src, dict(amps)) for name, src, amps in plan["derive"]}
    paths = {}
    for m in song["moves"]:
        keep = set().union(*(feature_joints(f) for f, _ in m["keys"]))
        segs = []
        for clip, a, b, mir in plan["moves"].get(m["clip"], []):
            src, amps = derives.get(clip, (None, {}))
            src = os.path.join(data_dir(), src) if src else mocap_bvh(clip)
            if not src:
                sys.stderr.write("make_child: warning: %s is no BVH: the sloppy child does it "
                                 "as recorded\n" % clip)
                segs.append((clip, a, b, mir))
                continue
            loose = (ALL_FEATURE_JOINTS - keep) & bvh_joints(src)
            scaled = [(j, amps.get(j, 1.0) * (SLOPPY if j in loose else 1.0))
                      for j in sorted(loose | set(amps))]
            name = "%s_sloppy_%s" % (clip, m["clip"])
            path = os.path.abspath(os.path.join(out, name + ".bvh"))
            derive_bvh(src, path, scaled)
            paths[name] = path
            segs.append((name, a, b, mir))
        plan["moves"][m["clip"]] = segs
    return paths


def write_expect(path, song, cues, expect, child):
    dance = {e[0]: e[5] for e in expect}
    with open(path, "w") as fh:
        fh.write("# every coach request the child follows: t_s clip reason move rep, and for\n"
                 "# the moves the verdict expected (right, or the planted wrong:KIND)\n")
        fh.write("beat %.4f\n" % song["beat"])
        fh.write("child %s\n" % child)
        for i, (tc, clip, reason, mi, r) in enumerate(cues):
            tag = dance.get(i, "-")
            fh.write("%.3f %s %s %d %d %s\n" % (tc, clip, reason, mi, r, tag))
        for e in expect:
            if e[0] < 0:
                fh.write("unled %d %d %s\n" % (e[3], e[4], e[5]))


def cmd_sequence(song_path, plan_path, out, cues_path, child="planted", clips=True):
    """clips False: expect.txt only (no mocap needed: the demo's shipped
    child brings its performance as a joint track)."""
    song, plan, cues = plan_and_cues(song_path, plan_path, cues_path)
    os.makedirs(out, exist_ok=True)
    derived = make_derived(plan, out) if clips else {}
    if child not in ("planted", "moving"):  # the late and the sloppy child make no mistake
        plan["mistakes"] = []
    if child == "sloppy" and clips:
        derived.update(make_sloppy(song, plan, out))
    loop, expect = build(song, plan, cues, LATE if child == "late" else REACT)
    if clips:
        write_sequence(loop, os.path.join(out, "child.seq"), derived)
        if child == "moving":
            write_moving(loop, os.path.join(out, "child.moving"))
    write_expect(os.path.join(out, "expect.txt"), song, cues, expect, child)
    print("make_child: %s%s: %.1f s, the coach's %d requests (%s), %d moves led, "
          "%d planted wrong" % (os.path.join(out, "child.seq") + " and " if clips else "",
                                os.path.join(out, "expect.txt"),
                                loop[-1][1], len(cues), cues_path or "from the song",
                                sum(1 for e in expect if e[0] >= 0),
                                sum(1 for e in expect if e[5] != "right")))


def cmd_scan(truth, keys, t_from, t_to, every):
    feats = truth_memberships(read_truth(truth))
    ts = [float(l.split()[1]) for l in open(truth) if l[:1].isdigit()][:2]
    fps = 1.0 / (ts[1] - ts[0]) if len(ts) == 2 else FPS
    ks = [parse_key(k) for k in keys]
    print("t_s  " + " ".join("%9s" % k for k in keys) + "   inputs")
    step = max(1, int(round(every * fps)))
    for i in range(int(t_from * fps), min(len(feats), int(t_to * fps) + 1), step):
        f = feats[i]
        mus = [key_membership(f, a, s) for a, s in ks]
        print("%5.2f " % (i / fps) + " ".join("%9.2f" % m for m in mus) + "   " +
              " ".join("%s=%.0f" % (a, f[a]) for a, _ in ks))


def cmd_check(song_path, plan_path, truth, cues_path):
    """The rendered child's TRUE joints over every window the coach opens
    (the bear's span + one beat): does the truth itself reach the keys?"""
    song, plan, cues = plan_and_cues(song_path, plan_path, cues_path)
    _, expect = build(song, plan, cues)
    feats = truth_memberships(read_truth(truth))
    ok = True
    print("%7s %-14s %4s %-16s %s" % ("t_s", "move", "rep", "expected",
                                      "best held membership per key (window: span + 1 beat)"))
    for i, t0, t1, mi, r, tag in expect:
        if i < 0:
            continue
        i0, i1 = int(round(t0 * FPS)), min(len(feats), int(round((t1 + song["beat"]) * FPS)))
        keys = song["moves"][mi]["keys"]
        cols = [(f + "=" + s, held([key_membership(feats[k], f, s) for k in range(i0, i1)]))
                for f, s in keys]
        # the judge needs every key >= 0.5 in the same frames, held 100 ms
        both = held([min(key_membership(feats[k], f, s) for f, s in keys) for k in range(i0, i1)])
        cols.append(("all", both))
        good = (both >= 0.5) == (tag == "right")
        ok &= good
        print("%7.2f %-14s %4d %-16s %s  %s" % (t0, song["moves"][mi]["clip"], r, tag,
                                                "  ".join("%s %.2f" % c for c in cols),
                                                "" if good else "<-- truth disagrees"))
    return 0 if ok else 1


def read_expect(path):
    beat, cues, tags, unled, child = None, [], [], [], "planted"
    for n, line in enumerate(open(path), 1):
        v = line.split()
        if not v or v[0].startswith("#"):
            continue
        if v[0] == "beat" and len(v) == 2:
            beat = float(v[1])
        elif v[0] == "child" and len(v) == 2:
            child = v[1]
        elif v[0] == "unled" and len(v) == 4:
            unled.append((int(v[1]), int(v[2]), v[3]))
        elif len(v) == 6:
            cues.append((float(v[0]), v[1], v[2], int(v[3]), int(v[4])))
            tags.append(v[5])
        else:
            raise ValueError("%s:%d: cannot read %r" % (path, n, line.strip()))
    if beat is None or not cues:
        raise ValueError("%s: no beat or no cues" % path)
    return beat, cues, tags, unled, child


def cues_diverge(want, got):
    """The first cue where the coach did not do what the child followed."""
    for k in range(max(len(want), len(got))):
        if k >= len(want) or k >= len(got):
            return k
        w, g = want[k], got[k]
        if w[1:] != g[1:] or abs(w[0] - g[0]) > 0.1:
            return k
    return None


def read_judging(log_path):
    """Verdicts (t, move, rep, result, detail) and the times corrections
    began (the coach's state line, logged with the wrong verdict)."""
    vre = re.compile(r"t=\s*([\d.]+) judge verdict move=(\d+) rep=(\d+) result=(\w+)(.*)")
    cre = re.compile(r"t=\s*([\d.]+) coach state .*to=(correct|worried) reason=(wrong|misses)")
    verdicts, corrections = [], []
    for line in open(log_path):
        m = vre.search(line)
        if m:
            verdicts.append((float(m.group(1)), int(m.group(2)), int(m.group(3)), m.group(4),
                             m.group(5).strip()))
        m = cre.search(line)
        if m:
            corrections.append(float(m.group(1)))
    return verdicts, corrections


CORRECTING = ("head_shake", "watch_me")
WRE = re.compile(r"t=\s*([\d.]+) judge window move=(\d+) rep=(\d+) key_ms=(\d+) end_ms=(\d+)")
SRE = re.compile(r"t=\s*([\d.]+) bridge (?:switch from=\S+ to=|cut from=\S+ to=)([a-z_]+)@")


def read_reaction(log_path):
    """The judge's windows (t, move, rep, key_ms, end_ms) and the frames the
    player entered a clip at (t, clip: its switches and cuts)."""
    windows, entries = [], []
    for line in open(log_path):
        m = WRE.search(line)
        if m:
            windows.append((float(m.group(1)), int(m.group(2)), int(m.group(3)),
                            int(m.group(4)) / 1000.0, int(m.group(5)) / 1000.0))
        m = SRE.search(line)
        if m:
            entries.append((float(m.group(1)), m.group(2)))
    return windows, entries


def latency_rows(rows, log_path):
    """Per corrected planted mistake: when its repetition began, when the
    mistake shows (the bear's key moment in it), the verdict, the
    correcting clip's first frame, the latency and whether that frame is
    inside the repetition (before the bear's clip for it would end)."""
    windows, entries = read_reaction(log_path)
    out = []
    for tc, mi, r, label, vt in rows:
        w = next((x for x in windows if x[1:3] == (mi, r) and abs(x[0] - tc) < 0.05), None)
        first = next((t for t, clip in entries if t >= vt - 1e-6 and clip in CORRECTING), None)
        if w is None or first is None:
            out.append((label, tc, None, vt, first, None, False))
            continue
        shows = w[0] + w[3]
        out.append((label, tc, shows, vt, first, first - shows, first < w[0] + w[4]))
    return out


def print_latency(lat):
    if not lat:
        return True
    print("\n| planted mistake | repetition began | mistake shows | verdict | "
          "first correcting frame | latency | judge's wait | switch | inside |")
    print("|---|---|---|---|---|---|---|---|---|")
    fmt = lambda v: "-" if v is None else "%.2f s" % v
    for label, tc, shows, vt, first, lat_s, inside in lat:
        # where the latency goes: the judge's wait (shows -> verdict: the
        # lag and the time left for a sign) and the switch (verdict -> the
        # correcting clip's first frame: the coach, the planner, the player)
        wait = vt - shows if shows is not None else None
        switch = first - vt if first is not None else None
        print("| %s | %s | %s | %s | %s | %s | %s | %s | %s |"
              % (label, fmt(tc), fmt(shows), fmt(vt), fmt(first), fmt(lat_s), fmt(wait),
                 fmt(switch), "yes" if inside else "NO"))
    vals = sorted(x[5] for x in lat if x[5] is not None)
    med = vals[len(vals) // 2] if len(vals) % 2 else sum(vals[len(vals) // 2 - 1:][:2]) / 2
    inside = sum(1 for x in lat if x[6])
    ok = bool(vals) and len(vals) == len(lat) and vals[-1] <= 1.5 and inside == len(lat)
    print("e2e: latency from the mistake showing to the correcting clip: median %.2f s "
          "(goal <= 0.70), max %.2f s (limit 1.50), inside its repetition %d of %d"
          % (med, vals[-1], inside, len(lat)) if vals else "e2e: no latency measured")
    return ok


def cmd_score(expect_path, log_path):
    """Every window the coach opened: its verdict against the plan (a
    slower demonstration opens none: the child watches it). A
    window gets the first unclaimed verdict of its move and repetition
    from its start to its end + 2 beats; one with none was cancelled when a
    correction began inside it (else: unjudged, a failure). Fails when a
    planted mistake is not judged wrong and corrected, a move done right is
    judged wrong and corrected, or not judged at all, or the coach did not
    lead what the child followed; a move done right judged wrong with no
    correction (the coach had moved on) is counted and printed apart."""
    beat, want, tags, unled, child = read_expect(expect_path)
    caught_rows = []
    got = read_cues(log_path)
    verdicts, corrections = read_judging(log_path)
    claimed = set()
    n = {"caught": 0, "missed": 0, "right": 0, "false": 0, "unseen": 0, "unsure": 0,
         "cancelled": 0, "unjudged": 0, "watched": 0}
    print("%7s %4s %4s %-14s %-7s %-16s %-8s %s" % ("t_s", "move", "rep", "clip", "led_as",
                                                    "planted", "verdict", "detail"))
    for k, (tc, clip, reason, mi, r) in enumerate(want):
        if tags[k] == "-":
            continue
        if reason == "demo":  # the child only watches it (SEEDS.md § 000): no window
            n["watched"] += 1
            print("%7.2f %4d %4d %-14s %-7s %-16s %-8s %s" % (tc, mi, r, clip, reason, "-", "-",
                                                              "watched, not judged"))
            continue
        end = want[k + 1][0] if k + 1 < len(want) else tc + 10
        v = next((j for j, x in enumerate(verdicts) if j not in claimed and x[1:3] == (mi, r)
                  and tc - 1e-6 <= x[0] <= end + 2 * beat + 1e-6), None)
        fixed = any(tc - 1e-6 <= c <= end + beat + 1e-6 for c in corrections)
        if v is not None:
            claimed.add(v)
            res = verdicts[v][3]
            corr = res == "wrong" and any(abs(c - verdicts[v][0]) < 1e-6 for c in corrections)
            if tags[k] == "right":
                n["right" if res == "right" else "false" if corr else
                  "unsure" if res == "unsure" else "unseen"] += 1
            else:
                n["caught" if corr else "missed"] += 1
                if corr:
                    caught_rows.append((tc, mi, r, "%d.%d %s %s" % (mi, r, clip, tags[k][6:]),
                                        verdicts[v][0]))
            detail = "t=%.2f %s %s%s" % (verdicts[v][0], res, verdicts[v][4],
                                         " -> corrected" if corr else "")
        else:
            res = "-"
            if tags[k] == "right":
                n["cancelled" if fixed else "unjudged"] += 1
            else:
                n["missed"] += 1
            detail = "cancelled by a correction" if fixed else "NO VERDICT"
        print("%7.2f %4d %4d %-14s %-7s %-16s %-8s %s" % (tc, mi, r, clip, reason,
                                                          tags[k] if tags[k] != "right" else "-",
                                                          res, detail))
    for mi, r, tag in unled:
        print("%7s %4d %4d %-14s %-7s %-16s %-8s %s" % ("-", mi, r, "-", "-", tag, "-",
                                                        "the coach never led it"))
        n["missed"] += 1
    planted = sum(1 for t in tags if t.startswith("wrong")) + len(unled)
    print("e2e: planted mistakes caught=%d missed=%d of %d; repetitions done right: judged "
          "right=%d, wrongly corrected=%d, judged wrong without a correction=%d, unsure (never "
          "corrected)=%d, cancelled by a correction=%d, without a verdict=%d; slower "
          "demonstrations watched=%d"
          % (n["caught"], n["missed"], planted, n["right"], n["false"], n["unseen"], n["unsure"],
             n["cancelled"], n["unjudged"], n["watched"]))
    if n["unseen"]:
        print("e2e: NOTE: %d repetition(s) done right were judged wrong (not recognised) where "
              "the coach did not correct (it had moved on): not a failure of the acceptance "
              "(no correct repetition triggers a correction), but the child was not credited"
              % n["unseen"])
    lat_ok = print_latency(latency_rows(caught_rows, log_path))
    k = cues_diverge(want, got)
    if k is not None:
        w = want[k] if k < len(want) else None
        g = got[k] if k < len(got) else None
        print("e2e: the coach did not do what the child followed: request %d was %s, the child "
              "followed %s (re-make the cues: scripts/e2e_child.sh --remake)" % (k, g, w))
    print("e2e: child=%s planted=%d caught=%d right_corrected=%d" % (child, planted, n["caught"],
                                                                     n["false"]))
    return 0 if (n["missed"] == 0 and n["false"] == 0 and n["unjudged"] == 0 and k is None
                 and (planted > 0) == (child in ("planted", "moving")) and lat_ok) else 1


def main(argv):
    if argv[:1] in (["sequence"], ["expect"]) and "--child" in argv:
        k = argv.index("--child")
        child = argv[k + 1] if k + 1 < len(argv) else ""
        if child not in ("planted", "late", "sloppy", "moving"):
            sys.stderr.write("make_child: --child is planted, late, sloppy or moving, not %r\n"
                             % child)
            return 2
        argv = argv[:k] + argv[k + 2:]
    else:
        child = "planted"
    if len(argv) in (4, 5) and argv[0] in ("sequence", "expect"):
        cmd_sequence(argv[1], argv[2], argv[3], argv[4] if len(argv) == 5 else None, child,
                     argv[0] == "sequence")
        return 0
    if len(argv) in (4, 5) and argv[0] == "check":
        return cmd_check(argv[1], argv[2], argv[3], argv[4] if len(argv) == 5 else None)
    if len(argv) == 3 and argv[0] == "derive":
        os.makedirs(argv[2], exist_ok=True)
        make_derived(read_plan(argv[1]), argv[2])
        return 0
    if len(argv) == 4 and argv[0] == "move":
        cmd_move(argv[1], argv[2], argv[3])
        return 0
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

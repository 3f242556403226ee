#!/usr/bin/env python3
"""Write the fuzz targets' small seed inputs (issue 18) into tests/fuzz/:
seeds_dump/ (fuzz_fakenect_dump, fuzz_track_dump), seeds_synth/,
seeds_cli/, seeds_font/, seeds_forest/, seeds_map/, seeds_codec/, seeds_keys/, seeds_voice/, seeds_trc/,
seeds_ase/, seeds_keyscript/, seeds_evolve/, seeds_floor/. Everything is made
here from the formats' rules, nothing copied from the shared data; run it again
after changing a format:

  tests/fuzz/make_seeds.py          # rewrite the seed folders
"""
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def put(folder, name, data):
    os.makedirs(os.path.join(HERE, folder), exist_ok=True)
    with open(os.path.join(HERE, folder, name), "wb") as f:
        f.write(data)


# ---- dumps: 2 bytes of INDEX.txt length, INDEX.txt, a control byte a file
def frame_name(letter, k):
    t = 1300000000 + k / 30
    return "%s-%.6f-%d.%s" % (letter, t, 1000000 + 2000000 * k,
                              {"d": "pgm", "r": "ppm", "a": "dump"}[letter])


def dump(lines, controls=b""):
    index = "".join(ln + "\n" for ln in lines).encode()
    return struct.pack("<H", len(index)) + index + controls


def dump_seeds():
    three = [frame_name(x, k) for k in range(3) for x in "da"]
    put("seeds_dump", "three_frames", dump(three))
    put("seeds_dump", "colour_too", dump([frame_name(x, k) for k in range(2) for x in "rda"]))
    # A truncated (2: 1000 bytes), a missing (1) and a 0-byte (4) depth frame: mended.
    bad = [frame_name("d", k) for k in range(5)]
    put("seeds_dump", "mended_frames", dump(bad, b"\x00\x02\xe8\x03\x01\x04\x00"))
    put("seeds_dump", "blank_first", dump([""] + three))
    put("seeds_dump", "depth_only", dump([frame_name("d", k) for k in range(4)]))


# ---- the synthesizer's texts: 'T' truth.txt, 'S' a sequence file
JOINTS = 20


def truth_seed():
    head = ("# cub-synth truth v1: line 2 'gravity gx gy gz' (down, camera space, length 1000); "
            "then per frame: frame t_s ts, then 20 joints as x y z visible\n"
            "gravity 0.000 -1000.000 0.000\n")
    rows = []
    for f in range(3):
        joints = " ".join("%.1f %.1f %.1f %d" % (10.0 * j - 100, 50.0 * f + j, 2200.0 + j, j % 2)
                          for j in range(JOINTS))
        rows.append("%d %.6f %d %s\n" % (f, 1300000000 + f / 30, 1000000 + 2000000 * f, joints))
    return ("T" + head + "".join(rows)).encode()


def synth_seeds():
    put("seeds_synth", "truth", truth_seed())
    put("seeds_synth", "jtrack", b"J# three frames\ncub-jtrack 1\nfps 30\nunit_mm 0.25\n"
        b"frames 3\n" + b"(4000)" * 63 + b"\n" + b"`^" * 31 + b"_\n" + b"(40)(-40)" + b"_" * 61 + b"\n")
    put("seeds_synth", "sequence", b"S# a warm-up then a wave\n13_29 0 2.5\njumping_jacks 1 end mirror\n")


# ---- command lines: arguments separated by NUL; byte 0 picks the program
def cli_seeds():
    box = [b"--headless", b"--size", b"640x360", b"--seconds", b"1.5", b"--clock", b"virtual",
           b"--song", b"twinkle.song.xml", b"--depth", b"off", b"--attract-after", b"20"]
    put("seeds_cli", "cubdance", b"d" + b"\0".join(box))
    put("seeds_cli", "cubdance_config", b"c" + b"volume=40\nresolution=800x600\nfont=/x.ttf\n")
    put("seeds_cli", "retarget", b"r" + b"\0".join([b"src.bvh", b"--map", b"m.map", b"--from", b"1",
                                                      b"--to", b"2.5", b"--speed", b"1.2", b"--mirror"]))
    put("seeds_cli", "build", b"b" + b"\0".join([b"--recipe", b"r.txt", b"--out", b"o.cubclips",
                                                   b"--root", b"/src", b"--data", b"/data"]))
    put("seeds_cli", "synth", b"s" + b"\0".join([b"--clip", b"13_29", b"--from", b"0", b"--to", b"5",
                                                   b"--out", b"/tmp/x", b"--fps", b"30", b"--frames", b"4"]))


# ---- a tiny TrueType font: glyphs for ' ' .. '~' of one square outline
def table_checksum(data):
    data += b"\0" * (-len(data) % 4)
    return sum(struct.unpack(">%dI" % (len(data) // 4), data)) & 0xFFFFFFFF


def font_seed():
    first, last = 32, 126
    n = last - first + 2  # .notdef + the printable ASCII range
    square = struct.pack(">hhhhh", 1, 0, 0, 500, 700)  # one contour, its box
    square += struct.pack(">H", 3)                      # end point of the contour
    square += struct.pack(">H", 0)                      # no instructions
    square += bytes([0x01] * 4)                          # 4 on-curve points, long coords
    square += struct.pack(">hhhh", 0, 500, 0, -500)      # x deltas
    square += struct.pack(">hhhh", 0, 0, 700, 0)         # y deltas
    square += b"\0" * (-len(square) % 4)
    glyf = square * n
    loca = struct.pack(">%dI" % (n + 1), *[len(square) * i for i in range(n + 1)])
    head = struct.pack(">IIIIHHQQhhhhHHhhh", 0x10000, 0x10000, 0, 0x5F0F3CF5, 0, 1000, 0, 0,
                       0, 0, 500, 700, 0, 8, 2, 1, 0)
    hhea = struct.pack(">IhhhHhhhhhhhhhhhH", 0x10000, 800, -200, 0, 600, 0, 0, 500, 1, 1, 0,
                       0, 0, 0, 0, 0, n)
    maxp = struct.pack(">IHHHHHHHHHHHHHH", 0x10000, n, 4, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0)
    hmtx = struct.pack(">%dH" % (2 * n), *([600, 0] * n))
    # cmap format 4: one segment first..last -> glyphs 1.., and the 0xFFFF end.
    seg = struct.pack(">HHHHHHH", 4, 0, 0, 4, 4, 1, 0)  # fields patched below
    ends, starts = [last, 0xFFFF], [first, 0xFFFF]
    deltas, ranges = [(1 - first) & 0xFFFF, 1], [0, 0]
    body = struct.pack(">2H", *ends) + b"\0\0" + struct.pack(">2H", *starts)
    body += struct.pack(">2H", *deltas) + struct.pack(">2H", *ranges)
    seg = struct.pack(">HHHHHHH", 4, 14 + len(body), 0, 4, 4, 1, 0) + body
    cmap = struct.pack(">HHHHI", 0, 1, 3, 1, 12) + seg
    tables = {b"cmap": cmap, b"glyf": glyf, b"head": head, b"hhea": hhea, b"hmtx": hmtx,
              b"loca": loca, b"maxp": maxp}
    out = struct.pack(">IHHHH", 0x10000, len(tables), 64, 2, 48)
    offset = 12 + 16 * len(tables)
    blobs = b""
    for tag in sorted(tables):
        data = tables[tag]
        out += tag + struct.pack(">III", table_checksum(data), offset + len(blobs), len(data))
        blobs += data + b"\0" * (-len(data) % 4)
    return out + blobs


def map_seeds():
    """The bear's joints linked one to one (hello.bvh is a bear BVH), and
    with weights: the maps the fuzz target binds both sides of."""
    import re
    with open(os.path.join(HERE, "..", "..", "assets", "clips", "hello.bvh"), "rb") as f:
        joints = re.findall(rb"(?:ROOT|JOINT)\s+(\S+)", f.read())
    put("seeds_map", "bear_identity.map", b"".join(j + b" " + j + b"\n" for j in joints))
    weighted = [b"%s %s:0.5 %s:0.5 rot" % (j, j, joints[0]) if i % 3 == 1 else b"%s %s" % (j, j)
                for i, j in enumerate(joints)]
    put("seeds_map", "bear_weighted.map", b"# weights\n" + b"\n".join(weighted) + b"\n")


def evolve_seeds():
    """cubtool evolve's map files (cub/evolve.h), over the bear's joints on
    both sides (the fuzz target crosses hello.bvh with itself): one to one,
    many to one, none on either side."""
    import re
    with open(os.path.join(HERE, "..", "..", "assets", "clips", "hello.bvh"), "rb") as f:
        joints = re.findall(rb"(?:ROOT|JOINT)\s+(\S+)", f.read())
    put("seeds_evolve", "bear_identity.evmap", b"".join(j + b" = " + j + b"\n" for j in joints))
    put("seeds_evolve", "bear_kinds.evmap",
        b"# legs -> one tail, a head with no partner, a second head\n"
        b"LeftUpLeg RightUpLeg = Spine\nHead = -\n- = Head\nNeck = Neck Chest\n")


# ---- the seed's codec (firmware/codec, docs/codec.md): a .cubseed stream
def trunc_div(a, b):
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b > 0) else -q


def split_m(mm):
    """A length in mm as the codec's i8 whole metres + u16 fraction code."""
    v = round(mm * 65536)
    whole = trunc_div(v, 65536000)
    rest = v - whole * 65536000
    return struct.pack("<bH", whole, trunc_div(rest * 32768, 65536000) + 32768)


def unit_code(x):
    return min(65535, max(0, trunc_div(round(x * (1 << 30)), 1 << 15) + 32768))


def kept(f, n):
    return f < 6 or f >= n - 6 or f % 4 == 0


def cubseed(frames=23, frame_ns=33333333):
    # name, parent, end site, offset mm: a leg with its foot as the effector
    joints = [("Hips", -1, 0, (0, 0, 0)), ("LeftUpLeg", 0, 0, (90, -40, 0)),
              ("LeftLeg", 1, 0, (0, -420, 0)), ("LeftFoot", 2, 0, (0, -400, 20)),
              ("LeftFoot_end", 3, 1, (0, -40, 110))]
    effectors = [3]
    body = b""
    for name, parent, end, off in joints:
        body += struct.pack("<B", len(name)) + name.encode() + struct.pack("<BB", parent + 1, end)
        body += b"".join(split_m(c) for c in off)
    body += bytes(effectors)
    for f in range(frames):
        if not kept(f, frames):
            continue
        body += split_m(100 * math.sin(f / 5)) + split_m(900 + f) + split_m(-1500)
        for j, (_, _, end, _) in enumerate(joints):
            if end:
                continue
            a = 0.2 * j + 0.5 * math.sin(f / 4 + j)
            q = (math.cos(a / 2), math.sin(a / 2), 0.0, 0.0)
            body += struct.pack("<4H", *(unit_code(c) for c in q))
    blocks = (frames + 3) // 4
    body += b"\xff" * ((blocks * len(effectors) + 7) // 8)
    total = 24 + len(body) + 4
    head = b"CUBSEED" + struct.pack("<BHBBIII", 1, len(joints), len(effectors), 0, frames,
                                    frame_ns, total)
    data = head + body
    return data + struct.pack("<I", zlib.crc32(data))


# ---- our error-bounded codec (firmware/codec/codec_keys.c, docs/codec.md): .cubkeys
def bits_le(fields):
    """(value, width) pairs packed LSB first into bytes."""
    acc, have, out = 0, 0, bytearray()
    for v, w in fields:
        acc |= (v & ((1 << w) - 1)) << have
        have += w
        while have >= 8:
            out.append(acc & 0xFF)
            acc >>= 8
            have -= 8
    if have:
        out.append(acc & 0xFF)
    return bytes(out)


KEYS_SEGMENT = 32  # CUB_KEYS_SEGMENT


def keys_track(values, every, shift, rotation):
    """An animated track: values [frame][3] (ints), a key every `every`
    frames (and the last), codes above each segment's minimum."""
    n = len(values)
    keys = [f for f in range(n) if f % every == 0 or f == n - 1]
    base = [min(v[c] for v in values) for c in range(3)]
    code = {f: [(values[f][c] - base[c] + (1 << shift >> 1)) >> shift for c in range(3)] for f in keys}
    words = (n + 63) // 64
    segs = []
    for w in range((n + KEYS_SEGMENT - 1) // KEYS_SEGMENT):
        ks = [f for f in keys if f // KEYS_SEGMENT == w]
        mins = [min(code[f][c] for f in ks) for c in range(3)]
        widths = [max(code[f][c] - mins[c] for f in ks).bit_length() for c in range(3)]
        segs.append((ks, mins, widths))
    rb = [max(sg[1][c] for sg in segs).bit_length() for c in range(3)]
    offs, at, codes = [], 0, []
    for ks, mins, widths in segs:
        offs.append(at)
        for f in ks:
            codes += [(code[f][c] - mins[c], widths[c]) for c in range(3)]
        at += len(ks) * sum(widths)
    code_bytes = bits_le(codes)
    out = struct.pack("<B3B3B3iI", 2, shift, shift, shift, *rb, *base, len(code_bytes))
    for w in range(words):
        out += struct.pack("<Q", sum(1 << (f - 64 * w) for f in keys if f // 64 == w))
    out += b"".join(struct.pack("<I", o) for o in offs)
    headers = []
    for _, mins, widths in segs:
        headers += [(wd, 6) for wd in widths] + list(zip(mins, rb))
    out += bits_le(headers)
    return out + code_bytes


def cubkeys(frames=70, frame_ns=33333333):
    # name, parent, end site, offset mm: an arm; the hand is an end site
    joints = [("Hips", -1, 0, (0, 0, 0)), ("Arm", 0, 0, (150, 400, 0)),
              ("Elbow", 1, 0, (280, 0, 0)), ("Hand", 2, 1, (250, 0, 0))]
    body = b""
    for name, parent, end, off in joints:
        body += struct.pack("<B", len(name)) + name.encode() + struct.pack("<BB", parent + 1, end)
        body += struct.pack("<3i", *(round(c * 65536) for c in off))
    def rot(f, j):
        a = 0.3 * j + 0.6 * math.sin(f / 6 + j)
        return [round(math.sin(a / 2) * (1 << 30)), round(0.1 * math.sin(f / 9) * (1 << 30)), 0]
    body += keys_track([rot(f, 0) for f in range(frames)], 3, 12, True)    # Hips: keys
    body += struct.pack("<B3i", 1, round(0.2 * (1 << 30)), 0, 0)            # Arm: a constant
    body += keys_track([rot(f, 2) for f in range(frames)], 1, 14, True)    # Elbow: every frame
    root = [[round(10 * f * 65536), round(900 * 65536), 0] for f in range(frames)]
    body += keys_track(root, 5, 8, False)                                   # the root's position
    total = 24 + len(body) + 4
    head = b"CUBKEYS" + struct.pack("<BHBBIII", 1, len(joints), 0, 0, frames, frame_ns, total)
    data = head + body
    return data + struct.pack("<I", zlib.crc32(data))


def codec_seeds():
    # byte 0 of a fuzz input: bit 0 mends length and CRC, bits 1-2 the method, 3-4 the IK mode
    put("seeds_codec", "leg.cubseed", cubseed())
    put("seeds_codec", "leg_fixed", b"\x01" + cubseed(frames=40))
    put("seeds_codec", "short_fixed", b"\x0b" + cubseed(frames=9))
    # byte 0 of a fuzz_codec_keys input: bit 0 mends length and CRC
    put("seeds_keys", "arm.cubkeys", cubkeys())
    put("seeds_keys", "arm_fixed", b"\x01" + cubkeys(frames=130))
    put("seeds_keys", "short_fixed", b"\x01" + cubkeys(frames=2))
# ---- voice packs (cub/voicepack.h): phrases of a few samples each
def fnv1a(text):
    h = 2166136261
    for b in text:
        h = ((h ^ b) * 16777619) & 0xFFFFFFFF
    return h


def voice_pack(rate, phrases):
    body = b"CUBVOICE" + struct.pack("<III", 1, rate, len(phrases))
    for text, samples in phrases:
        t = text.encode()
        body += struct.pack("<II", fnv1a(t), len(t)) + t
        body += struct.pack("<I", len(samples)) + struct.pack("<%dh" % len(samples), *samples)
    return body + struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)


def voice_seeds():
    wave = [(i * 2000) % 16000 - 8000 for i in range(24)]
    put("seeds_voice", "two_phrases",
        voice_pack(22050, [("Press START!", wave), ("Jump!", wave[::-2])]))
    put("seeds_voice", "one_at_8k", voice_pack(8000, [("Come closer!", [32767, -32768, 0, 1])]))


# ---- TRC marker files: the header, names, X1 Y1 Z1 line, then rows of
# frame, time, x y z per marker; three blank cells where a marker is lost.
def trc(units, rate, rows, names, trailing_tab=False):
    end = "\t\n" if trailing_tab else "\n"
    out = "PathFileType\t4\t(X/Y/Z)\tseed.trc\n"
    out += "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\t"
    out += "OrigDataStartFrame\tOrigNumFrames\n"
    out += "%g\t%g\t%d\t%d\t%s\t%g\t1\t%d\n" % (rate, rate, len(rows), len(names), units,
                                                   rate, len(rows))
    out += "Frame#\tTime\t" + "".join(n + "\t\t\t" for n in names).rstrip("\t") + end
    out += "\t\t" + "\t".join("%s%d" % (a, i + 1) for i in range(len(names)) for a in "XYZ")
    out += end + "\n"
    for f, row in enumerate(rows):
        cells = ["%d" % (f + 1), "%.6f" % (f / rate)]
        for p in row:
            cells += ["", "", ""] if p is None else ["%.3f" % v for v in p]
        out += "\t".join(cells) + end
    return out.encode()


def trc_seeds():
    names = ["R.Knee", "L.Knee", "Sternum"]
    rows = [[(400.0 + f, 500.0 - 2 * f, 30.5 * math.sin(f)), (-400.0, 500.0, f * 1.5),
             None if f == 2 else (0.0, 1300.0 + f, -12.25)] for f in range(4)]
    put("seeds_trc", "small_mm.trc", trc("mm", 60, rows, names, trailing_tab=True))
    metres = [[(1.25, 0.5, -0.125)], [None]]
    put("seeds_trc", "lost_m.trc", trc("m", 100, metres, ["Head"]))


# ---- ASE (3ds Max ASCII): a scene, nodes with rest transforms, sampled
# position and rotation tracks (axis, angle), one sample a frame.
def ase_node(name, parent, pos, quat=None, rows=None, pos_track=None, rot_track=None, dummy=False):
    out = '*HELPEROBJECT {\n\t*NODE_NAME "%s"\n' % name
    if parent:
        out += '\t*NODE_PARENT "%s"\n' % parent
    out += '\t*HELPER_CLASS "%s"\n\t*NODE_TM {\n' % ("Dummy" if dummy else "Bone")
    for i, row in enumerate(rows or []):
        out += "\t\t*TM_ROW%d %g %g %g\n" % ((i,) + tuple(row))
    out += "\t\t*TM_POS %g %g %g\n" % tuple(pos)
    if quat:
        out += "\t\t*TM_QUATERNION %g %g %g %g\n" % tuple(quat)
    out += "\t}\n"
    if pos_track or rot_track:
        out += "\t*TM_ANIMATION {\n"
        if pos_track:
            out += "\t\t*CONTROL_POS_TRACK {\n"
            out += "".join("\t\t\t*CONTROL_POS_SAMPLE %d %g %g %g\n" % ((160 * k,) + tuple(p))
                           for k, p in enumerate(pos_track))
            out += "\t\t}\n"
        if rot_track:
            out += "\t\t*CONTROL_ROT_TRACK {\n"
            out += "".join("\t\t\t*CONTROL_ROT_SAMPLE %d %g %g %g %.9f\n" % ((160 * k,) + tuple(r))
                           for k, r in enumerate(rot_track))
            out += "\t\t}\n"
        out += "\t}\n"
    return out + "}\n"


def ase_seeds():
    head = "*3DSMAX_ASCIIEXPORT\t200\n*COMMENT \"seed\"\n*SCENE {\n\t*SCENE_FIRSTFRAME 0\n"
    head += "\t*SCENE_LASTFRAME 2\n\t*SCENE_FRAMESPEED 30\n\t*SCENE_TICKSPERFRAME 160\n}\n"
    body = ase_node("Hips", None, (0, 900, 0), quat=(0, 0, 0, 1),
                    pos_track=[(0, 900, 0), (5, 905, 0), (10, 900, 2)],
                    rot_track=[(0, 1, 0, 0.3), (0, 1, 0, 0.1), (0, 0, 0, 0)])
    body += ase_node("Spine", "Hips", (0, 1100, 0), rows=[(1, 0, 0), (0, 1, 0), (0, 0, 1)],
                     rot_track=[(1, 0, 0, 0.2), (0, 0, 1, -0.05), (1, 0, 0, 0.01)])
    body += ase_node("Head", "Spine", (0, 1500, 0), quat=(0, 0, 0.7071068, 0.7071068))
    body += ase_node("Head_end", "Head", (0, 1650, 0), dummy=True)
    put("seeds_ase", "small.ase", (head + body).encode())
    one = "*3DSMAX_ASCIIEXPORT 200\n*SCENE {\n*SCENE_LASTFRAME 0\n*SCENE_FRAMESPEED 24\n}\n"
    one += "*MATERIAL_LIST {\n\t*MATERIAL_COUNT 0\n}\n" + ase_node("root", None, (1, 2, 3))
    put("seeds_ase", "one_node.ase", one.encode())


# ---- the body-part forest (cub/forest.h): header, roots, 28-byte nodes, u16 leaves
def forest(classes=3):
    nodes = [(100000, 0, 0, 0, 500, 1, 0x80000000 | 1),       # node 0: left to node 1
             (0, -80000, 30000, 0, -200, 0x80000000, 0x80000000 | 2)]
    leaves = [[(i * 7919 + c * 104729) % 65536 for c in range(classes)] for i in range(3)]
    body = b"CUBFRST1" + struct.pack("<HHHHII", 1, classes, 2, 0, len(nodes), len(leaves))
    body += struct.pack("<II", 0, 0x80000000 | 2)
    for n in nodes:
        body += struct.pack("<iiiiiII", *n)
    for leaf in leaves:
        body += struct.pack("<%dH" % classes, *leaf)
    return body


def forest_seeds():
    put("seeds_forest", "two_trees.cubforest", forest())
    put("seeds_forest", "many_classes.cubforest", forest(classes=16))


def keyscript_seeds():
    """cubtool play's scripted keys (app/include/cub/keyscript.h)."""
    put("seeds_keyscript", "scene.keys",
        b"# pause, select B, move it, numbers, zoom\n0 Space\n2 2 L L L\n4 N\n6 Up Up\n")
    put("seeds_keyscript", "every_key.keys",
        b"0 tab 1 2 I J K L W A S D up down pageup PageDown N\n"
        b"10 Plus minus C V F G Space Home Left Right Esc\n")


def floor_seeds():
    """The forest floor (app/include/cub/floor_file.h): a small hill with a
    log and a stone, and the smallest grid with nothing on it."""
    rows = "".join("row %s\n" % " ".join(str(60 * (i + j) - 120) for i in range(4))
                   for j in range(3))
    put("seeds_floor", "hill.floor",
        ("# a small hill\ncubfloor 1\ngrid 4 3 500 -750 -500\n" + rows +
         "log 0 -300 900 120 x\nstone 400 200 150 100 90\n").encode())
    put("seeds_floor", "bare.floor", b"cubfloor 1\r\ngrid 2 2 100 0 0\r\nrow 0 0\r\nrow 0 -5\r\n")


def main():
    floor_seeds()
    forest_seeds()
    keyscript_seeds()
    ase_seeds()
    trc_seeds()
    codec_seeds()
    map_seeds()
    evolve_seeds()
    dump_seeds()
    synth_seeds()
    cli_seeds()
    voice_seeds()
    put("seeds_font", "squares.ttf", b"\x10" + font_seed())  # byte 0: the pixel height
    print("seeds written under", HERE)


if __name__ == "__main__":
    main()

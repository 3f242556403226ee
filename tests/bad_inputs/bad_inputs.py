#!/usr/bin/env python3
"""The bad-input suite (issue 18): cases.txt's rows, each a nasty file of
one kind fed to the real cubdance or cubtool.

  bad_inputs.py setup BUILD OUT             the shared base files (a dump)
  bad_inputs.py run BUILD OUT KIND CASE     one row; exit 0 when it holds
  bad_inputs.py rows [--quick]              the rows, one `KIND CASE` a line
  bad_inputs.py report OUT                  the README's markdown table from
                                            the runs' result files
EMULATOR (the environment, e.g. qemu-aarch64-static) runs the programs;
CUB_FAKENECT_DIR is fakenect's library folder. Large files are sparse and
made at run time; nothing here is copied from the shared data.
"""
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.dirname(os.path.dirname(HERE))
ASSETS = os.path.join(SRC, "assets")
SHARED_DATA = os.environ.get("CUB_DATA_DIR") or os.path.join(SRC, "..", "shared", "data")
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"
SOUNDFONT = "/usr/share/sounds/sf2/TimGM6mb.sf2"
SANITIZER = re.compile(rb"AddressSanitizer|LeakSanitizer|runtime error:|MemorySanitizer")
BINARY = {"midi", "groove", "soundfont", "library", "font", "frame", "track_frame", "cubseed", "cubkeys", "voice",
          "forest"}
TEXT_ONLY = {"nan", "inf", "crlf", "bom", "badutf8"}


def read_table():
    """limits, kinds {kind: argv template}, cases {case: pattern}, rows."""
    limits, kinds, cases, rows = {}, {}, {}, []
    with open(os.path.join(HERE, "cases.txt"), encoding="utf-8") as f:
        for line in f:
            line = line.split(" #", 1)[0].strip()
            if not line or line.startswith("#"):
                continue
            w = line.split()
            if w[0] == "limit":
                limits[w[1]] = float(w[2])
            elif w[0] == "kind":
                kinds[w[1]] = w[2:]
            elif w[0] == "case":
                cases[w[1]] = line.split(None, 2)[2]
            elif w[2] == "pending":  # not registered: a fault not fixed yet, the note says
                rows.append({"kind": w[0], "case": w[1], "expect": w[3], "quick": False,
                             "pending": line.split(None, 4)[4]})
            else:
                rows.append({"kind": w[0], "case": w[1], "expect": w[2],
                             "quick": "quick" in w[3:]})
    return limits, kinds, cases, rows


# ---- the base file of each kind and what it needs beside it ---------------

def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)


def read(path):
    with open(path, "rb") as f:
        return f.read()


def bvh_joints(bvh):
    return re.findall(rb"(?:ROOT|JOINT)\s+(\S+)", bvh)


def copy_dump(shared, dst):
    src = os.path.join(shared, "dump")
    os.makedirs(dst, exist_ok=True)
    for n in os.listdir(src):
        shutil.copyfile(os.path.join(src, n), os.path.join(dst, n))
    return sorted(n for n in os.listdir(dst) if n.startswith("d-"))


def song_beside(d, midi_name, faults_name="faults.words"):
    song = read(os.path.join(ASSETS, "songs", "twinkle.song.xml"))
    song = song.replace(b'midi="twinkle.mid"', b'midi="' + midi_name.encode() + b'"')
    write(os.path.join(d, "twinkle.song.xml"),
          song.replace(b'faults="faults.words"', b'faults="' + faults_name.encode() + b'"'))
    shutil.copyfile(os.path.join(ASSETS, "songs", "twinkle.mid"), os.path.join(d, "twinkle.mid"))
    faults_beside(d)


def faults_beside(d):
    """The song's fault words, beside it as the song names them."""
    shutil.copyfile(os.path.join(ASSETS, "songs", "faults.words"), os.path.join(d, "faults.words"))


def base_of(kind, d, shared, build=""):
    """(base bytes, the nasty file's path) for KIND in the case folder d
    (None when this build lacks the base: the voice pack without espeak-ng)."""
    bear_bvh = read(os.path.join(ASSETS, "clips", "hello.bvh"))
    # The bear's own joints linked one to one: a map for a bear-shaped BVH.
    bear_map = b"".join(j + b" " + j + b":1.0\n" for j in bvh_joints(bear_bvh))
    if kind in ("character", "tags", "library", "routes"):  # read when the coach leads a song
        song_beside(d, "twinkle.mid")
    if kind == "config":
        return (b"# a small box config\nvolume=80\nresolution=640x360\nattract_after_s=20\n"
                b"doze_after_s=60\ndebounce_ms=30\nlog_max_kb=1024\n", "box.conf")
    if kind == "song":
        shutil.copyfile(os.path.join(ASSETS, "songs", "twinkle.mid"), os.path.join(d, "twinkle.mid"))
        faults_beside(d)
        return read(os.path.join(ASSETS, "songs", "twinkle.song.xml")), "bad.song.xml"
    if kind == "freesong":  # a song with <free> bars (issue 23): the groove's spans
        shutil.copyfile(os.path.join(ASSETS, "songs", "twinkle.mid"), os.path.join(d, "twinkle.mid"))
        faults_beside(d)
        return read(os.path.join(SRC, "tests", "scenario", "free_twinkle.song.xml")), "bad.song.xml"
    if kind == "faults":
        song_beside(d, "twinkle.mid", "bad.words")
        return read(os.path.join(ASSETS, "songs", "faults.words")), "bad.words"
    if kind == "midi":
        song_beside(d, "bad.mid")
        return read(os.path.join(ASSETS, "songs", "twinkle.mid")), "bad.mid"
    if kind == "groove":  # cubtool groove reads the MIDI file alone
        return read(os.path.join(ASSETS, "songs", "twinkle.mid")), "bad.mid"
    if kind == "soundfont":
        song_beside(d, "twinkle.mid")
        write(os.path.join(d, "soundfont.conf"), b"soundfont=" + os.path.join(d, "bad.sf2").encode() + b"\n")
        return read(SOUNDFONT), "bad.sf2"
    if kind == "timeline":
        return b"# scripted judge\n0.1 player\n0.2 wrong\n0.3 right\n0.4 clap\n", "bad.timeline"
    if kind == "buttons":
        return b"# buttons\n0.1 start press\n0.2 start down\n0.25 start up\n0.4 stop press\n", "bad.buttons"
    if kind == "character":
        return read(os.path.join(ASSETS, "bear", "bear.xml")), "bad.xml"
    if kind == "tags":
        return read(os.path.join(ASSETS, "clips", "bear.tags.xml")), "bad.tags.xml"
    if kind == "routes":  # read beside the tags they are given with
        shutil.copyfile(os.path.join(ASSETS, "clips", "bear.tags.xml"), os.path.join(d, "bad.tags.xml"))
        return read(os.path.join(ASSETS, "clips", "bear.routes.txt")), "bad.routes.txt"
    if kind == "library":
        return read(os.path.join(ASSETS, "clips", "bear.cubclips")), "bad.cubclips"
    if kind == "clip":
        return bear_bvh, "bad.bvh"
    if kind == "cubseed":  # the seed's codec stream, made by tests/fuzz/make_seeds.py
        return read(os.path.join(SRC, "tests", "fuzz", "seeds_codec", "leg.cubseed")), "bad.cubseed"
    if kind == "cubkeys":  # our error-bounded codec's stream, made by tests/fuzz/make_seeds.py
        return read(os.path.join(SRC, "tests", "fuzz", "seeds_keys", "arm.cubkeys")), "bad.cubkeys"
    if kind == "ase":  # a small 3ds Max ASCII export, made by tests/fuzz/make_seeds.py
        return read(os.path.join(SRC, "tests", "fuzz", "seeds_ase", "small.ase")), "bad.ase"
    if kind == "forest":  # a two-tree body-part forest, made by tests/fuzz/make_seeds.py
        return read(os.path.join(SRC, "tests", "fuzz", "seeds_forest", "two_trees.cubforest")), "bad.forest"
    if kind == "labels":  # hand labels of the real frames, read in place; the fuzz seeds' small forest
        os.symlink(os.path.join(SHARED_DATA, "depth", "skeltrack"), os.path.join(d, "real"))
        shutil.copyfile(os.path.join(SRC, "tests", "fuzz", "seeds_forest", "two_trees.cubforest"),
                        os.path.join(d, "two_trees.forest"))
        return read(os.path.join(SRC, "tests", "labels", "skeltrack_labels.txt")), "bad_labels.txt"
    if kind == "trc":  # a small marker file, made by tests/fuzz/make_seeds.py
        return read(os.path.join(SRC, "tests", "fuzz", "seeds_trc", "small_mm.trc")), "bad.trc"
    if kind == "floor":  # the box's forest floor (the format: cub/floor_file.h)
        return read(os.path.join(ASSETS, "floor", "forest.floor")), "bad.floor"
    if kind == "keyscript":  # cubtool play's scripted keys (the format: cub/keyscript.h)
        write(os.path.join(d, "hello.bvh"), bear_bvh)
        return b"# pause, select B, move it, numbers, zoom\n0 Space\n2 2 L L\n4 N\n6 Up Up\n", "bad.keys"
    if kind == "jtrack":  # a joint track of three frames (the format: cub/synth.h)
        head = b"# every point at one spot, then moving\ncub-jtrack 1\nfps 30\nunit_mm 0.5\nframes 3\n"
        frames = b"(100)(2000)(-50)" * 21 + b"\n" + b"`__" * 21 + b"\n" + b"___" * 21 + b"\n"
        return head + frames, "bad.jtrack"
    if kind == "voice":  # made by the build (app/voice.cmake), not committed
        song_beside(d, "twinkle.mid")
        pack = os.path.join(build, "assets", "voice", "bear.cubvoice")
        return (read(pack), "bad.cubvoice") if os.path.exists(pack) else (None, None)
    if kind == "font":
        return read(FONT), "bad.ttf"
    if kind == "index":
        copy_dump(shared, d)
        return read(os.path.join(d, "INDEX.txt")), "INDEX.txt"
    if kind in ("frame", "track_frame"):
        frames = copy_dump(shared, d)
        if kind == "track_frame":
            shutil.copyfile(os.path.join(shared, "truth.txt"), os.path.join(d, "truth.txt"))
        name = frames[len(frames) // 2]
        return read(os.path.join(d, name)), name
    if kind == "map":
        write(os.path.join(d, "source.bvh"), bear_bvh)
        return bear_map, "bad.map"
    if kind == "evolve_map":  # the bear crossed with itself, its joints paired one to one
        write(os.path.join(d, "p1.bvh"), bear_bvh)
        write(os.path.join(d, "p2.bvh"), bear_bvh)
        return b"".join(j + b" = " + j + b"\n" for j in bvh_joints(bear_bvh)), "bad.evmap"
    if kind == "bvh":
        write(os.path.join(d, "bear.map"), bear_map)
        return bear_bvh, "bad.bvh"
    if kind in ("asf", "amc"):  # a CMU subject of the shared data, read in place, never copied in
        cmu = os.path.join(SHARED_DATA, "mocap", "cmu", "asfamc")
        asf, amc = read(os.path.join(cmu, "13.asf")), read(os.path.join(cmu, "13_17.amc"))
        amc = b"\n".join(amc.split(b"\n")[:2000]) + b"\n"  # the first frames
        write(os.path.join(d, "source.asf"), asf)
        write(os.path.join(d, "source.amc"), amc)
        shutil.copyfile(os.path.join(ASSETS, "retarget", "cmu_asf.map"), os.path.join(d, "asf.map"))
        return (asf, "bad.asf") if kind == "asf" else (amc, "bad.amc")
    if kind == "recipe":
        write(os.path.join(d, "assets", "keys", "clap.keys"), read(os.path.join(ASSETS, "keys", "clap.keys")))
        return b"# a one-clip library\nclap  dance  assets/keys/clap.keys  -  0.0  1.5  speed=1.0\n", "bad.recipe"
    if kind == "keys":
        write(os.path.join(d, "recipe.txt"), b"clap  dance  assets/keys/bad.keys  -  -  -\n")
        return read(os.path.join(ASSETS, "keys", "clap.keys")), os.path.join("assets", "keys", "bad.keys")
    if kind == "truth":
        copy_dump(shared, os.path.join(d, "dump"))
        return read(os.path.join(shared, "truth.txt")), "bad.truth.txt"
    raise SystemExit("bad_inputs.py: no base for kind " + kind)


# ---- the nasty cases -------------------------------------------------------

NUMBER = re.compile(rb"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")
INTEGER = re.compile(rb"(?<![\d.])\d+(?![\d.])")


def second_half(base, pattern, by):
    """The first match of pattern on each line of base's second half -> by."""
    lines = base.split(b"\n")
    half = len(lines) // 2
    for i in range(half, len(lines)):
        lines[i] = pattern.sub(by, lines[i], count=1)
    return b"\n".join(lines)


def mid_line(base):
    """The offset of the start of the line in the middle of base."""
    at = base.find(b"\n", len(base) // 2)
    return at + 1 if 0 <= at < len(base) - 1 else len(base) // 2


def make_case(case, kind, base, path):
    """Write the nasty file for case at path (or a FIFO, folder, link)."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if os.path.lexists(path):
        os.remove(path)
    if case == "empty":
        write(path, b"")
    elif case == "truncated":  # cut in the middle of a line (a copy that stopped)
        at = mid_line(base)
        end = base.find(b"\n", at)
        write(path, base[: at + max(1, ((end if end > at else len(base)) - at) // 2)])
    elif case == "huge":
        write(path, base)
        os.truncate(path, 4 << 30)  # sparse: 4 GiB, no disk used
    elif case in ("nan", "inf"):
        write(path, second_half(base, NUMBER, b"nan" if case == "nan" else b"1e999"))
    elif case == "overflow":
        if kind in BINARY:  # 0xffffffff over every eighth of the file: counts, sizes, offsets
            b = bytearray(base)
            for k in range(1, 8):
                o = len(b) * k // 8
                b[o:o + 4] = b"\xff\xff\xff\xff"
            write(path, bytes(b))
        else:
            write(path, second_half(base, INTEGER, b"99999999999999999999"))
    elif case == "crlf":
        write(path, base.replace(b"\r\n", b"\n").replace(b"\n", b"\r\n"))
    elif case == "nul":
        at = mid_line(base)
        write(path, base[:at] + b"\0\0\0\0" + base[at:])
    elif case == "bom":
        write(path, b"\xef\xbb\xbf" + base)
    elif case == "badutf8":
        at = mid_line(base)
        write(path, base[:at] + b"\xff\xfe\xc3(\xed\xa0\x80" + base[at:])
    elif case == "fifo":
        os.mkfifo(path)
    elif case == "dir":
        os.mkdir(path)
    elif case == "symlink_loop":
        os.symlink(os.path.basename(path), path)
    elif case == "devzero":
        os.symlink("/dev/zero", path)
    else:
        raise SystemExit("bad_inputs.py: unknown case " + case)


# ---- running one row -------------------------------------------------------

def program_argv(build, prog, args, out):
    emu = os.environ.get("EMULATOR", "").split()
    if prog == "cubdance":
        exe = os.path.join(build, "app", "cubdance", "cubdance")
        fixed = ["--headless", "--clock", "virtual", "--seconds", "0.5", "--audio-driver", "dummy",
                 "--log", os.path.join(out, "event.log")]
        if "--replay" not in args:
            fixed += ["--depth", "off"]
        return emu + [exe] + fixed + args
    return emu + [os.path.join(build, "app", "cubtool", "cubtool")] + args


def environment(args):
    env = dict(os.environ, SDL_AUDIODRIVER="dummy", EGL_PLATFORM="surfaceless",
               LIBGL_ALWAYS_SOFTWARE="1", ASAN_OPTIONS="detect_leaks=0")
    if "--replay" in args:  # fakenect's environment, as the `fakenect` wrapper sets it
        env["FAKENECT_PATH"] = args[args.index("--replay") + 1]
        libs = [os.environ.get("CUB_FAKENECT_DIR", ""), os.environ.get("LD_LIBRARY_PATH", "")]
        env["LD_LIBRARY_PATH"] = ":".join(p for p in libs if p)
    return env


def run_limited(argv, env, limit_s, err_path):
    """exit code (-signal), seconds, max RSS in MB; None code on a hang."""
    t0 = time.monotonic()
    with open(err_path, "wb") as err, open(os.devnull, "wb") as null:
        p = subprocess.Popen(argv, env=env, stdout=null, stderr=err, stdin=subprocess.DEVNULL,
                             start_new_session=True)
        deadline, code, ru = t0 + limit_s, None, None
        while code is None:
            pid, status, ru = os.wait4(p.pid, os.WNOHANG)
            if pid:
                code = os.waitstatus_to_exitcode(status)
            elif time.monotonic() > deadline:
                os.killpg(p.pid, signal.SIGKILL)
                os.wait4(p.pid, 0)
                return None, limit_s, 0.0
            else:
                time.sleep(0.02)
    return code, time.monotonic() - t0, ru.ru_maxrss / 1024.0


def judge(row, pattern, name, code, rss_mb, limits, err):
    """'' when the row holds, else what went wrong."""
    if code is None:
        return "hung"
    if code < 0 or code >= 128:
        return "crashed (exit %d)" % code
    if SANITIZER.search(err):
        return "sanitizer report"
    if rss_mb > limits["rss_mb"]:
        return "max RSS %.0f MB" % rss_mb
    text = err.decode("utf-8", "replace")
    named = os.path.basename(name) in text
    if row["expect"] == "accepted":
        return "" if code == 0 else "refused (exit %d)" % code
    if row["expect"] == "mended":
        return "" if code == 0 and named else "exit %d, named %s" % (code, named)
    if code == 0:
        return "accepted (exit 0)"
    if not named:
        return "the message does not name %s" % os.path.basename(name)
    if pattern != "-" and not re.search(pattern, text):
        return "no '%s' in the message" % pattern
    return ""


def run_row(build, out, kind, case):
    limits, kinds, cases, rows = read_table()
    row = next((r for r in rows if r["kind"] == kind and r["case"] == case),
               {"kind": kind, "case": case, "expect": "refused", "quick": False})
    d = os.path.join(out, "%s.%s" % (kind, case))
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    base, name = base_of(kind, d, os.path.join(out, "shared"), build)
    if base is None:
        print("%s %s: SKIP: this build has no base file of the kind" % (kind, case))
        return 77
    path = os.path.join(d, name)
    make_case(case, kind, base, path)
    if os.path.isfile(path) and not os.path.islink(path) and case not in ("huge",) and read(path) == base:
        print("%s %s: the case leaves the file as it is: not a case for this kind" % (kind, case))
        return 77
    words = kinds[kind]
    args = [w.replace("{file}", path).replace("{dir}", d) for w in words[1:]]
    argv = program_argv(build, words[0], args, d)
    slow = 10 if os.environ.get("EMULATOR") else 1
    err_path = os.path.join(d, "stderr.txt")
    code, secs, rss = run_limited(argv, environment(args), limits["seconds"] * slow, err_path)
    err = read(err_path)
    why = judge(row, cases[case], name, code, rss, limits, err)
    first = next((ln for ln in err.decode("utf-8", "replace").splitlines() if os.path.basename(name) in ln),
                 err.decode("utf-8", "replace").splitlines()[0] if err else "")
    result = dict(row, code=code, seconds=round(secs, 2), rss_mb=round(rss), ok=not why, why=why,
                  message=first[:200].replace(d + "/", ""))
    with open(os.path.join(out, "%s.%s.json" % (kind, case)), "w", encoding="utf-8") as f:
        json.dump(result, f)
    print(" ".join(argv))
    print("%s %s: expect %s: exit %s, %.1f s, max RSS %.0f MB: %s" %
          (kind, case, row["expect"], code, secs, rss, why or "ok"))
    print("stderr: " + first)
    return 0 if not why else 1


def setup(build, out):
    """A small dump and its truth, made by our own cubtool synth-depth."""
    shared = os.path.join(out, "shared")
    shutil.rmtree(shared, ignore_errors=True)
    os.makedirs(shared)
    emu = os.environ.get("EMULATOR", "").split()
    argv = emu + [os.path.join(build, "app", "cubtool", "cubtool"), "synth-depth", "--clip",
                  "13_29", "--frames", "5", "--data", SHARED_DATA,
                  "--out", os.path.join(shared, "dump")]
    env = dict(os.environ, ASAN_OPTIONS="detect_leaks=0")
    subprocess.run(argv, env=env, check=True, stdout=subprocess.DEVNULL)
    os.rename(os.path.join(shared, "dump", "truth.txt"), os.path.join(shared, "truth.txt"))
    print("dump of %d files in %s" % (len(os.listdir(os.path.join(shared, "dump"))), shared))
    return 0


def report(out):
    """The README table: one line a kind, one column a case, from the runs'
    result files (pending rows: their note, listed under the table)."""
    _, kinds, cases, rows = read_table()
    res, notes = {}, []
    for r in rows:
        p = os.path.join(out, "%s.%s.json" % (r["kind"], r["case"]))
        if r.get("pending"):
            notes.append(r)
            res[(r["kind"], r["case"])] = dict(r, ok=None)
        elif os.path.exists(p):
            with open(p, encoding="utf-8") as f:
                res[(r["kind"], r["case"])] = json.load(f)
    texts = list(dict.fromkeys(n["pending"] for n in notes))  # one note, many rows
    print("| kind | " + " | ".join(c.replace("_", " ") for c in cases) + " |")
    print("|---" * (len(cases) + 1) + "|")
    for k in kinds:
        cells = []
        for c in cases:
            r = res.get((k, c))
            if not r:
                cells.append("")
            elif r["ok"] is None:
                cells.append("not yet (%d)" % (texts.index(r["pending"]) + 1))
            else:
                cells.append(r["expect"] + ("" if r["ok"] else " **FAIL: %s**" % r["why"]))
        print("| %s | %s |" % (k, " | ".join(cells)))
    for i, t in enumerate(texts):
        rows_of = ", ".join("%s %s" % (n["kind"], n["case"]) for n in notes if n["pending"] == t)
        print("\n(%d) %s: %s." % (i + 1, rows_of, t), end="")
    done = [r for r in res.values() if r["ok"] is not None]
    if done:
        worst = max(done, key=lambda r: r["rss_mb"])
        slowest = max(done, key=lambda r: r["seconds"])
        print("\n\n%d rows run, %d hold; the largest max RSS %d MB (%s %s), the longest run %.1f s (%s %s)." %
              (len(done), sum(bool(r["ok"]) for r in done), worst["rss_mb"], worst["kind"], worst["case"],
               slowest["seconds"], slowest["kind"], slowest["case"]))
    return 0


def main(argv):
    if len(argv) >= 2 and argv[1] == "rows":
        for r in read_table()[3]:
            if not r.get("pending") and (r["quick"] or "--quick" not in argv):
                print(r["kind"], r["case"])
        return 0
    if len(argv) == 4 and argv[1] == "setup":
        return setup(argv[2], argv[3])
    if len(argv) == 6 and argv[1] == "run":
        return run_row(*argv[2:6])
    if len(argv) >= 4 and argv[1] == "explore":  # every kind x case, for writing the table
        _, kinds, cases, _ = read_table()
        for k in kinds:
            if len(argv) > 4 and k not in argv[4:]:
                continue
            for c in cases:
                if not (k in BINARY and c in TEXT_ONLY):
                    run_row(argv[2], argv[3], k, c)
        return 0
    if len(argv) == 3 and argv[1] == "report":
        return report(argv[2])
    sys.stderr.write(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))

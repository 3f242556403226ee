#!/usr/bin/env python3
"""Who allocates: read the `alloc-trace:` stacks that cubdance prints with
CUB_ALLOC_TRACE=N under libcub_alloc_count.so (see app/cubdance/mem_stats.h)
and count them by owner and by our call site.

    scripts/alloc_sites.py TRACE_FILE [--top N]

The owner is the library of the innermost frame that is not an allocation
wrapper (libc's strdup / fopen, libstdc++'s operator new, glib's g_malloc):
our program, FluidSynth, the GL driver (Mesa, LLVM), libfreenect / fakenect,
SDL. Our call site is the innermost frame in our program, named with
addr2line (function, file:line when the build has -g)."""
import collections
import re
import subprocess
import sys

WRAPPERS = ("libcub_alloc_count", "libc.so", "libstdc++", "libglib", "libgcc_s", "ld-linux")
OWNERS = (("libfluidsynth", "FluidSynth"), ("libglib", "FluidSynth (glib)"),
          ("swrast_dri", "GL driver (Mesa)"), ("libgallium", "GL driver (Mesa)"),
          ("_dri.so", "GL driver (Mesa)"), ("libLLVM", "GL driver (LLVM)"),
          ("libgomp", "FluidSynth (OpenMP)"), ("libEGL", "GL driver (EGL)"), ("libGLES", "GL driver (GLES)"),
          ("libGLdispatch", "GL driver (glvnd)"), ("libglapi", "GL driver (glapi)"),
          ("fakenect", "fakenect (the replay)"), ("libfreenect", "libfreenect"),
          ("libSDL2", "SDL2"), ("libpng", "libpng"), ("libtinyxml2", "tinyxml2"))
FRAME = re.compile(r"^(.*)\((.*)\)\[(0x[0-9a-f]+)\]$")


def owner_of(dso, exe):
    if dso == exe:
        return "ours"
    for key, name in OWNERS:
        if key in dso:
            return name
    return dso.rsplit("/", 1)[-1]


def read_traces(path):
    """{phase: [trace]}, a trace being [(dso, where)], innermost first."""
    phases, phase, cur = {}, "start", None
    for line in open(path, errors="replace"):
        line = line.rstrip("\n")
        if line.startswith("alloc-phase:"):
            phase, cur = line.split()[1], None
        elif line.startswith("alloc-trace:"):
            cur = []
            phases.setdefault(phase, []).append(cur)
        elif cur is not None:
            m = FRAME.match(line)
            if m:
                cur.append((m.group(1), m.group(2)))
            else:
                cur = None
    return phases


def exe_of(traces):
    """Our program: the file that holds main."""
    for t in traces:
        for dso, where in t:
            if where.startswith("main+"):
                return dso
    return None


def symbolize(exe, offsets):
    """Offsets (+0x..., or symbol+0x...) in exe -> 'function file:line'."""
    plain = [o for o in offsets if o.startswith("+0x")]
    names = {}
    if plain:
        # A return address is the instruction after the call: look one back.
        addrs = ["%x" % (int(o[1:], 16) - 1) for o in plain]
        out = subprocess.run(["addr2line", "-f", "-C", "-e", exe] + addrs,
                             capture_output=True, text=True).stdout.splitlines()
        for i, o in enumerate(plain):
            fn = out[2 * i] if 2 * i < len(out) else "?"
            loc = out[2 * i + 1] if 2 * i + 1 < len(out) else "?"
            loc = re.sub(r" \(discriminator \d+\)", "", loc)
            loc = loc if not loc.startswith("??") else ""
            names[o] = (fn + " " + loc.replace("/work/", "").split("wt-memory/")[-1]).strip()
    for o in offsets:
        names.setdefault(o, o)
    return names


def main():
    args = sys.argv[1:]
    top = 25
    if "--top" in args:
        i = args.index("--top")
        top = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 1:
        sys.exit(__doc__)
    for phase, traces in read_traces(args[0]).items():
        report(phase, traces, top)


def report(phase, traces, top):
    exe = exe_of(traces)
    rows = []
    for t in traces:
        inner = [f for f in t if not any(w in f[0] for w in WRAPPERS)]
        owner = owner_of(inner[0][0], exe) if inner else "libc"
        ours = next((where for dso, where in t if dso == exe), None)
        rows.append((owner, ours))
    names = symbolize(exe, sorted({o for _, o in rows if o})) if exe else {}
    by_owner = collections.Counter(o for o, _ in rows)
    print("alloc-sites: %s: %d traced allocations; by owner: %s" % (
        phase, len(rows), ", ".join("%s %d" % kv for kv in by_owner.most_common())))
    sites = collections.Counter((o, names.get(s, "(no frame of ours)")) for o, s in rows)
    for (owner, site), n in sites.most_common(top):
        print("%6d  %-24s from %s" % (n, owner, site))


if __name__ == "__main__":
    main()

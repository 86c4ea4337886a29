#!/usr/bin/env python3
"""bench/skip: what Lobe avoids computing, each with its measured effect.

Each row runs the same work twice through `lobe shade` (shaders in bench/skip/shaders/; the
unread-globals row through `lobe render`): once where Lobe can skip part of it, once where
that part is needed, interleaved repetition by repetition, and prints medians. The difference
is what the skip saves:

  unused layer        an expensive layer nothing reads, against the same layer connected
                      (and the cheap layer alone)
  unread output       an expensive output not requested, against requested
  derivatives         noise whose derivatives nothing reads, against read
  zero-weight lobes   three lobes weighted by a parameter 0, against 1
  unused texture      a texture lookup on a branch not taken, against taken (whole process
                      at 1x1: opening OpenImageIO and the file)
  unread globals      lobe render of a uv-mapped mesh (a 256x256 grid of quads) with the stdlib
                      matte, which reads no tangent, against a matte reading dPdu, whose
                      triangles' tangents the renderer then computes at every hit (per shade:
                      whole process at 33 spp minus at 1 spp, one thread, over the difference
                      of the shade counts --stats reports)
  closure kernels     the closure code of the lobes the default scene's materials can produce
                      (lobe render --closures jit-setup, no disk cache), against every BSDF's
                      (bench/closures_jit's one module of all of them)

Per point: (whole process at RES x RES minus at 1x1) / RES^2, one thread.

  python3 bench/skip/run.py --lobe build/lobe [--reps 5] [--res 2048]
                            [--closures-jit build/bench/closures_jit]

Nothing here is asserted: the figures are reported (docs/runtime.md, "What Lobe skips").
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SHADERS = os.path.join(HERE, "shaders")
sys.path.insert(0, os.path.join(HERE, "..", "osl_compare"))
from run import make_texture, timed  # noqa: E402 (bench/osl_compare/run.py; (seconds, stdout))

# name: (what is skipped, the run that can skip it, the run that needs it[, a third reference]).
PER_POINT = {
    "unused layer": [
        ["-layer", "h", "heavy", "-layer", "l", "light", "-o", "l.g", "null"],
        ["-layer", "h", "heavy", "-layer", "l", "light", "-connect", "h", "f", "l", "x",
         "-o", "l.g", "null"],
        ["light", "-o", "g", "null"],
    ],
    "unread output": [
        ["twoout", "-o", "cheap", "null"],
        ["twoout", "-o", "cheap", "null", "-o", "costly", "null"],
    ],
    "derivatives": [
        ["derivs", "-o", "f", "null"],
        ["-param", "read_derivs", "1", "derivs", "-o", "f", "null", "-o", "d", "null"],
    ],
    "zero-weight lobes": [
        ["-param", "w", "0.0", "zerow", "-o", "Cout", "null"],
        ["-param", "w", "1.0", "zerow", "-o", "Cout", "null"],
    ],
}
LATENCY = {
    "unused texture": [
        ["tex", "-o", "c", "null"],
        ["-param", "use", "1", "tex", "-o", "c", "null"],
    ],
}


def kernels(lobe, closures_jit, work):
    """(materials' kernel compile time in s, their count) and (all BSDFs' time in s, count)."""
    env = dict(os.environ, LOBE_CACHE_DIR="off")
    r = subprocess.run([lobe, "render", "--res", "32", "16", "--spp", "1", "--closures",
                        "jit-setup", "--stats", "-o", os.path.join(work, "k.exr")],
                       env=env, capture_output=True, text=True)
    m = re.search(r"(\d+) compiled in ([\d.]+)s, (?:\d+ from the cache, )?"
                  r"(\d+) with closure kernels", r.stdout + r.stderr)
    mats = (float(m.group(2)), int(m.group(3))) if m else None
    every = None
    if closures_jit and os.path.exists(closures_jit):
        r = subprocess.run([closures_jit, "--benchmark_filter=^$"], env=env, capture_output=True,
                           text=True)
        m = re.search(r"kernels for (\d+) closures: optimise ([\d.]+) ms, machine code ([\d.]+) ms",
                      r.stdout)
        if m:
            every = ((float(m.group(2)) + float(m.group(3))) / 1000, int(m.group(1)))
    return mats, every


def write_mesh_scenes(work, n=256):
    """A wavy n x n grid of quads with uvs (2 n^2 triangles) under a constant sky, twice: with the
    stdlib matte (reads no tangent) and with tangent_matte (reads dPdu)."""
    with open(os.path.join(work, "grid.obj"), "w") as fh:
        for j in range(n + 1):
            for i in range(n + 1):
                x, z = i / n * 4 - 2, j / n * 4 - 2
                fh.write("v %.6f %.6f %.6f\nvt %.6f %.6f\n"
                         % (x, 0.1 * ((i * 7 + j * 3) % 5) / 5, z, i / n, j / n))
        for j in range(n):
            for i in range(n):
                a = j * (n + 1) + i + 1
                b, c, d = a + 1, a + n + 2, a + n + 1
                fh.write("f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d\n"
                         % (a, a, b, b, c, c, a, a, c, c, d, d))
    for name, shader in (("plain", "matte"), ("tangents", "tangent_matte")):
        with open(os.path.join(work, "mesh_%s.json" % name), "w") as fh:
            fh.write('{"camera": {"eye": [0, 3, 4], "look_at": [0, 0, 0], "fov": 50},\n'
                     ' "materials": {"m": {"shader": "%s", "params": {"Cs": [0.5, 0.5, 0.5]}}},\n'
                     ' "shapes": [{"type": "mesh", "file": "grid.obj", "material": "m"}],\n'
                     ' "environment": {"type": "constant", "color": [1, 1, 1]}}\n' % shader)


def render_ns_per_shade(lobe, work, scene):
    """ns a shade of `lobe render` on one thread: whole process at 33 spp minus at 1 spp, over
    the difference of the shade counts --stats reports."""
    runs = []
    for spp in (1, 33):
        t0 = time.perf_counter()
        r = subprocess.run([lobe, "render", scene, "--res", "256", "256", "--spp", str(spp),
                            "--threads", "1", "--stats", "-o", os.path.join(work, "m.exr")],
                           cwd=work, capture_output=True, text=True)
        t = time.perf_counter() - t0
        m = re.search(r"(\d+) shades\)", r.stdout + r.stderr)
        if r.returncode != 0 or not m:
            sys.exit("lobe render %s failed:\n%s" % (scene, r.stderr[-2000:]))
        runs.append((t, int(m.group(1))))
    return (runs[1][0] - runs[0][0]) / (runs[1][1] - runs[0][1]) * 1e9


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("--lobe", default="build/lobe")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--res", type=int, default=2048)
    ap.add_argument("--closures-jit", default="build/bench/closures_jit")
    a = ap.parse_args()
    lobe = os.path.abspath(a.lobe)
    work = tempfile.mkdtemp(prefix="lobe_skip_")
    for f in os.listdir(SHADERS):
        if f.endswith(".osl"):
            shutil.copy(os.path.join(SHADERS, f), work)
            subprocess.run([lobe, "compile", f], cwd=work, check=True, capture_output=True)
    if not make_texture(work):
        del LATENCY["unused texture"]  # no oiiotool/maketx to make the texture
    write_mesh_scenes(work)
    grid1 = ["-g", "1", "1", "-t", "1"]
    gridn = ["-g", str(a.res), str(a.res), "-t", "1"]
    times = {}
    for rep in range(a.reps):
        for name, runs in PER_POINT.items():
            for i, args in enumerate(runs):
                for g, grid in (("1", grid1), ("n", gridn)):
                    times.setdefault((name, i, g), []).append(
                        timed([lobe, "shade"] + grid + args, work)[0])
        for name, runs in LATENCY.items():
            for i, args in enumerate(runs):
                times.setdefault((name, i, "1"), []).append(
                    timed([lobe, "shade"] + grid1 + args, work)[0])
        for i, name in enumerate(("plain", "tangents")):
            times.setdefault(("unread globals", i), []).append(
                render_ns_per_shade(lobe, work, "mesh_%s.json" % name))
        print("repetition %d of %d done" % (rep + 1, a.reps), file=sys.stderr)
    med = lambda k: statistics.median(times[k])
    print("\n%s: medians of %d runs; per point at %dx%d, one thread" % (a.lobe, a.reps, a.res,
                                                                          a.res))
    print("| skipped | where skipped | where needed | saved |")
    print("|---|---|---|---|")
    for name, runs in PER_POINT.items():
        ns = [(med((name, i, "n")) - med((name, i, "1"))) / (a.res * a.res) * 1e9
              for i in range(len(runs))]
        extra = " (cheap layer alone %.1f ns)" % ns[2] if len(ns) > 2 else ""
        print("| %s | %.1f ns/pt%s | %.1f ns/pt | %.1fx |" % (name, ns[0], extra, ns[1],
                                                             ns[1] / max(ns[0], 1e-9)))
    for name, runs in LATENCY.items():
        ms = [med((name, i, "1")) * 1000 for i in range(len(runs))]
        print("| %s | %.0f ms (1x1 process) | %.0f ms | %.0f ms |" % (name, ms[0], ms[1],
                                                                      ms[1] - ms[0]))
    g = [med(("unread globals", i)) for i in range(2)]
    print("| unread globals (tangents) | %.1f ns a shade (lobe render) | %.1f ns | %+.1f ns |"
          % (g[0], g[1], g[1] - g[0]))
    mats, every = kernels(lobe, os.path.abspath(a.closures_jit), work)
    if mats and every:
        print("| closure kernels | %d materials' own lobes: %.2f s on 2 threads | all %d BSDFs: "
              "%.2f s a material | %.1fx |" % (mats[1], mats[0], every[1], every[0],
                                               every[0] * mats[1] / 2 / mats[0]))
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()

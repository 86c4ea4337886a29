#!/usr/bin/env python3
"""Lobe against Embree's tutorial path tracer (and OSL's testrender) on one scene.

    python3 bench/embree_compare/run.py --lobe build/lobe [--reps 3] [--out DIR]
        [--spp 16] [--res 512] [--threads 2] [--ref-spp 512] [--curve 1,2,4,8,16,32]

Scene (gen_spheres.py, written into DIR): 64 tessellated spheres on a ground quad (524,290
triangles), grey Lambert 0.5, uniform light of radiance 1 (`pathtracer --ambientlight 1 1 1`,
Lobe: a constant environment), max path length 8.

1. Equal spp: whole-process wall time of `pathtracer` and `lobe render` at --spp, interleaved
   (Lobe with --no-aovs: both write the image alone, no albedo/normal/depth channels)
   (rep, renderer), --reps times; medians and the Embree/Lobe ratio (above 1: Lobe faster).
   Lobe's own split is printed from `lobe render --stats`.
2. Error against time: each renderer at the --curve sample counts, relMSE (mean over pixels and
   RGB of (x-r)^2/(r^2+0.01)) against its own converged image (--ref-spp, cached in DIR)
   that shares no samples with the curve: Lobe's with another seed; pathtracer and testrender
   take no seed and seed each sample by pixel and sample index (so a plain reference would
   start with the curve image's own samples, and the fireflies they share would cancel in
   the relative error), so theirs is rendered REF_PAD pixels wider on every side, the field
   of view widened to keep the pixel size, and cropped. Whole-process time; both curves are
   interpolated log-log at common times for the equal-time ratio. Writes DIR/embree_compare.csv and DIR/embree_compare.png (log-log).
3. With OSL_BIN exported (`export $(bash ../shared/osl-reference/setup.sh)`): testrender and Lobe on
   the same scene with analytic spheres (testrender reads no meshes), spheres.xml, added to
   the CSV and the plot.

Needs Debian's embree-tools (pathtracer), python3-numpy, python3-matplotlib and
python3-openimageio (run with /usr/bin/python3 if another python3 comes first on PATH).
Embree's pathtracer writes 8-bit-quantised, clamped [0, 1] values into its .pfm output and adds
the ambient light both through light sampling and through BSDF-sampled rays that escape (so
its image is brighter than Lobe's); each renderer is therefore compared with its own converged
image, as the issue asks.
"""
import argparse
import csv
import math
import os
import shutil
import statistics
import subprocess
import sys
import time

try:
    import numpy as np
    import OpenImageIO as oiio
except ImportError:
    if sys.executable != "/usr/bin/python3" and os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    raise

HERE = os.path.dirname(os.path.abspath(__file__))
# Renderers without a seed render their reference REF_PAD pixels wider on every side (pixel
# size kept) and cropped: the same pixels, other random numbers.
REF_PAD = 8


def read_image(path):
    if path.endswith(".pfm"):
        with open(path, "rb") as fh:
            data = fh.read()
        parts = data.split(b"\n", 3)
        w, h = map(int, parts[1].split())
        scale = float(parts[2])
        a = np.frombuffer(parts[3][: w * h * 12], dtype="<f4" if scale < 0 else ">f4")
        return a.reshape(h, w, 3)[::-1].astype(np.float64)  # PFM rows run bottom to top
    inp = oiio.ImageInput.open(path)
    if not inp:
        raise RuntimeError("cannot read " + path)
    a = inp.read_image("float")
    inp.close()
    return np.asarray(a, dtype=np.float64)[:, :, :3]


def rel_mse(x, ref):
    return float(np.mean((x - ref) ** 2 / (ref * ref + 0.01)))


def timed(cmd, cwd):
    t0 = time.perf_counter()
    r = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (r.returncode, " ".join(cmd), r.stdout))
    return dt, r.stdout


class Embree:
    name = "embree"

    def __init__(self, a, d):
        self.a, self.d = a, d
        with open(os.path.join(d, "camera.txt")) as fh:
            self.cam = fh.read().split()

    def cmd(self, spp, out, seed=0, pad=0):
        # pathtracer has no seed option: its sampler is seeded per pixel and sample, so a
        # reference shares no samples with the curve only when its pixels are shifted (pad).
        cam = list(self.cam)
        cam[cam.index("--fov") + 1] = "%.7f" % widened_fov(float(cam[cam.index("--fov") + 1]),
                                                           self.a.res, pad)
        n = str(self.a.res + 2 * pad)
        return (["pathtracer", "-i", "spheres.obj"] + cam +
                ["--size", n, n, "--spp", str(spp),
                 "--max-path-length", "8", "--ambientlight", "1", "1", "1",
                 "--threads", str(self.a.threads), "-o", out + ".pfm"]), out + ".pfm"


class Lobe:
    name = "lobe"

    def __init__(self, a, d, scene="spheres.json", name="lobe"):
        self.a, self.d, self.scene, self.name = a, d, scene, name

    def cmd(self, spp, out, seed=1, extra=()):
        cmd = [self.a.lobe, "render", self.scene, "--res", str(self.a.res), str(self.a.res),
               "--spp", str(spp), "--max-depth", "8", "--threads", str(self.a.threads),
               "--seed", str(seed), "-q", "--no-aovs", "-o", out + ".exr"]
        return cmd + list(extra), out + ".exr"


class TestRender:
    name = "testrender"

    def __init__(self, a, d):
        self.a, self.d = a, d
        self.bin = os.path.join(os.environ["OSL_BIN"], "testrender")

    def cmd(self, spp, out, seed=0, pad=0):
        aa = max(1, int(round(math.sqrt(spp))))  # -aa N is N x N samples
        n = str(self.a.res + 2 * pad)
        return ([self.bin, "-t", str(self.a.threads), "--res", n, n, "-aa", str(aa),
                 "spheres_pad%d.xml" % pad if pad else "spheres.xml", out + ".exr"]), out + ".exr"


def widened_fov(fov, res, pad):
    """The vertical field of view (degrees) that keeps the pixel size at res + 2 pad pixels."""
    return math.degrees(2 * math.atan(math.tan(math.radians(fov) / 2) * (res + 2 * pad) / res))


def write_xml(d, name="spheres.xml", pad=0, res=512):
    """The same scene with analytic spheres, in testrender's XML (Lobe reads it too)."""
    lines = ["<World>",
             '  <Camera eye="0, 4.2, 8.6" look_at="0, 0.2, 0" fov="%.7f" />'
             % widened_fov(tr_fov(40.0), res, pad),
             '  <Option max_bounces="int 8" />',
             "  <ShaderGroup>color Cs 0.5 0.5 0.5; shader bench_matte grey;</ShaderGroup>",
             '  <Quad corner="-30, 0, 30" edge_x="60, 0, 0" edge_y="0, 0, -60" />']
    for i in range(8):
        for j in range(8):
            lines.append('  <Sphere center="%g, 0.4, %g" radius="0.4" />' % (-3.5 + i, -3.5 + j))
    lines += ["  <ShaderGroup>color Cs 1 1 1; shader bench_bg bg;</ShaderGroup>",
              '  <Background resolution="1" />', "</World>"]
    with open(os.path.join(d, name), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    for s in ("bench_matte.osl", "bench_bg.osl"):
        shutil.copy(os.path.join(HERE, s), d)


def tr_fov(vertical_deg):
    # testrender: the image height spans tan(fov/2) at distance 2, i.e. a vertical angle of
    # 2 atan(tan(fov/2)/2); invert for the vertical angle the OBJ camera uses.
    return math.degrees(2 * math.atan(2 * math.tan(math.radians(vertical_deg) / 2)))


def interp_loglog(pts, t):
    """relMSE at time t on the log-log polyline through (seconds, relmse) points."""
    pts = sorted(pts)
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if t0 <= t <= t1 and t1 > t0:
            f = (math.log(t) - math.log(t0)) / (math.log(t1) - math.log(t0))
            return math.exp(math.log(e0) + f * (math.log(e1) - math.log(e0)))
    return None


def save_loglog(path, curves, xlabel, ylabel, title):
    """A log-log plot of relMSE against time: curves are (points (t, e), style, label)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 5))
    for points, style, label in curves:
        p = sorted(points)
        ax.loglog([x for x, _ in p], [y for _, y in p], style, label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lobe", required=True)
    ap.add_argument("--out", default="bench_out/embree_compare")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--res", type=int, default=512)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--ref-spp", type=int, default=512)
    ap.add_argument("--curve", default="1,2,4,8,16,32")
    a = ap.parse_args()
    a.lobe = os.path.abspath(a.lobe)
    d = os.path.abspath(a.out)
    os.makedirs(d, exist_ok=True)
    if not os.path.exists(os.path.join(d, "spheres.obj")):
        subprocess.run([sys.executable, os.path.join(HERE, "gen_spheres.py"), d], check=True)
    if shutil.which("pathtracer") is None:
        sys.exit("pathtracer not found: apt-get install embree-tools")
    embree, lobe = Embree(a, d), Lobe(a, d)
    renderers = [embree, lobe]
    if os.environ.get("OSL_BIN"):
        write_xml(d)
        write_xml(d, "spheres_pad%d.xml" % REF_PAD, REF_PAD, a.res)
        for s in ("bench_matte", "bench_bg"):
            subprocess.run([os.path.join(os.environ["OSL_BIN"], "oslc"), "-q", s + ".osl"],
                           cwd=d, check=True, stdout=subprocess.DEVNULL)
        renderers += [TestRender(a, d), Lobe(a, d, "spheres.xml", "lobe_xml")]

    # 1. Equal spp, interleaved.
    times = {r.name: [] for r in renderers}
    for rep in range(a.reps):
        for r in renderers:
            cmd, _ = r.cmd(a.spp, os.path.join(d, "eq_%s" % r.name))
            times[r.name].append(timed(cmd, d)[0])
    med = {k: statistics.median(v) for k, v in times.items()}
    print("equal spp (%d spp, %dx%d, %d threads, %d reps, whole process, median s):"
          % (a.spp, a.res, a.res, a.threads, a.reps))
    for k, v in med.items():
        print("  %-11s %7.2f   (%s)" % (k, v, " ".join("%.2f" % x for x in times[k])))
    print("  Embree/Lobe %.2f (above 1: Lobe faster)" % (med["embree"] / med["lobe"]))
    if "testrender" in med:
        print("  testrender/Lobe(xml) %.2f" % (med["testrender"] / med["lobe_xml"]))
    cmd, _ = lobe.cmd(a.spp, os.path.join(d, "stats_lobe"), extra=["--stats"])
    cmd.remove("-q")
    print("".join("  " + l + "\n" for l in timed(cmd, d)[1].splitlines() if l))

    # 2. Error against time.
    rows = []
    curve = [int(x) for x in a.curve.split(",")]
    refs = {}
    for r in renderers:
        # Lobe's references take another seed; the others' shift their pixels (see cmd()).
        pad = 0 if r.name.startswith("lobe") else REF_PAD
        ref = os.path.join(d, "ref_%s_%d%s" % (r.name, a.ref_spp, "_pad%d" % pad if pad else ""))
        cmd, path = r.cmd(a.ref_spp, ref, seed=7777, **({"pad": pad} if pad else {}))
        if not os.path.exists(path):
            print("reference %s: %d spp ..." % (r.name, a.ref_spp), flush=True)
            timed(cmd, d)
        refs[r.name] = read_image(path)[pad:pad + a.res, pad:pad + a.res]
    for spp in curve:
        for r in renderers:
            cmd, path = r.cmd(spp, os.path.join(d, "c_%s_%d" % (r.name, spp)))
            t, _ = timed(cmd, d)
            e = rel_mse(read_image(path), refs[r.name])
            rows.append((r.name, spp, t, e))
            print("  %-11s %4d spp %7.2f s  relMSE %.5f" % (r.name, spp, t, e), flush=True)
    with open(os.path.join(d, "embree_compare.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["renderer", "spp", "seconds", "relmse"])
        w.writerows(rows)
    pts = {r.name: [(t, e) for (n, s, t, e) in rows if n == r.name] for r in renderers}
    print("equal time (relMSE interpolated log-log):")
    pairs = [("embree", "lobe")] + ([("testrender", "lobe_xml")] if "testrender" in pts else [])
    for ref_name, lobe_name in pairs:
        for (n, s, t, e) in rows:
            if n != ref_name:
                continue
            le = interp_loglog(pts[lobe_name], t)
            if le:
                print("  at %.2f s (%s %d spp): %s %.5f  %s %.5f  ratio %s/%s %.2f"
                      % (t, ref_name, s, ref_name, e, lobe_name, le, lobe_name, ref_name, le / e))

    style = {"embree": "s-", "lobe": "o-", "testrender": "^--", "lobe_xml": "v--"}
    label = {"embree": "Embree pathtracer (OBJ)", "lobe": "Lobe (OBJ)",
             "testrender": "OSL testrender (analytic spheres)",
             "lobe_xml": "Lobe (analytic spheres, XML)"}
    save_loglog(os.path.join(d, "embree_compare.png"),
                [(pts[r.name], style[r.name], label[r.name]) for r in renderers],
                "whole-process time (s), %d threads" % a.threads,
                "relMSE against own %d-spp image" % a.ref_spp,
                "64 spheres, 524k triangles, uniform light, %dx%d" % (a.res, a.res))
    print("wrote %s/embree_compare.csv and %s/embree_compare.png" % (d, d))


if __name__ == "__main__":
    main()

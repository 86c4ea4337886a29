#!/usr/bin/env python3
"""Lobe against OSL's testrender on a testrender scene: set-up, equal samples, equal time.

    export $(bash ../shared/osl-reference/setup.sh)
    python3 bench/testrender_compare/run.py --lobe build/lobe [--reps 3] [--out DIR]
        [--res 320 240] [--threads 2] [--ref-aa 24] [--curve-aa 1,2,4,8] [--probe FILE]
        [--scene OTHER.xml]

Scene (scene.xml and its shaders, copied into DIR and compiled there with OSL's oslc for
testrender): an angular light probe through a texture() background shader with a
1024-resolution importance table, a checkerboard floor and wall, a matte, a glossy and a glass
sphere. The probe is --probe (an angular map, e.g. OSL's kitchen_probe.hdr, which
../shared/osl-conformance/cases/common/textures/ holds and is the default when present) or,
without one, a generated 512x512 sky-and-sun probe.

1. Set-up: whole process at 8x8 and one sample (scene load, shader compile, background table,
   OpenImageIO start-up; no image to speak of), interleaved, --reps times, medians.
2. Equal samples: whole process at -aa 4 (16 samples a pixel), interleaved, medians and the
   testrender/Lobe ratio (above 1: Lobe faster); Lobe's own split from --stats.
3. Error against time: each renderer at -aa N for N in --curve-aa (Lobe at N*N spp), relMSE
   (mean over pixels and RGB of (x-r)^2/(r^2+0.01)) against its own converged image, made
   so that it shares no samples with the curve: Lobe's at R*R spp (--ref-aa R) with another
   seed; testrender's at -aa R over a frame PAD pixels wider on every side, the field of view
   widened to keep the pixel size, then cropped: the same pixels and pixel filter, other
   random numbers. (testrender takes no seed and seeds each sample by its pixel and sample
   index, so its -aa N image is the first N*N samples of a plain -aa R reference; the
   fireflies the two share then cancel in the relative error, and its error is understated:
   0.119 against 0.146 at -aa 4 on this scene, the two images' deviations correlating at
   0.76 at -aa 8. That plain reference is still rendered, for the image means and for the
   understated figure, printed beside the fair one for continuity with earlier runs.)
   Whole-process time; Lobe's relMSE interpolated log-log at testrender's times gives the
   equal-time ratio. Writes DIR/testrender_compare.csv and .png. Image means of the
   references are printed side by side (the same picture: within a few per cent).
"""
import argparse
import csv
import math
import os
import re
import shutil
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "embree_compare"))
from run import interp_loglog, read_image, rel_mse, save_loglog, timed  # noqa: E402 (re-execs for numpy)

import numpy as np  # noqa: E402

SHADERS = ("envmap", "checker", "tr_mat", "tr_glossy", "tr_glass")
DEFAULT_PROBE = os.path.join(HERE, "..", "..", "..", "shared", "osl-conformance", "cases",
                             "common", "textures", "kitchen_probe.hdr")


def make_probe(path):
    """A 512x512 angular probe: a blue-to-white sky, a dark ground, a small bright sun."""
    import OpenImageIO as oiio
    n = 512
    y, x = np.mgrid[0:n, 0:n]
    px, py = (x + 0.5) / n * 2 - 1, 1 - (y + 0.5) / n * 2
    r = np.sqrt(px * px + py * py)
    theta = np.clip(r, 0, 1) * math.pi  # angle from -Z
    with np.errstate(invalid="ignore", divide="ignore"):
        s = np.where(r > 0, np.sin(theta) / r, 0)
    dx, dy, dz = px * s, py * s, -np.cos(theta)
    sky = np.stack([0.3 + 0.7 * (1 - dy), 0.5 + 0.5 * (1 - dy), np.ones_like(dy)], -1)
    img = np.where((dy > 0)[..., None], sky * np.clip(dy, 0.1, 1)[..., None] + 0.2, 0.15)
    sun = np.array([0.5, 0.6, -0.62]) / np.linalg.norm([0.5, 0.6, -0.62])
    img[(dx * sun[0] + dy * sun[1] + dz * sun[2]) > math.cos(math.radians(3))] = [60, 55, 45]
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(n, n, 3, "float"))
    out.write_image(img.astype(np.float32))
    out.close()


def testrender_cmd(a, aa, out, res=None):
    res = res or a.res
    return [os.path.join(os.environ["OSL_BIN"], "testrender"), "-t", str(a.threads),
            "--res", str(res[0]), str(res[1]), "-aa", str(aa), "scene.xml", out]


def lobe_cmd(a, spp, out, seed=1, res=None, extra=()):
    res = res or a.res
    return [a.lobe, "render", "scene.xml", "--res", str(res[0]), str(res[1]), "--spp", str(spp),
            "--threads", str(a.threads), "--seed", str(seed), "-q", "--no-aovs", "-o", out] + list(extra)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lobe", required=True)
    ap.add_argument("--out", default="bench_out/testrender_compare")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--res", type=int, nargs=2, default=[320, 240])
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--ref-aa", type=int, default=24)
    ap.add_argument("--curve-aa", default="1,2,4,8")
    ap.add_argument("--probe", default=DEFAULT_PROBE)
    ap.add_argument("--scene", default=None,
                    help="another testrender XML scene (its folder's .osl files are its shaders; "
                         "an <Option aa=...> is dropped so that -aa and --spp set the samples)")
    a = ap.parse_args()
    if not os.environ.get("OSL_BIN"):
        sys.exit("OSL_BIN is not set: export $(bash ../shared/osl-reference/setup.sh)")
    a.lobe = os.path.abspath(a.lobe)
    d = os.path.abspath(a.out)
    os.makedirs(d, exist_ok=True)
    if a.scene:
        with open(a.scene) as fh:
            xml = re.sub(r'\s+aa="[^"]*"', "", fh.read())
        with open(os.path.join(d, "scene.xml"), "w") as fh:
            fh.write(xml)
        folder = os.path.dirname(os.path.abspath(a.scene))
        shaders = [f[:-4] for f in sorted(os.listdir(folder)) if f.endswith(".osl")]
        src = folder
    else:
        shutil.copy(os.path.join(HERE, "scene.xml"), d)
        shaders, src = SHADERS, HERE
    for s in shaders:
        shutil.copy(os.path.join(src, s + ".osl"), d)
        subprocess.run([os.path.join(os.environ["OSL_BIN"], "oslc"), "-q", s + ".osl"], cwd=d,
                       check=True, stdout=subprocess.DEVNULL)
    probe = os.path.join(d, "probe.hdr")
    if a.probe and os.path.exists(a.probe):
        shutil.copy(a.probe, probe)
        print("probe: %s" % os.path.abspath(a.probe))
    else:
        make_probe(probe)
        print("probe: generated sky and sun")

    # 1. Set-up, 2. equal samples: interleaved.
    runs = {"setup testrender": [], "setup lobe": [], "16spp testrender": [], "16spp lobe": []}
    for rep in range(a.reps):
        runs["setup testrender"].append(
            timed(testrender_cmd(a, 1, "s_tr.exr", res=(8, 8)), d)[0])
        runs["setup lobe"].append(timed(lobe_cmd(a, 1, "s_lobe.exr", res=(8, 8)), d)[0])
        runs["16spp testrender"].append(timed(testrender_cmd(a, 4, "eq_tr.exr"), d)[0])
        runs["16spp lobe"].append(timed(lobe_cmd(a, 16, "eq_lobe.exr"), d)[0])
    med = {k: statistics.median(v) for k, v in runs.items()}
    print("whole process, median of %d interleaved runs (%d threads):" % (a.reps, a.threads))
    for k, v in med.items():
        print("  %-17s %6.2f s   (%s)" % (k, v, " ".join("%.2f" % x for x in runs[k])))
    print("  set-up testrender/Lobe %.2f, 16 spp testrender/Lobe %.2f (above 1: Lobe faster)"
          % (med["setup testrender"] / med["setup lobe"],
             med["16spp testrender"] / med["16spp lobe"]))
    cmd = lobe_cmd(a, 16, "stats_lobe.exr", extra=["--stats"])
    cmd.remove("-q")
    print("".join("  " + l + "\n" for l in timed(cmd, d)[1].splitlines() if l))

    # 3. Error against time.
    ref_tr = os.path.join(d, "ref_tr_%d.exr" % a.ref_aa)
    ref_lobe = os.path.join(d, "ref_lobe_%d.exr" % a.ref_aa)
    if not os.path.exists(ref_tr):
        print("reference testrender -aa %d ..." % a.ref_aa, flush=True)
        timed(testrender_cmd(a, a.ref_aa, ref_tr), d)
    if not os.path.exists(ref_lobe):
        print("reference lobe %d spp ..." % (a.ref_aa ** 2), flush=True)
        timed(lobe_cmd(a, a.ref_aa ** 2, ref_lobe, seed=7777), d)
    # testrender's independent reference: PAD more pixels on every side, the vertical field of
    # view widened by (H + 2 PAD) / H (testrender's fov spans the image height), then cropped.
    pad = 8
    ref_tr_indep = os.path.join(d, "ref_tr_shifted_%d.exr" % a.ref_aa)
    if not os.path.exists(ref_tr_indep):
        print("reference testrender -aa %d, pixels shifted by %d ..." % (a.ref_aa, pad), flush=True)
        with open(os.path.join(d, "scene.xml")) as fh:
            xml = fh.read()
        fov = float(re.search(r'<Camera[^>]*fov="([^"]+)"', xml).group(1))
        wide = math.degrees(2 * math.atan(math.tan(math.radians(fov) / 2) *
                                          (a.res[1] + 2 * pad) / a.res[1]))
        with open(os.path.join(d, "scene_shifted.xml"), "w") as fh:
            fh.write(re.sub(r'(<Camera[^>]*fov=")[^"]+"', r'\g<1>%.7f"' % wide, xml, count=1))
        cmd = testrender_cmd(a, a.ref_aa, ref_tr_indep, res=(a.res[0] + 2 * pad, a.res[1] + 2 * pad))
        cmd[cmd.index("scene.xml")] = "scene_shifted.xml"
        timed(cmd, d)
    shifted = read_image(ref_tr_indep)[pad:pad + a.res[1], pad:pad + a.res[0]]
    refs = {"testrender": read_image(ref_tr), "lobe": read_image(ref_lobe)}
    indep = {"testrender": shifted, "lobe": refs["lobe"]}
    print("plain and shifted testrender references agree to relMSE %.5f (the shifted one's mean"
          " %s)" % (rel_mse(refs["testrender"], shifted),
                    " ".join("%.4f" % m for m in shifted.mean(axis=(0, 1)))))
    print("reference image means (R G B): testrender %s, Lobe %s" % (
        " ".join("%.4f" % m for m in refs["testrender"].mean(axis=(0, 1))),
        " ".join("%.4f" % m for m in refs["lobe"].mean(axis=(0, 1)))))
    rows = []
    for aa in [int(x) for x in a.curve_aa.split(",")]:
        for name in ("testrender", "lobe"):
            out = os.path.join(d, "c_%s_%d.exr" % (name, aa))
            cmd = testrender_cmd(a, aa, out) if name == "testrender" else lobe_cmd(a, aa * aa, out)
            t, _ = timed(cmd, d)
            img = read_image(out)
            e, e_plain = rel_mse(img, indep[name]), rel_mse(img, refs[name])
            rows.append((name, aa * aa, t, e, e_plain))
            print("  %-11s %4d spp %7.2f s  relMSE %.5f%s" % (
                name, aa * aa, t, e, "" if name == "lobe" else
                " (against the plain reference, sharing its samples: %.5f)" % e_plain), flush=True)
    with open(os.path.join(d, "testrender_compare.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["renderer", "spp", "seconds", "relmse", "relmse_plain_reference"])
        w.writerows(rows)
    pts = {n: [(t, e) for (m, s, t, e, _) in rows if m == n] for n in ("testrender", "lobe")}
    print("equal time (Lobe's relMSE interpolated log-log at testrender's times):")
    for (n, s, t, e, _) in rows:
        if n != "testrender":
            continue
        le = interp_loglog(pts["lobe"], t)
        if le:
            print("  at %.2f s (testrender %d spp): testrender %.5f  lobe %.5f  ratio lobe/testrender"
                  " %.2f" % (t, s, e, le, le / e))

    save_loglog(os.path.join(d, "testrender_compare.png"),
                [(pts["testrender"], "^--", "OSL testrender"), (pts["lobe"], "o-", "Lobe")],
                "whole-process time (s), %d threads" % a.threads,
                "relMSE against own independent %d-spp image" % (a.ref_aa ** 2),
                "testrender %s, %dx%d" % ((os.path.basename(a.scene) if a.scene else
                                           "envmap scene",) + tuple(a.res)))
    print("wrote %s/testrender_compare.csv and %s/testrender_compare.png" % (d, d))


if __name__ == "__main__":
    main()

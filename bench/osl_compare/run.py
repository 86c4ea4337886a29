#!/usr/bin/env python3
"""bench/osl_compare: lobe shade against OSL's testshade, side by side in one run.

Runs a suite of shaders (bench/osl_compare/shaders/) through `lobe shade` and, when OSL_BIN is
set (e.g. `eval "$(bash ../shared/osl-reference/setup.sh)"`), through `$OSL_BIN/testshade` with
the same arguments. Runs are interleaved (case by case, tool by tool, repetition by repetition)
so that the load of a shared machine falls on both alike, and medians are reported:

  (a) latency   whole process at 1x1, default threads (start-up + compile + JIT + one point)
  (b) per point the shading time on one thread as each tool reports it (testshade --runstats
                "Run", lobe shade --stats "us per point"), at RES x RES minus at 1x1, over
                RES^2 - 1 points: the first point's one-off costs (opening a texture; in Lobe,
                loading OpenImageIO at the first lookup) cancel as in a difference of whole
                processes, but not the noise of two process start-ups (OSL's alone varies by
                0.2 s here). The CSV also keeps that older difference of whole processes.
  (c) wall      whole process at RES x RES, default threads

and OSL/Lobe ratios (above 1: Lobe is faster). Without OSL_BIN only Lobe's figures are printed.

  python3 bench/osl_compare/run.py --lobe build/lobe [--reps 5] [--res 1024] [-k NAME] [--csv F]
                                   [--base OTHER_LOBE]

--base runs a second lobe binary (e.g. a copy of main's) interleaved with the others, and prints
its table too, so a change is measured before and after in one session.

Nothing here is asserted: the figures are reported (issue notes, bench/README.md).
"""
import argparse
import csv
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SHADERS = os.path.join(HERE, "shaders")

# name: (shader files to compile, testshade arguments naming the group and its outputs).
# Every output is requested with -o so that neither system may optimise the work away.
CASES = {
    "fbm_perlin": (["fbm_perlin"], ["fbm_perlin", "-o", "f", "null"]),
    "noise_triple": (["noise_triple"], ["noise_triple", "-o", "disp", "null", "-o", "c", "null"]),
    "cell_voronoi": (["cell_voronoi"],
                     ["cell_voronoi", "-o", "f1", "null", "-o", "f2", "null", "-o", "id", "null"]),
    "simplex": (["simplex"], ["simplex", "-o", "f", "null"]),
    "periodic": (["periodic"], ["periodic", "-o", "f", "null", "-o", "c", "null"]),
    "texture": (["texture_lookup"],
                ["texture_lookup", "-o", "c", "null", "-o", "a", "null"]),
    "marble": (["marble"], ["marble", "-o", "Cs", "null", "-o", "Cout", "null"]),
    "strings_branches": (["strings_branches"],
                         ["strings_branches", "-o", "f", "null", "-o", "n", "null"]),
    "matrix_transform": (["matrix_transform"],
                         ["matrix_transform", "-o", "q", "null", "-o", "det", "null"]),
    # A MaterialX-style network: position -> noise and fractal -> mix -> surface. (Parameter values
# are typed as testshade reads them: "4" would be an int and a bare "0.9 0.7 0.3" a string,
# which both tools refuse with a warning and leave the default.)
    "mx_network": (["mx_position", "mx_noise3d", "mx_fractal3d", "mx_mix", "mx_surface"],
                   ["-param", "scale", "4.0", "-shader", "mx_position", "pos",
                    "-param", "amplitude", "0.5", "-param", "pivot", "0.5",
                    "-shader", "mx_noise3d", "n1",
                    "-param", "octaves", "5", "-shader", "mx_fractal3d", "n2",
                    "-param:type=color", "fg", "0.9 0.7 0.3", "-shader", "mx_mix", "mixer",
                    "-shader", "mx_surface", "surf",
                    "-connect", "pos", "out", "n1", "position",
                    "-connect", "pos", "out", "n2", "position",
                    "-connect", "n1", "out", "mixer", "mix_amount",
                    "-connect", "n2", "out", "surf", "roughness",
                    "-connect", "mixer", "out", "surf", "base_color",
                    "-o", "surf.albedo", "null", "-o", "surf.out", "null"]),
    "uber": (["uber"], ["uber", "-o", "Cout", "null"]),
}


def make_texture(work):
    """A 512x512 checker texture, made mip-mapped and tiled with OIIO's maketx (grid.tx)."""
    src = os.path.join(work, "grid_src.exr")
    tx = os.path.join(work, "grid.tx")
    if shutil.which("oiiotool") and shutil.which("maketx"):
        subprocess.run(["oiiotool", "--pattern", "checker:width=32:height=32", "512x512", "3",
                        "-o", src], check=True, capture_output=True)
        subprocess.run(["maketx", src, "-o", tx], check=True, capture_output=True)
        return True
    return False


def prepare(work, osl_bin):
    for f in os.listdir(SHADERS):
        if f.endswith(".osl"):
            shutil.copy(os.path.join(SHADERS, f), work)
    if osl_bin:
        for f in os.listdir(work):
            if f.endswith(".osl"):
                subprocess.run([os.path.join(osl_bin, "oslc"), "-q", f], cwd=work, check=True)
    return make_texture(work)


def timed(cmd, work):
    """(wall seconds, stdout) of one run."""
    t0 = time.perf_counter()
    r = subprocess.run(cmd, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (r.returncode, " ".join(cmd), r.stderr.decode()[-2000:]))
    return dt, r.stdout.decode(errors="replace")


def reported_shading_s(tool, out, points):
    """The shading time a run reports of itself: testshade's "Run   : 0.4736s" (--runstats),
    lobe's "shade: N points, 0.452 us per point" (--stats)."""
    for line in out.splitlines():
        if tool == "osl" and line.startswith("Run") and ":" in line:
            return float(line.split(":")[1].strip().rstrip("s"))
        if tool != "osl" and line.strip().startswith("shade:") and "us per point" in line:
            return float(line.split(",")[1].split()[0]) * 1e-6 * points
    sys.exit("no shading time in the output of %s (%s)" % (tool, out[-500:]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("--lobe", default="build/lobe")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--res", type=int, default=1024)
    ap.add_argument("-k", dest="only", action="append", help="run only cases containing NAME")
    ap.add_argument("--csv", help="write the medians as CSV")
    ap.add_argument("--base", help="a second lobe binary, measured interleaved (before/after)")
    a = ap.parse_args()
    lobe = os.path.abspath(a.lobe)
    osl_bin = os.environ.get("OSL_BIN")
    tools = [("lobe", [lobe, "shade"])]
    if a.base:
        tools.append(("base", [os.path.abspath(a.base), "shade"]))
    if osl_bin:
        tools.insert(0, ("osl", [os.path.join(osl_bin, "testshade")]))
    cases = {n: c for n, c in CASES.items() if not a.only or any(k in n for k in a.only)}
    work = tempfile.mkdtemp(prefix="osl_compare_")
    have_tex = prepare(work, osl_bin)
    if not have_tex:
        cases.pop("texture", None)
        print("(no oiiotool/maketx: the texture case is skipped)")
    res = str(a.res)
    measures = {  # name: (grid and threads, whether at default threads)
        "latency": (["-g", "1", "1"], True),
        "point_1t": (["-g", res, res, "-t", "1"], False),
        "ref_1t": (["-g", "1", "1", "-t", "1"], False),
        "wall": (["-g", res, res], True),
    }
    stats_flag = {"osl": ["--runstats"], "lobe": ["--stats"], "base": ["--stats"]}
    times = {}  # (case, tool, measure) -> [seconds]
    for rep in range(a.reps):
        for name, (_, args) in cases.items():
            for m, (grid, default_threads) in measures.items():
                for tool, cmd in tools:
                    extra = [] if default_threads else stats_flag[tool]
                    dt, out = timed(cmd + grid + extra + args, work)
                    times.setdefault((name, tool, m), []).append(dt)
                    if not default_threads:
                        points = a.res * a.res if m == "point_1t" else 1
                        times.setdefault((name, tool, "reported_" + m), []).append(
                            reported_shading_s(tool, out, points))
        print("repetition %d of %d done" % (rep + 1, a.reps), file=sys.stderr)

    def med(name, tool, m):
        return statistics.median(times[(name, tool, m)])

    rows = []
    for name in cases:
        row = {"case": name}
        for tool, _ in tools:
            row[tool + "_latency_ms"] = 1e3 * med(name, tool, "latency")
            row[tool + "_ns_per_point_1t"] = 1e9 * max(
                0.0, med(name, tool, "reported_point_1t") - med(name, tool, "reported_ref_1t")) / (
                    a.res * a.res - 1)
            row[tool + "_ns_per_point_1t_diff"] = 1e9 * max(
                0.0, med(name, tool, "point_1t") - med(name, tool, "ref_1t")) / (a.res * a.res)
            row[tool + "_wall_s"] = med(name, tool, "wall")
        rows.append(row)

    def table(lobe_tool):
        print("\n%s: medians of %d runs, %dx%d grid%s" % (
            dict(tools)[lobe_tool][0], a.reps, a.res, a.res, "" if osl_bin else " (OSL_BIN not set)"))
        if osl_bin:
            hdr = "%-18s %10s %10s %6s | %9s %9s %6s | %8s %8s %6s" % (
                "case", "osl 1x1", "lobe 1x1", "ratio", "osl ns/pt", "lobe", "ratio",
                "osl wall", "lobe", "ratio")
            print(hdr)
            print("-" * len(hdr))
            for r in rows:
                def ratio(o, l):
                    return (r["osl_" + o] / r[lobe_tool + "_" + l] if r[lobe_tool + "_" + l] > 0
                            else float("inf"))
                print("%-18s %8.0fms %8.0fms %6.2f | %9.1f %9.1f %6.2f | %7.2fs %7.2fs %6.2f" % (
                    r["case"], r["osl_latency_ms"], r[lobe_tool + "_latency_ms"],
                    ratio("latency_ms", "latency_ms"), r["osl_ns_per_point_1t"],
                    r[lobe_tool + "_ns_per_point_1t"], ratio("ns_per_point_1t", "ns_per_point_1t"),
                    r["osl_wall_s"], r[lobe_tool + "_wall_s"], ratio("wall_s", "wall_s")))
        else:
            print("%-18s %10s %12s %10s" % ("case", "1x1", "ns/pt (1t)", "wall"))
            for r in rows:
                print("%-18s %8.0fms %12.1f %9.2fs" % (
                    r["case"], r[lobe_tool + "_latency_ms"], r[lobe_tool + "_ns_per_point_1t"],
                    r[lobe_tool + "_wall_s"]))

    if a.base:
        table("base")
    table("lobe")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows(rows)
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()

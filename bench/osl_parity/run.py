#!/usr/bin/env python3
"""bench/osl_parity: numeric parity of `lobe shade` against OSL's testshade, point by point.

Generates small shaders (into a temporary directory) that printf, at every point of an N x N
grid, the result of a library function ("%.9g", all components of triples and matrices) and,
for float and triple results, its Dx() derivative. Each shader is run through `lobe shade`
and through `$OSL_BIN/testshade` with identical arguments (-g N N -t 1, at -O2 and at -O0),
and for every case (a table row; a row gathers a few variants, e.g. float and colour results
on ordinary, large and huge inputs) the outputs are compared point by point:

  pts       points x variants compared (a line missing from one side is reported, not compared)
  ident     how many were bit-identical in every component (value; Dx)
  max ulp   largest float32 ulp distance over all components (value / Dx); -0 vs +0 is
            0 ulp but not identical; NaN vs NaN counts as equal
  max abs   largest absolute difference (value / Dx), finite pairs only
  nonfin    pairs where exactly one side is NaN/Inf, or both Inf of different sign

Inputs are varying and spread widely: x = (u - 0.5) * 20 + v * 3.7, y = (v - 0.5) * 17 - u * 2.3,
z = (u + v - 1) * 6.1 + P[2] * 0.5, t = u * v * 11 - 3, a in [-1.6, 1.7] (for asin/acos), and
large (~2e5) and huge (~4e8) versions of them; they are built from multiplies and adds only
(the "inputs" row checks that both tools agree on them).

  OSL_BIN=... python3 bench/osl_parity/run.py --lobe build/lobe [--res N] [-k FILTER] [--md OUT.md] [--no-O0]
                                [--keep DIR]

-k keeps only the rows whose name contains FILTER (repeatable). After the table, the worst
point of every row that is not bit-identical is listed (variant, u, v, OSL's and Lobe's values),
which is a starting point for a minimal repro. Nothing is asserted: the figures are reported.
"""
import argparse
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile

# ----------------------------------------------------------------------------------------------
# Cases. A row is (name, group, [variant...], note); a variant is
# (label, statements, [(type, expression)...]). Rows of one group share one shader.

PREAMBLE = """\
    float x = (u - 0.5) * 20 + v * 3.7;
    float y = (v - 0.5) * 17 - u * 2.3;
    float z = (u + v - 1) * 6.1 + P[2] * 0.5;
    float t = u * v * 11 - 3;
    float a = (u - 0.5) * 3.2 + v * 0.1;
    float Xb = x * 13711.3 + y * 311.1;
    float Yb = y * 9137.7 - x * 77.7;
    float Zb = z * 17001.1 - 45000;
    float Tb = t * 5311.5;
    float Xh = x * 3.3e7 - v * 1.1e8;
    point p = point(x, y, z);
    point pb = point(Xb, Yb, Zb);
    point ph = point(Xh, y * 2.9e7, z * 4.1e7);
    point pf = point(x, y, P[2] * 1.5);
    point pfb = point(Xb, Yb, P[2] * 1500);
    vector Iv = vector(x, y, z - 0.25);
    vector Nv = vector(y * 0.3 - 1, x * 0.2 + 0.5, 1 - u * 2);
    vector Nref = vector(0.3 - v, 1 - u, 0.5);
    vector Iu = normalize(Iv);
    vector Nu = normalize(Nv);
    color C = color(u * 1.2 - 0.1, v, (u + v) * 0.5);
    color Cw = color(x * 0.1, y * 0.1, z * 0.1);
    matrix M = matrix(x, y * 0.3, 0.5, 1,  0.2, y, z * 0.1, 0,  t * 0.1, 0.3, x * 0.5 + 3, 0,
                      1, 2, 3, 1);
    matrix M2 = matrix(1, v, 0, 0,  u, 2, 0.5, 0,  0, 0.25, 3, 0,  x, y, z, 1);
"""

SIZES = {"float": 1, "int": 1, "color": 3, "vector": 3, "point": 3, "normal": 3, "matrix": 16}

ROWS = []


def row(name, group, variants, note=""):
    ROWS.append((name, group, variants, note))


def V(label, *outs, pre=""):
    """A variant: outputs given as (type, expr) pairs."""
    return (label, pre, list(outs))


# --- 1. Noise ---------------------------------------------------------------------------------
DIMS = {  # dim: {input set: argument list}
    1: {"std": "x", "big": "Xb", "huge": "Xh"},
    2: {"std": "x, y", "big": "Xb, Yb"},
    3: {"std": "p", "big": "pb", "huge": "ph"},
    4: {"std": "p, t", "big": "pb, Tb"},
}
GABOR_DIMS = {1: DIMS[1], 2: DIMS[2], 3: {"std": "pf", "big": "pfb"},
              4: {"std": "pf, t", "big": "pfb, Tb"}}
PERIODS = {1: "3.7", 2: "3.7, 5", 3: "vector(3.7, 5, 6)", 4: "vector(3.7, 5, 6), 2.5"}


def noise_rows(title, call, group, triple="color", dims=DIMS, periodic=False, note=""):
    """call: format with {a} (arguments), e.g. 'noise("perlin", {a})'."""
    for d, sets in dims.items():
        vs = []
        for sname, args in sets.items():
            if periodic:
                args = args + ", " + PERIODS[d]
            vs.append(V("f %s" % sname, ("float", call.format(a=args))))
            vs.append(V("%s %s" % (triple[0], sname), (triple, call.format(a=args))))
        row("%s %dD" % (title, d), group, vs, note)


for kind in ["perlin", "snoise", "uperlin", "noise", "cell", "hash", "simplex", "usimplex"]:
    noise_rows('noise("%s")' % kind, 'noise("%s", {a})' % kind, "n_" + kind)
noise_rows('noise("gabor")', 'noise("gabor", {a})', "n_gabor", dims=GABOR_DIMS)
for legacy in ["noise", "snoise", "cellnoise", "hashnoise"]:
    noise_rows("%s()" % legacy, "%s({a})" % legacy, "l_" + legacy)
noise_rows("pnoise()", "pnoise({a})", "p_pnoise", periodic=True)
noise_rows("psnoise()", "psnoise({a})", "p_psnoise", periodic=True)
noise_rows('pnoise("perlin")', 'pnoise("perlin", {a})', "p_perlin", periodic=True)
noise_rows('pnoise("cell")', 'pnoise("cell", {a})', "p_cell", periodic=True)
noise_rows('pnoise("gabor")', 'pnoise("gabor", {a})', "p_gabor", dims=GABOR_DIMS, periodic=True)
row('gabor options', "n_gabor_opt", [
    V("iso nofilter 3D", ("float", 'noise("gabor", p, "do_filter", 0)')),
    V("aniso 3D", ("float", 'noise("gabor", pf, "anisotropic", 1, "direction", vector(1,2,0.5))')),
    V("hybrid 2D", ("float", 'noise("gabor", x, y, "anisotropic", 2, "bandwidth", 2.5)')),
    V("impulses 3D", ("color", 'noise("gabor", pf, "impulses", 5, "bandwidth", 0.7)')),
    V("aniso periodic 3D", ("vector", 'pnoise("gabor", pf, vector(3,4,5), "anisotropic", 1)')),
])
row('gabor 3D tilted', "n_gabor_tilt", [
    V("f", ("float", 'noise("gabor", p)')), V("c", ("color", 'noise("gabor", p)')),
    V("4D", ("float", 'noise("gabor", p, t)')),
    V("periodic", ("float", 'pnoise("gabor", p, vector(3.7, 5, 6))'))],
    note="known: filtered gabor, footprint tilted out of the xy plane")

# --- 2. Math -----------------------------------------------------------------------------------
UNARY = [  # name, float inputs, triple variant?
    ("sin", ["x", "Xb", "Xh"], True), ("cos", ["x", "Xb", "Xh"], True),
    ("tan", ["x", "Xb", "Xh"], True), ("asin", ["a", "x"], True), ("acos", ["a", "x"], True),
    ("atan", ["x", "Xb", "Xh"], True), ("sinh", ["x", "x * 9.5"], True),
    ("cosh", ["x", "x * 9.5"], True), ("tanh", ["x", "x * 9.5"], True),
    ("exp", ["x", "x * 9.5"], True), ("exp2", ["x", "x * 13.5"], True),
    ("expm1", ["x * 0.001", "x", "x * 9.5"], True),
    ("log", ["x", "Xb", "x * 1e-30"], True), ("log2", ["x", "Xb", "x * 1e-30"], True),
    ("log10", ["x", "Xb", "x * 1e-30"], True), ("logb", ["x", "Xb", "x * 1e-40"], True),
    ("sqrt", ["x", "Xb"], True), ("inversesqrt", ["x", "Xb", "x * 1e-30"], True),
    ("cbrt", ["x", "Xh"], True), ("erf", ["x * 0.4", "x"], False),
    ("erfc", ["x * 0.4", "x"], False),
    ("floor", ["x", "Xh"], True), ("ceil", ["x", "Xh"], True), ("round", ["x", "x * 0.5"], True),
    ("trunc", ["x", "Xh"], True), ("sign", ["x"], True), ("abs", ["x"], True),
    ("radians", ["x", "Xb"], True), ("degrees", ["x", "Xb"], True),
]
for fn, ins, trip in UNARY:
    vs = [V(i, ("float", "%s(%s)" % (fn, i))) for i in ins]
    if trip:
        arg = "vector(a, y, t)" if fn in ("asin", "acos") else "vector(x, y, t)"
        vs.append(V("vector", ("vector", "%s(%s)" % (fn, arg))))
    row(fn, "m_" + fn, vs)

row("log(x, b)", "m_2", [V("b=2.5", ("float", "log(x, 2.5)")), V("b=y", ("float", "log(x, y)")),
                         V("color", ("color", "log(Cw, 3.0)"))])
row("atan2", "m_2", [V("y,x", ("float", "atan2(y, x)")), V("big", ("float", "atan2(Yb, Xb)")),
                     V("0,x", ("float", "atan2(0 * x, x)")),
                     V("vector", ("vector", "atan2(vector(y, x, t), vector(x, t, y))"))])
row("pow", "m_2", [V("x,y", ("float", "pow(x, y * 0.5)")),
                   V("|x|,y", ("float", "pow(abs(x), y * 0.3)")),
                   V("x,int", ("float", "pow(x, floor(y * 0.5))")),
                   V("big", ("float", "pow(abs(Xb), y * 0.1)")),
                   V("color,f", ("color", "pow(Cw, y * 0.3)")),
                   V("vector,v", ("vector", "pow(vector(abs(x), y, 2), vector(t, 0.5, y))"))])
row("fmod", "m_2", [V("x,y", ("float", "fmod(x, y)")), V("x,2.5", ("float", "fmod(x, 2.5)")),
                    V("big", ("float", "fmod(Xb, 3.3)")), V("x,0", ("float", "fmod(x, 0 * y)")),
                    V("vector", ("vector", "fmod(vector(x, y, t), 1.7)"))])
row("mod", "m_2", [V("x,y", ("float", "mod(x, y)")), V("x,2.5", ("float", "mod(x, 2.5)")),
                   V("big", ("float", "mod(Xb, 3.3)")),
                   V("vector", ("vector", "mod(vector(x, y, t), vector(1.7, y, 2))"))])
row("hypot", "m_2", [V("2", ("float", "hypot(x, y)")), V("3", ("float", "hypot(x, y, z)")),
                     V("big", ("float", "hypot(Xb, Yb)")), V("huge", ("float", "hypot(Xh, Xh)"))])
row("min/max", "m_2", [V("min", ("float", "min(x, y)")), V("max", ("float", "max(x, y)")),
                       V("vmin", ("vector", "min(vector(x, y, t), vector(y, x, 0))"))])
row("smoothstep", "m_3", [V("const", ("float", "smoothstep(-3, 4, x)")),
                          V("varying", ("float", "smoothstep(y, y + 5, x)")),
                          V("reversed", ("float", "smoothstep(4, -3, x)")),
                          V("equal", ("float", "smoothstep(1, 1, x)")),
                          V("color", ("color", "smoothstep(color(-3), color(4, 2, 1), Cw * 20)"))])
row("linearstep", "m_3", [V("const", ("float", "linearstep(-3, 4, x)")),
                          V("varying", ("float", "linearstep(y, y + 5, x)")),
                          V("color", ("color", "linearstep(color(-3), color(4, 2, 1), Cw * 20)"))])
row("smooth_linearstep", "m_3", [
    V("const", ("float", "smooth_linearstep(-3, 4, x, 0.5)")),
    V("varying", ("float", "smooth_linearstep(y, y + 5, x, abs(t) * 0.2)")),
    V("eps0", ("float", "smooth_linearstep(-3, 4, x, 0)")),
    V("color", ("color", "smooth_linearstep(color(-3), color(4), Cw * 20, color(0.5))"))])
row("mix", "m_3", [V("f", ("float", "mix(x, y, a)")), V("cf", ("color", "mix(C, Cw, a)")),
                   V("cc", ("color", "mix(C, Cw, C)"))])
row("clamp", "m_3", [V("f", ("float", "clamp(x, -2, 3)")), V("varying", ("float", "clamp(x, y, t)")),
                     V("color", ("color", "clamp(Cw, color(0), color(0.5))"))])
row("step", "m_3", [V("f", ("float", "step(1.5, x)")), V("varying", ("float", "step(y, x)")),
                    V("color", ("color", "step(color(0.1), Cw)"))])
row("hash()", "m_3", [V("1", ("int", "hash(x)")), V("2", ("int", "hash(x, y)")),
                      V("3", ("int", "hash(p)")), V("4", ("int", "hash(p, t)")),
                      V("int", ("int", "hash((int)floor(Xb))"))])
row("inputs", "m_3", [V("xyzta", ("vector", "vector(x, y, z)"), ("float", "t"), ("float", "a")),
                      V("big", ("point", "pb"), ("float", "Tb"), ("float", "Xh")),
                      V("huge", ("point", "ph"))])

# --- 3. Vector / matrix / colour ---------------------------------------------------------------
row("length/distance", "v_1", [
    V("length", ("float", "length(Iv)")), V("length big", ("float", "length(pb)")),
    V("length huge", ("float", "length(ph)")), V("distance", ("float", "distance(p, Nv)")),
    V("distance seg", ("float", "distance(point(0), point(Nv), p)"))])
row("normalize", "v_1", [V("vector", ("vector", "normalize(Iv)")),
                         V("normal", ("normal", "normalize(normal(Nv))")),
                         V("big", ("vector", "normalize(pb)")),
                         V("zero", ("vector", "normalize(Iv * 0)"))])
row("dot/cross", "v_1", [V("dot", ("float", "dot(Iv, Nv)")), V("cross", ("vector", "cross(Iv, Nv)")),
                         V("dot big", ("float", "dot(pb, Nv)"))])
row("faceforward", "v_1", [V("2", ("vector", "faceforward(Nv, Iv)")),
                           V("3", ("vector", "faceforward(Nv, Iv, Nref)"))])
row("reflect/refract", "v_1", [
    V("reflect", ("vector", "reflect(Iv, Nu)")),
    V("refract", ("vector", "refract(Iu, Nu, 0.5 + u * 1.1)")),
    V("refract in", ("vector", "refract(Iu, -Nu, 0.5 + u * 1.1)"))])
row("fresnel", "v_1", [
    V("eta", ("float", "Kr"), ("float", "Kt"), ("vector", "R"), ("vector", "T"),
      pre="float Kr, Kt; vector R, T; fresnel(Iu, normal(Nu), 0.5 + u * 1.1, Kr, Kt, R, T);"),
    V("KrKt", ("float", "Kr"), ("float", "Kt"),
      pre="float Kr, Kt; fresnel(Iu, normal(Nu), 1.5, Kr, Kt);")])
row("rotate", "v_1", [V("axis", ("point", "rotate(p, t, vector(0.3, 1, v))")),
                      V("a,b", ("point", "rotate(p, x * 0.3, point(1, 0, 0), point(u, v, 2))"))])
row("transform", "v_2", [
    V(sp + " " + ty, (ty, 'transform("%s", %s(p))' % (sp, ty)))
    for sp in ("shader", "object", "common") for ty in ("point", "vector", "normal")] + [
    V("object->world", ("point", 'transform("object", "world", p)')),
    V("M point", ("point", "transform(M, p)")), V("M vector", ("vector", "transform(M, Iv)")),
    V("M normal", ("normal", "transform(M, normal(Nv))"))])
row("matrix", "v_2", [V("determinant", ("float", "determinant(M)")),
                      V("transpose", ("matrix", "transpose(M)")),
                      V("inverse", ("matrix", "1 / M")), V("M2/M", ("matrix", "M2 / M")),
                      V("M*M2", ("matrix", "M * M2")),
                      V("matrix(sp,sp)", ("matrix", 'matrix("shader", "common")'))])
row("luminance", "v_3", [V("c", ("float", "luminance(C)")), V("w", ("float", "luminance(Cw)"))])
row("blackbody", "v_3", [V("T", ("color", "blackbody(800 + u * 12000 + v * 777)")),
                         V("low", ("color", "blackbody(x * 100)")),
                         V("high", ("color", "blackbody(Xb + 2e5)"))])
row("wavelength_color", "v_3", [V("vis", ("color", "wavelength_color(350 + u * 450 + v * 9)")),
                                V("out", ("color", "wavelength_color(x * 100)"))])
for sp in ("hsv", "hsl", "YIQ", "XYZ", "xyY"):
    row('color("%s")' % sp, "v_3", [
        V("unit", ("color", 'color("%s", C[0], C[1], C[2])' % sp)),
        V("wide", ("color", 'color("%s", Cw[0], Cw[1], Cw[2])' % sp))])
    row('transformc("%s")' % sp, "v_3", [
        V("to", ("color", 'transformc("%s", C)' % sp)),
        V("to wide", ("color", 'transformc("%s", Cw)' % sp)),
        V("from", ("color", 'transformc("%s", "rgb", C)' % sp))])


# ----------------------------------------------------------------------------------------------
# Shader generation and running.

def variant_code(tag, variant):
    """One block: compute the outputs, print 'tag u v values... dx...'."""
    _, pre, outs = variant
    lines = ["    {"]
    if pre:
        lines.append("        " + pre)
    fmt, args, dfmt, dargs = [], [], [], []
    for i, (ty, expr) in enumerate(outs):
        var = "R%d" % i
        lines.append("        %s %s = %s;" % (ty, var, expr))
        if ty == "int":
            fmt.append("%d")
            args.append(var)
        elif ty == "matrix":
            for r in range(4):
                for c in range(4):
                    fmt.append("%.9g")
                    args.append("%s[%d][%d]" % (var, r, c))
        elif ty == "float":
            fmt.append("%.9g")
            args.append(var)
            dfmt.append("%.9g")
            dargs.append("Dx(%s)" % var)
        else:
            lines.append("        %s D%d = Dx(%s);" % (ty, i, var))
            for c in range(3):
                fmt.append("%.9g")
                args.append("%s[%d]" % (var, c))
                dfmt.append("%.9g")
                dargs.append("D%d[%d]" % (i, c))
    lines.append('        printf("%s %%.9g %%.9g %s\\n", u, v, %s);' % (
        tag, " ".join(fmt + dfmt), ", ".join(args + dargs)))
    lines.append("    }")
    nval = len(fmt)
    return "\n".join(lines), nval, len(dfmt)


def write_shader(work, name, items):
    """items: [(tag, variant)]; returns {tag: (nval, ndx)}."""
    body, shape = [], {}
    for tag, var in items:
        code, nv, nd = variant_code(tag, var)
        body.append(code)
        shape[tag] = (nv, nd)
    with open(os.path.join(work, name + ".osl"), "w") as f:
        f.write("shader %s()\n{\n%s%s\n}\n" % (name, PREAMBLE, "\n".join(body)))
    return shape


def run(cmd, work):
    r = subprocess.run(cmd, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return r.returncode, r.stdout, r.stderr


def parse(out, shape):
    """{tag: {(u, v): (vals, dxs)}}; malformed lines are ignored."""
    res = {}
    for line in out.splitlines():
        f = line.split()
        if len(f) < 3 or f[0] not in shape:
            continue
        nv, nd = shape[f[0]]
        if len(f) != 3 + nv + nd:
            continue
        try:
            nums = [float(s) for s in f[3:]]
        except ValueError:
            continue
        res.setdefault(f[0], {})[(f[1], f[2])] = (nums[:nv], nums[nv:])
    return res


def bits(x):
    return struct.unpack("<I", struct.pack("<f", x))[0]


def ordered(b):
    return -(b & 0x7FFFFFFF) if b & 0x80000000 else b


class Stats:
    def __init__(self):
        self.pts = self.ident = self.dident = self.nonfin = self.missing = 0
        self.ulp = self.dulp = 0
        self.abs = self.dabs = 0.0
        self.worst = None  # (ulp, label, key, osl, lobe, which)

    def compare(self, xs, ys):
        """-> (identical, max ulp, max abs, nonfinite mismatches)"""
        ident, mu, ma, nf = True, 0, 0.0, 0
        for a, b in zip(xs, ys):
            fa, fb = math.isfinite(a), math.isfinite(b)
            if math.isnan(a) and math.isnan(b):
                continue
            if not (fa and fb):
                if a != b:
                    ident = False
                    nf += 1
                continue
            ba, bb = bits(a), bits(b)
            if ba != bb:
                ident = False
                mu = max(mu, abs(ordered(ba) - ordered(bb)))
                ma = max(ma, abs(a - b))
        return ident, mu, ma, nf

    def add(self, label, key, o, l):
        self.pts += 1
        i, u, m, n = self.compare(o[0], l[0])
        di, du, dm, dn = self.compare(o[1], l[1])
        self.ident += i
        self.dident += di
        self.nonfin += (n + dn) > 0
        self.ulp, self.abs = max(self.ulp, u), max(self.abs, m)
        self.dulp, self.dabs = max(self.dulp, du), max(self.dabs, dm)
        score = (n + dn > 0, u, (not i), du, (not di))
        if (not i or not di) and (self.worst is None or score > self.worst[0]):
            self.worst = (score, label, key, o, l)


def fmt_g(x):
    return "0" if x == 0 else "%.3g" % x


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lobe", default="build/lobe")
    ap.add_argument("--res", type=int, default=32)
    ap.add_argument("-k", dest="only", action="append", help="run only rows containing NAME")
    ap.add_argument("--md", help="also write the Markdown table (and worst points) to this file")
    ap.add_argument("--no-O0", dest="o0", action="store_false", help="skip the -O0 runs")
    ap.add_argument("--keep", help="generate the shaders in this directory and keep them")
    a = ap.parse_args()
    osl_bin = os.environ.get("OSL_BIN")
    if not osl_bin:
        sys.exit("OSL_BIN must name OSL's bin directory (testshade, oslc)")
    lobe = os.path.abspath(a.lobe)
    tools = [("osl", [os.path.join(osl_bin, "testshade"), os.path.join(osl_bin, "oslc")]),
             ("lobe", [lobe, "shade"])]
    rows = [r for r in ROWS if not a.only or any(k in r[0] for k in a.only)]
    if not rows:
        sys.exit("no row matches")
    if a.keep:
        work = os.path.abspath(a.keep)
        os.makedirs(work, exist_ok=True)
    else:
        work = tempfile.mkdtemp(prefix="parity_")
    levels = ["-O2"] + (["-O0"] if a.o0 else [])
    groups = {}  # group -> [(tag, variant, row index)]
    for ri, (name, group, variants, _) in enumerate(rows):
        for vi, var in enumerate(variants):
            groups.setdefault(group, []).append(("c%d_%d" % (ri, vi), var, ri))
    res = str(a.res)
    stats = {(ri, lv): Stats() for ri in range(len(rows)) for lv in levels}
    errors = {}
    for gi, (gname, items) in enumerate(groups.items()):
        for lv in levels:
            args = ["-g", res, res, "-t", "1", lv]
            outs, errs, _ = run_group(work, gname, [(t, v) for t, v, _ in items], tools, args)
            for tag, e in errs.items():
                errors.setdefault(tag, e)
            for tag, var, ri in items:
                st = stats[(ri, lv)]
                o, l = outs.get("osl", {}).get(tag, {}), outs.get("lobe", {}).get(tag, {})
                for key in sorted(set(o) | set(l)):
                    if key in o and key in l:
                        st.add(var[0], key, o[key], l[key])
                    else:
                        st.missing += 1
        print("group %d of %d done (%s)" % (gi + 1, len(groups), gname), file=sys.stderr)

    # Table.
    hdr = ["case", "pts"]
    for lv in levels:
        hdr += ["%s ident val;Dx" % lv, "%s max ulp val/Dx" % lv]
        if lv == "-O2":
            hdr += ["-O2 max abs val/Dx"]
    hdr += ["nonfin", "note"]
    lines = ["| " + " | ".join(hdr) + " |", "|" + "|".join("---" for _ in hdr) + "|"]
    details = []
    for ri, (name, group, variants, note) in enumerate(rows):
        tags = ["c%d_%d" % (ri, vi) for vi in range(len(variants))]
        err = [errors[t] for t in tags if t in errors]
        s2 = stats[(ri, "-O2")]
        cells = [name.replace("|", "\\|"), str(s2.pts)]
        nonfin = 0
        notes = [note] if note else []
        for lv in levels:
            s = stats[(ri, lv)]
            cells.append("%d;%d" % (s.ident, s.dident))
            cells.append("%d/%d" % (s.ulp, s.dulp))
            if lv == "-O2":
                cells.append("%s/%s" % (fmt_g(s.abs), fmt_g(s.dabs)))
            nonfin += s.nonfin
            if s.missing:
                notes.append("%s: %d missing" % (lv, s.missing))
            if s.worst:
                _, label, key, o, l = s.worst
                details.append("- %s [%s] %s at u=%s v=%s:\n    osl : %s | Dx %s\n    lobe: %s | Dx %s"
                               % (name, label, lv, key[0], key[1],
                                  " ".join("%.9g" % x for x in o[0]),
                                  " ".join("%.9g" % x for x in o[1]),
                                  " ".join("%.9g" % x for x in l[0]),
                                  " ".join("%.9g" % x for x in l[1])))
        if err:
            notes.append("%d variant(s) failed: %s" % (len(err), err[0][:80]))
        cells += [str(nonfin), "; ".join(notes)]
        lines.append("| " + " | ".join(cells) + " |")
    head = ("Lobe (%s) vs OSL testshade (%s), %dx%d grid, -t 1; pts = points x variants per "
            "level" % (lobe, osl_bin, a.res, a.res))
    text = head + "\n\n" + "\n".join(lines) + "\n"
    if details:
        text += "\nWorst point of each row that is not bit-identical:\n\n" + "\n".join(details) + "\n"
    print(text)
    if a.md:
        with open(a.md, "w") as f:
            f.write(text)
    if not a.keep:
        shutil.rmtree(work, ignore_errors=True)


def run_group(work, gname, items, tools, args):
    """Runs one shader (items: [(tag, variant)]) through every tool: osl: oslc NAME.osl, then
    testshade ARGS NAME; lobe: lobe shade ARGS NAME. If a tool fails, the shader is split into
    one shader per variant. Returns ({tool: parsed output}, {tag: error}, shape)."""
    shape = write_shader(work, gname, items)
    outs, failed = {}, None
    for tool, cmd in tools:
        if tool == "osl":
            rc, _, err = run([cmd[1], "-q", gname + ".osl"], work)
            if rc == 0:
                rc, out, err = run([cmd[0]] + args + [gname], work)
        else:
            rc, out, err = run(cmd + args + [gname], work)
        if rc != 0:
            failed = "%s: %s" % (tool, ((err or out).strip().splitlines() or ["failed"])[-1])
            break
        outs[tool] = parse(out, shape)
    if failed is None:
        return outs, {}, shape
    if len(items) == 1:
        return outs, {items[0][0]: failed}, shape
    outs = {t: {} for t, _ in tools}
    errs = {}
    for i, item in enumerate(items):
        o, e, _ = run_group(work, "%s_%d" % (gname, i), [item], tools, args)
        for t in o:
            outs[t].update(o[t])
        errs.update(e)
    return outs, errs, shape


if __name__ == "__main__":
    main()

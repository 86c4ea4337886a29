#!/usr/bin/env python3
"""Writes the Embree-comparison scene: 64 tessellated spheres on a ground quad.

    python3 bench/embree_compare/gen_spheres.py OUT_DIR [--segments 64]

OUT_DIR gets spheres.obj (8 x 8 UV spheres of radius 0.4 on a 1.0 grid, each 64 segments by 65
bands = 8192 triangles, smooth vertex normals, plus a 2-triangle ground quad: 524,290 triangles),
spheres.mtl (one grey Lambertian material, Kd 0.5), spheres.json (the same scene for
`lobe render`: matte Cs 0.5, a constant environment of radiance 1) and camera.txt (the
camera as Embree pathtracer flags). The OBJ is generated, never committed.
"""
import argparse
import math
import os

EYE = (0.0, 4.2, 8.6)
LOOK_AT = (0.0, 0.2, 0.0)
FOV = 40.0  # vertical, degrees (both renderers)


def write_obj(path, segments):
    bands = segments + 1
    lines = ["# 64 UV spheres on a ground quad (bench/embree_compare/gen_spheres.py)",
             "mtllib spheres.mtl", "usemtl grey"]
    nv = 0
    ntri = 0
    r = 0.4
    for gi in range(8):
        for gj in range(8):
            cx, cz = -3.5 + gi, -3.5 + gj
            cy = r
            base = nv + 1  # OBJ indices are 1-based
            # Poles, then (bands - 1) rings of `segments` vertices.
            verts = [(0.0, 1.0, 0.0)]
            for b in range(1, bands):
                th = math.pi * b / bands
                st, ct = math.sin(th), math.cos(th)
                for s in range(segments):
                    ph = 2 * math.pi * s / segments
                    verts.append((st * math.cos(ph), ct, st * math.sin(ph)))
            verts.append((0.0, -1.0, 0.0))
            for (x, y, z) in verts:
                lines.append("v %.6f %.6f %.6f" % (cx + r * x, cy + r * y, cz + r * z))
            for (x, y, z) in verts:
                lines.append("vn %.6f %.6f %.6f" % (x, y, z))
            nv += len(verts)

            def ring(b, s):  # vertex of ring b (1..bands-1), segment s
                return base + 1 + (b - 1) * segments + (s % segments)

            def f(a, b, c):
                lines.append("f %d//%d %d//%d %d//%d" % (a, a, b, b, c, c))

            top, bottom = base, base + len(verts) - 1
            for s in range(segments):  # counter-clockwise seen from outside
                f(top, ring(1, s + 1), ring(1, s))
                ntri += 1
            for b in range(1, bands - 1):
                for s in range(segments):
                    a0, a1 = ring(b, s), ring(b, s + 1)
                    b0, b1 = ring(b + 1, s), ring(b + 1, s + 1)
                    f(a0, a1, b1)
                    f(a0, b1, b0)
                    ntri += 2
            for s in range(segments):
                f(bottom, ring(bands - 1, s), ring(bands - 1, s + 1))
                ntri += 1
    # Ground quad, facing +Y.
    g = 30.0
    for (x, z) in [(-g, -g), (-g, g), (g, g), (g, -g)]:
        lines.append("v %.1f 0 %.1f" % (x, z))
    lines.append("vn 0 1 0")
    nvn = nv + 1
    q = nv + 1
    lines.append("f %d//%d %d//%d %d//%d" % (q, nvn, q + 1, nvn, q + 2, nvn))
    lines.append("f %d//%d %d//%d %d//%d" % (q, nvn, q + 2, nvn, q + 3, nvn))
    ntri += 2
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    return ntri


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out_dir")
    ap.add_argument("--segments", type=int, default=64)
    a = ap.parse_args()
    os.makedirs(a.out_dir, exist_ok=True)
    ntri = write_obj(os.path.join(a.out_dir, "spheres.obj"), a.segments)
    with open(os.path.join(a.out_dir, "spheres.mtl"), "w") as fh:
        fh.write("newmtl grey\nKd 0.5 0.5 0.5\nKs 0 0 0\nNs 1\nd 1\nillum 1\n")
    v = lambda t: "[%g, %g, %g]" % t
    with open(os.path.join(a.out_dir, "spheres.json"), "w") as fh:
        fh.write("""{
  "camera": {"eye": %s, "look_at": %s, "fov": %g},
  "settings": {"resolution": [512, 512], "spp": 16, "max_depth": 8},
  "materials": {"grey": {"shader": "matte", "params": {"Cs": [0.5, 0.5, 0.5]}}},
  "shapes": [{"type": "mesh", "file": "spheres.obj", "material": "grey"}],
  "environment": {"type": "constant", "color": [1, 1, 1]}
}
""" % (v(EYE), v(LOOK_AT), FOV))
    with open(os.path.join(a.out_dir, "camera.txt"), "w") as fh:
        fh.write("--vp %g %g %g --vi %g %g %g --vu 0 1 0 --fov %g\n" % (EYE + LOOK_AT + (FOV,)))
    print("%s: %d triangles" % (os.path.join(a.out_dir, "spheres.obj"), ntri))


if __name__ == "__main__":
    main()

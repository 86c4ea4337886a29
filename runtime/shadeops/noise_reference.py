#!/usr/bin/env python3
"""Independent reference for Lobe's noise (runtime/shadeops/noise.cpp), transcribed from OSL's
src/include/OSL/oslnoise.h (Bob Jenkins lookup3 inthash, bits_to_01, CellNoise/HashNoise,
perlin() with OSL's grad/fade/lerp/bilerp/trilerp and scale constants), and of OSL's
src/liboslnoise/simplexnoise.cpp (Gustavson's sdnoise1234 with a scramble() hash; transcribed
from memory of OSL's source, so its constants are unverified against a real OSL). Every float
operation is rounded to binary32 (f32) in the same order as OSL's float code, so the values are
the bit patterns OSL prints. Values only (no derivatives: the tests check those by finite
differences).

  python3 runtime/shadeops/noise_reference.py          # prints the values used in the tests
"""
import itertools
import math
import struct

M = 0xFFFFFFFF


def f32(x):
    return struct.unpack('f', struct.pack('f', x))[0]


def fbits(x):
    return struct.unpack('I', struct.pack('f', x))[0]


def rot(x, k):
    return ((x << k) | (x >> (32 - k))) & M


def bjmix(a, b, c):
    a = (a - c) & M; a ^= rot(c, 4); c = (c + b) & M
    b = (b - a) & M; b ^= rot(a, 6); a = (a + c) & M
    c = (c - b) & M; c ^= rot(b, 8); b = (b + a) & M
    a = (a - c) & M; a ^= rot(c, 16); c = (c + b) & M
    b = (b - a) & M; b ^= rot(a, 19); a = (a + c) & M
    c = (c - b) & M; c ^= rot(b, 4); b = (b + a) & M
    return a, b, c


def bjfinal(a, b, c):
    c ^= b; c = (c - rot(b, 14)) & M
    a ^= c; a = (a - rot(c, 11)) & M
    b ^= a; b = (b - rot(a, 25)) & M
    c ^= b; c = (c - rot(b, 16)) & M
    a ^= c; a = (a - rot(c, 4)) & M
    b ^= a; b = (b - rot(a, 14)) & M
    c ^= b; c = (c - rot(b, 24)) & M
    return c


def inthash(*k):
    k = [x & M for x in k]
    n = len(k)
    a = b = c = (0xdeadbeef + (n << 2) + 13) & M
    a = (a + k[0]) & M
    if n > 1: b = (b + k[1]) & M
    if n > 2: c = (c + k[2]) & M
    if n > 3:
        a, b, c = bjmix(a, b, c)
        a = (a + k[3]) & M
        if n > 4: b = (b + k[4]) & M
    return bjfinal(a, b, c)


def bits_to_01(bits):
    # float(bits) * (1.0f / float(UINT_MAX)); float(UINT_MAX) = 2^32, so the factor is 2^-32.
    return f32(f32(float(bits)) * 2.0 ** -32)


def cellnoise(*x):
    return bits_to_01(inthash(*[math.floor(v) for v in x]))


def vcellnoise(*x):
    keys = [math.floor(v) for v in x]
    return [bits_to_01(inthash(*keys, j)) for j in range(3)]


def hashnoise(*x):
    return bits_to_01(inthash(*[fbits(f32(v)) for v in x]))


def fade(t):
    tt = f32(f32(t * t) * t)
    return f32(tt * f32(f32(t * f32(f32(t * 6.0) - 15.0)) + 10.0))


def lerp(a, b, x):
    return f32(f32(a * f32(1.0 - x)) + f32(b * x))


def grad(h, *r):
    n = len(r)
    if n == 1:
        h &= 15
        g = float(1 + (h & 7))
        if h & 8: g = -g
        return f32(g * r[0])
    if n == 2:
        h &= 7
        x, y = r
        u = x if h < 4 else y
        v = f32(2.0 * (y if h < 4 else x))
        return f32((-u if h & 1 else u) + (-v if h & 2 else v))
    if n == 3:
        h &= 15
        x, y, z = r
        u = x if h < 8 else y
        v = y if h < 4 else (x if h in (12, 14) else z)
        return f32((-u if h & 1 else u) + (-v if h & 2 else v))
    h &= 31
    x, y, z, w = r
    u = x if h < 24 else y
    v = y if h < 16 else z
    s = z if h < 8 else w
    return f32(f32((-u if h & 1 else u) + (-v if h & 2 else v)) + (-s if h & 4 else s))


def perlin(*x, period=None, channel=None):
    """Signed noise; channel j of a vector noise uses inthash >> (8 j) (OSL's HashVector)."""
    n = len(x)
    X = [math.floor(v) for v in x]
    f = [f32(x[k] - X[k]) for k in range(n)]
    u = [fade(v) for v in f]
    per = None if period is None else [max(1, math.floor(p)) for p in period]

    def corner(bits):
        c = [X[k] + ((bits >> k) & 1) for k in range(n)]
        if per: c = [c[k] % per[k] for k in range(n)]  # Python % is OSL's imod
        h = inthash(*c)
        if channel is not None: h >>= 8 * channel
        r = [f32(f[k] - 1.0) if (bits >> k) & 1 else f[k] for k in range(n)]
        return grad(h, *r)

    # lerp along x, then y, then z, then w: bilerp/trilerp expand to exactly these lerps.
    v = [corner(i) for i in range(1 << n)]
    for k in range(n):
        v = [lerp(v[2 * i], v[2 * i + 1], u[k]) for i in range(len(v) // 2)]
    scale = [0.2500, 0.6616, 0.9820, 0.8344][n - 1]
    return f32(f32(scale) * v[0])


def unoise(*x, **kw):
    return f32(0.5 * f32(perlin(*x, **kw) + 1.0))


# ---- Simplex noise (OSL's simplexnoise.cpp) ----

def scramble(v0, v1=0, v2=0):
    return bjfinal(v0 & M, v1 & M, (v2 & M) ^ 0xdeadbeef)


GRAD2 = [(-1, -1), (1, 0), (-1, 0), (1, 1), (-1, 1), (0, -1), (0, 1), (1, -1)]
GRAD3 = [(1, 0, 1), (0, 1, 1), (-1, 0, 1), (0, -1, 1), (1, 0, -1), (0, 1, -1), (-1, 0, -1),
         (0, -1, -1), (1, -1, 0), (1, 1, 0), (-1, 1, 0), (-1, -1, 0),
         (1, 0, 1), (-1, 0, 1), (0, 1, -1), (0, -1, -1)]
# The 32 tesseract edges: the zero in position 0, 1, 2, 3 in turn; the other three coordinates'
# signs with the last varying fastest, + before -.
GRAD4 = [tuple(signs[:zero] + (0,) + signs[zero:])
         for zero in range(4) for signs in itertools.product((1, -1), repeat=3)]

# Gustavson's 4-D traversal table, indexed by the six pairwise comparisons of the offsets
# (x>y: 32, x>z: 16, y>z: 8, x>w: 4, y>w: 2, z>w: 1); entry k is the rank of coordinate k.
SIMPLEX4 = [
    (0, 1, 2, 3), (0, 1, 3, 2), (0, 0, 0, 0), (0, 2, 3, 1),
    (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0), (1, 2, 3, 0),
    (0, 2, 1, 3), (0, 0, 0, 0), (0, 3, 1, 2), (0, 3, 2, 1),
    (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0), (1, 3, 2, 0),
    (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0),
    (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0),
    (1, 2, 0, 3), (0, 0, 0, 0), (1, 3, 0, 2), (0, 0, 0, 0),
    (0, 0, 0, 0), (0, 0, 0, 0), (2, 3, 0, 1), (2, 3, 1, 0),
    (1, 0, 2, 3), (1, 0, 3, 2), (0, 0, 0, 0), (0, 0, 0, 0),
    (0, 0, 0, 0), (2, 0, 3, 1), (0, 0, 0, 0), (2, 1, 3, 0),
    (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0),
    (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0),
    (2, 0, 1, 3), (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0),
    (3, 0, 1, 2), (3, 0, 2, 1), (0, 0, 0, 0), (3, 1, 2, 0),
    (2, 1, 0, 3), (0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0),
    (3, 1, 0, 2), (0, 0, 0, 0), (3, 2, 0, 1), (3, 2, 1, 0)]


def grad1(i, seed):
    h = scramble(i, seed) & 15
    g = float(1 + (h & 7))
    return -g if h & 8 else g


def simplex1(x, seed=0):
    i0 = math.floor(x)
    x0 = f32(x - f32(i0))
    x1 = f32(x0 - 1.0)
    n = []
    for i, xc in ((i0, x0), (i0 + 1, x1)):
        t = f32(1.0 - f32(xc * xc))
        t2 = f32(t * t)
        t4 = f32(t2 * t2)
        n.append(f32(f32(t4 * grad1(i, seed)) * xc))
    return f32(f32(0.36) * f32(n[0] + n[1]))


def simplex_corner(c, d, seed):
    """t^4 (g . d) of one corner (0 outside the radius)."""
    n = len(d)
    t = 0.5
    for v in d:
        t = f32(t - f32(v * v))
    if t < 0.0:
        return 0.0
    if n == 2:
        g = GRAD2[scramble(c[0], c[1], seed) & 7]
    elif n == 3:
        g = GRAD3[scramble(c[0], c[1], scramble(c[2], seed)) & 15]
    else:
        g = GRAD4[scramble(c[0], c[1], scramble(c[2], c[3], seed)) & 31]
    dot = f32(g[0] * d[0])
    for k in range(1, n):
        dot = f32(dot + f32(g[k] * d[k]))
    t2 = f32(t * t)
    return f32(f32(t2 * t2) * dot)


def offsets_order(d0):
    """Offsets (0/1 per coordinate) of the middle corners, as OSL picks them."""
    n = len(d0)
    if n == 2:
        return [(1, 0) if d0[0] > d0[1] else (0, 1)]
    if n == 3:
        x0, y0, z0 = d0
        if x0 >= y0:
            if y0 >= z0: return [(1, 0, 0), (1, 1, 0)]
            if x0 >= z0: return [(1, 0, 0), (1, 0, 1)]
            return [(0, 0, 1), (1, 0, 1)]
        if y0 < z0: return [(0, 0, 1), (0, 1, 1)]
        if x0 < z0: return [(0, 1, 0), (0, 1, 1)]
        return [(0, 1, 0), (1, 1, 0)]
    x0, y0, z0, w0 = d0
    c = ((32 if x0 > y0 else 0) | (16 if x0 > z0 else 0) | (8 if y0 > z0 else 0) |
         (4 if x0 > w0 else 0) | (2 if y0 > w0 else 0) | (1 if z0 > w0 else 0))
    rank = SIMPLEX4[c]
    return [tuple(1 if r >= lim else 0 for r in rank) for lim in (3, 2, 1)]


SKEW = {2: (0.366025403, 0.211324865, 64.0), 3: (0.333333333, 0.166666667, 68.0),
        4: (0.309016994, 0.138196601, 54.0)}


def simplex(*x, seed=0):
    """OSL's simplexnoise1..4 (signed); `seed` is the channel of a vector noise."""
    n = len(x)
    if n == 1:
        return simplex1(x[0], seed)
    F, G, scale = (f32(v) for v in SKEW[n])
    s = x[0]
    for v in x[1:]:
        s = f32(s + v)
    s = f32(s * F)
    i = [math.floor(f32(v + s)) for v in x]
    t = f32(f32(float(sum(i))) * G)
    d0 = [f32(x[k] - f32(f32(i[k]) - t)) for k in range(n)]
    corners = [((0,) * n, d0)]
    for m, off in enumerate(offsets_order(d0), 1):
        mg = f32(m * G)
        corners.append((off, [f32(f32(d0[k] - off[k]) + mg) for k in range(n)]))
    lg = f32(n * G)
    corners.append(((1,) * n, [f32(f32(v - 1.0) + lg) for v in d0]))
    total = None
    for off, d in corners:
        v = simplex_corner([i[k] + off[k] for k in range(n)], d, seed)
        total = v if total is None else f32(total + v)
    return f32(scale * total)


def usimplex(*x, **kw):
    return f32(0.5 * f32(simplex(*x, **kw) + 1.0))


if __name__ == '__main__':
    print('inthash(0) = %#010x' % inthash(0))
    print('inthash(1) = %#010x' % inthash(1))
    print('inthash(1,2,3,4,5) = %#010x' % inthash(1, 2, 3, 4, 5))
    print('cellnoise(0.5) = %.9g' % cellnoise(0.5))
    print('cellnoise(2.1,5.9) = %.9g' % cellnoise(2.1, 5.9))
    print('cellnoise(point(2.1,5.9,0.5)) = %.9g' % cellnoise(2.1, 5.9, 0.5))
    print('vcellnoise(0.5) = %.9g %.9g %.9g' % tuple(vcellnoise(0.5)))
    print('hashnoise(1.5) = %.9g' % hashnoise(1.5))
    print('noise(0.5) = %.9g' % unoise(0.5))
    print('snoise(0.3) = %.9g' % perlin(f32(0.3)))
    print('snoise(0.3,1.7) = %.9g' % perlin(f32(0.3), f32(1.7)))
    print('snoise(0.3,1.7,-0.4) = %.9g' % perlin(f32(0.3), f32(1.7), f32(-0.4)))
    print('snoise(0.3,1.7,-0.4,2.6) = %.9g' % perlin(f32(0.3), f32(1.7), f32(-0.4), f32(2.6)))
    print('vsnoise(0.3,1.7,-0.4) = %.9g %.9g %.9g' %
          tuple(perlin(f32(0.3), f32(1.7), f32(-0.4), channel=j) for j in range(3)))
    print('psnoise(0.3, 4) = %.9g' % perlin(f32(0.3), period=[4.0]))
    # Simplex: channel j of a vector noise is seed j (channel 0 is the float noise).
    for name, pt in (('p', (0.3, 1.7, -0.4, 2.6)), ('q', (-3.71, 12.25, 0.83, -5.4))):
        pt = [f32(v) for v in pt]
        for n in range(1, 5):
            print('simplex %s %dD = %s | usimplex %s' % (
                name, n, ' '.join('%.9g' % simplex(*pt[:n], seed=j) for j in range(3)),
                ' '.join('%.9g' % usimplex(*pt[:n], seed=j) for j in range(3))))

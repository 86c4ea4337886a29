// Gabor noise as OSL 1.13 computes it: sparse convolution noise of Lagae, Lefebvre, Drettakis
// and Dutre, "Procedural Noise using Sparse Gabor Convolution" (SIGGRAPH 2009), evaluated the
// way OSL's liboslnoise does (a standalone implementation written for Lobe from the paper and
// from OSL's public interface: oslnoise.h's gabor/gabor3/pgabor/pgabor3 and the keyword
// arguments of noise("gabor", ...)).
//
// Summary of the algorithm (all in float, with derivatives carried as OSL's Dual2 does):
//  * parameters: bandwidth b (clamped to [0.01, 100]), impulses per cell (clamped to [1, 32]),
//    anisotropic 0 (isotropic), 1 (fixed direction) or 2 (hybrid: random in-plane direction of
//    length |direction|), do_filter, direction (default (1, 0, 0)).
//  * kernel frequency F0 = 2; a = F0 (2^b - 1) / (2^b + 1) sqrt(pi / ln 2); the kernel
//    w exp(-pi a^2 |x|^2) cos(2 pi omega.x + phi) is truncated where its envelope falls below
//    0.02: radius r = sqrt(-ln 0.02 / pi) / a. Space is cut into cubic cells of side r; each cell
//    holds Poisson(impulses / (4/3 pi)) impulses, drawn with a per-cell LCG seeded by lookup3
//    of the cell (and the output channel), uniformly placed, each with a random phase and (for
//    the isotropic kind) a uniformly random direction on the sphere.
//  * the 27 cells around the point are summed, times 1/sqrt(lambda) (lambda = impulse density)
//    and a normalising scale 0.5 / (3 sqrt(1 / (4 sqrt 2 a^3))).
//  * do_filter (the default): the kernel is sliced by the tangent plane of the pixel footprint
//    (normal Dx(P) x Dy(P)) and convolved analytically with the footprint's Gaussian (the
//    paper's equations 6 and 10); skipped when |Dx(P) x Dy(P)|^2 < 1e-6.
//  * 1-D and 2-D inputs are the 3-D noise at (x, 0, 0) and (x, y, 0); a 4-D input ignores its
//    fourth coordinate. Periodic forms wrap the cell coordinates used to seed each cell.
//
// Interface (Lobe shadeop style): lobe_gabor(x[nin], dx[nin], dy[nin], nin, period or null,
// options, out[nout], odx[nout], ody[nout], nout) with nin 1..4 and nout 1 or 3.
#include "hashword.h"
#include "shadeop_decls.h"
#include "shadeops.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace gabor_impl {

// ---- OSL's inthash of four words: lookup3 hashword with initval 13 (runtime/mathlib) ----
inline uint32_t inthash4(const uint32_t k[4]) { return lobe::math::hashword(k, 4, 13); }

// int(floor(x)), with x86's result (INT_MIN) for a NaN or out-of-range value.
inline int to_int(float f) {
  return f >= -2147483648.0f && f < 2147483648.0f ? int(f) : std::numeric_limits<int>::min();
}
inline int ifloor_(float x) { return to_int(std::floor(x)); }

// ---- small vectors and OSL-style duals ----
struct V3 {
  float x, y, z;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(V3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline float dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Imath's Vec3 length (with its tiny-vector path) and normalize (divide by the length).
inline float length(V3 v) {
  float l2 = dot(v, v);
  if (l2 < 2.0f * std::numeric_limits<float>::min()) {
    float ax = std::fabs(v.x), ay = std::fabs(v.y), az = std::fabs(v.z), m = ax;
    if (m < ay) m = ay;
    if (m < az) m = az;
    if (m == 0.0f) return 0.0f;
    ax /= m, ay /= m, az /= m;
    return m * std::sqrt(ax * ax + ay * ay + az * az);
  }
  return std::sqrt(l2);
}
inline V3 normalized(V3 v) {
  float l = length(v);
  return l != 0.0f ? V3{v.x / l, v.y / l, v.z / l} : v;
}

struct D1 { // Dual2<float>
  float v, dx, dy;
};
inline D1 operator+(D1 a, D1 b) { return {a.v + b.v, a.dx + b.dx, a.dy + b.dy}; }
inline D1 operator-(D1 a, D1 b) { return {a.v - b.v, a.dx - b.dx, a.dy - b.dy}; }
inline D1 operator-(D1 a) { return {-a.v, -a.dx, -a.dy}; }
inline D1 operator+(D1 a, float b) { return {a.v + b, a.dx, a.dy}; }
inline D1 operator-(float a, D1 b) { return {a - b.v, -b.dx, -b.dy}; }
inline D1 operator*(D1 a, D1 b) {
  return {a.v * b.v, a.v * b.dx + a.dx * b.v, a.v * b.dy + a.dy * b.v};
}
inline D1 operator*(D1 a, float s) { return {a.v * s, a.dx * s, a.dy * s}; }
inline D1 operator*(float s, D1 a) { return a * s; }
inline D1 dexp(D1 a) {
  float f = std::exp(a.v);
  return {f, f * a.dx, f * a.dy};
}
inline D1 dcos(D1 a) {
  float s, c;
  sincosf(a.v, &s, &c);
  float m = -s;
  return {c, m * a.dx, m * a.dy};
}

struct DV { // Dual2<Vec3>: value, d/dx, d/dy
  V3 v, dx, dy;
};
inline D1 comp(const DV& a, int i) {
  const float* v = &a.v.x;
  const float* x = &a.dx.x;
  const float* y = &a.dy.x;
  return {v[i], x[i], y[i]};
}
inline DV operator-(const DV& a, V3 b) { return {a.v - b, a.dx, a.dy}; }
inline DV operator*(const DV& a, float s) { return {a.v * s, a.dx * s, a.dy * s}; }
inline DV operator*(float s, const DV& a) { return a * s; }
// dot of a dual vector with itself / with a constant vector (OSL's dual_vec.h dot).
inline D1 ddot(const DV& a, const DV& b) {
  return comp(a, 0) * comp(b, 0) + comp(a, 1) * comp(b, 1) + comp(a, 2) * comp(b, 2);
}
inline D1 ddot(const DV& a, V3 b) { return comp(a, 0) * b.x + comp(a, 1) * b.y + comp(a, 2) * b.z; }

// ---- 2x2 and 3x3 matrices (Imath semantics: m[row][col], row vectors times matrices) ----
struct M22 {
  float m[2][2];
};
inline float det(const M22& a) { return a.m[0][0] * a.m[1][1] - a.m[1][0] * a.m[0][1]; }
inline M22 operator*(const M22& a, const M22& b) {
  M22 r;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j];
  return r;
}
inline M22 operator+(const M22& a, const M22& b) {
  M22 r;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) r.m[i][j] = a.m[i][j] + b.m[i][j];
  return r;
}
inline M22 operator*(float s, const M22& a) {
  M22 r;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) r.m[i][j] = a.m[i][j] * s;
  return r;
}
inline M22 transposed(const M22& a) { return {{{a.m[0][0], a.m[1][0]}, {a.m[0][1], a.m[1][1]}}}; }
// Imath's Matrix22::inverse(): the adjugate over the determinant, the identity... no: a zero
// matrix when singular (Imath returns Matrix22() = identity only from the throwing variant's
// fallthrough; the non-throwing one returns the identity).
inline M22 inverse(const M22& a) {
  M22 s{{{a.m[1][1], -a.m[0][1]}, {-a.m[1][0], a.m[0][0]}}};
  float r = a.m[0][0] * a.m[1][1] - a.m[1][0] * a.m[0][1];
  if (std::fabs(r) >= 1.0f) {
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) s.m[i][j] /= r;
  } else {
    float mr = std::fabs(r) / std::numeric_limits<float>::min();
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        if (mr > std::fabs(s.m[i][j]))
          s.m[i][j] /= r;
        else
          return M22{{{1, 0}, {0, 1}}};
      }
  }
  return s;
}
// v * M (row vector), 2-D
inline void mult(const M22& M, const float v[2], float out[2]) {
  out[0] = v[0] * M.m[0][0] + v[1] * M.m[1][0];
  out[1] = v[0] * M.m[0][1] + v[1] * M.m[1][1];
}

struct M33 {
  float m[3][3];
};
inline V3 mult(const M33& M, V3 s) { // s * M
  return {s.x * M.m[0][0] + s.y * M.m[1][0] + s.z * M.m[2][0],
          s.x * M.m[0][1] + s.y * M.m[1][1] + s.z * M.m[2][1],
          s.x * M.m[0][2] + s.y * M.m[1][2] + s.z * M.m[2][2]};
}
inline DV mult(const M33& M, const DV& s) { // s * M, with derivatives (per component duals)
  D1 s0 = comp(s, 0), s1 = comp(s, 1), s2 = comp(s, 2);
  D1 r[3];
  for (int c = 0; c < 3; ++c) r[c] = s0 * M.m[0][c] + s1 * M.m[1][c] + s2 * M.m[2][c];
  return {{r[0].v, r[1].v, r[2].v}, {r[0].dx, r[1].dx, r[2].dx}, {r[0].dy, r[1].dy, r[2].dy}};
}

// OIIO's fast_exp2 (OSL is built with OSL_FAST_MATH): a degree-5 polynomial on the fraction,
// the integer part added to the exponent.
inline float fast_exp2(float xval) {
  float x = xval < -126.0f ? -126.0f : xval > 126.0f ? 126.0f : xval;
  int m = int(x);
  x -= float(m);
  x = 1.0f - (1.0f - x);
  float r = 1.33336498402e-3f;
  r = x * r + 9.810352697968e-3f;
  r = x * r + 5.551834031939e-2f;
  r = x * r + 0.2401793301105f;
  r = x * r + 0.693144857883f;
  r = x * r + 1.0f;
  uint32_t bits;
  std::memcpy(&bits, &r, 4);
  bits += uint32_t(m) << 23;
  std::memcpy(&r, &bits, 4);
  return r;
}

// OIIO's fast_sincos (OSL_FAST_MATH), used for the random impulse directions.
inline void fast_sincos(float x, float* sine, float* cosine) {
  float t = x * float(M_1_PI);
  int q = int(t + std::copysign(0.5f, t)); // fast_rint (ties away; ties never occur here)
  float qf = float(q);
  x = qf * (-0.78515625f * 4) + x;
  x = qf * (-0.00024187564849853515625f * 4) + x;
  x = qf * (-3.7747668102383613586e-08f * 4) + x;
  x = qf * (-1.2816720341285448015e-12f * 4) + x;
  x = float(M_PI_2) - (float(M_PI_2) - x);
  float s = x * x;
  if ((q & 1) != 0) x = -x;
  float su = 2.6083159809786593541503e-06f;
  su = su * s + -0.0001981069071916863322258f;
  su = su * s + +0.00833307858556509017944336f;
  su = su * s + -0.166666597127914428710938f;
  su = s * (su * x) + x;
  float cu = -2.71811842367242206819355e-07f;
  cu = cu * s + +2.47990446951007470488548e-05f;
  cu = cu * s + -0.00138888787478208541870117f;
  cu = cu * s + +0.0416666641831398010253906f;
  cu = cu * s + -0.5f;
  cu = cu * s + +1.0f;
  if ((q & 1) != 0) cu = -cu;
  *sine = su < -1.0f ? -1.0f : su > 1.0f ? 1.0f : su;
  *cosine = cu < -1.0f ? -1.0f : cu > 1.0f ? 1.0f : cu;
}

// ---- the noise ----

constexpr float kPi = 3.14159265358979323846f;
constexpr float kTwoPi = 6.28318530717958647692f;
constexpr float kFrequency = 2.0f;
constexpr float kTruncate = 0.02f;

using Options = lobe::shadeops::GaborOptions;

struct Params {
  V3 omega;
  int anisotropic;
  bool do_filter;
  float a, weight;
  V3 N;
  M22 filter;
  M33 local;
  float det_filter;
  float bandwidth;
  bool periodic;
  V3 period;
  float lambda, sqrt_lambda_inv;
  float radius, radius2, radius3, radius_inv;

  explicit Params(const Options& o) {
    omega = {o.direction[0], o.direction[1], o.direction[2]};
    anisotropic = o.anisotropic;
    do_filter = o.do_filter != 0;
    weight = 1.0f;
    bandwidth = std::fmin(std::fmax(o.bandwidth, 0.01f), 100.0f);
    periodic = false;
    float two_to_bw = fast_exp2(bandwidth);
    const float sqrt_pi_over_ln2 = std::sqrt(float(M_PI / M_LN2));
    a = float(kFrequency * ((two_to_bw - 1.0) / (two_to_bw + 1.0)) * sqrt_pi_over_ln2);
    radius = std::sqrt(-std::log(kTruncate) / kPi) / a;
    radius2 = radius * radius;
    radius3 = radius2 * radius;
    radius_inv = 1.0f / radius;
    float impulses = std::fmin(std::fmax(o.impulses, 1.0f), 32.0f);
    lambda = impulses / (float(1.33333 * M_PI) * radius3);
    sqrt_lambda_inv = 1.0f / std::sqrt(lambda);
  }
};

// Borosh-Niederreiter LCG seeded by lookup3 of the cell (and the channel).
struct Rng {
  uint32_t seed;
  Rng(V3 p, int s) {
    uint32_t k[4] = {uint32_t(ifloor_(p.x)), uint32_t(ifloor_(p.y)), uint32_t(ifloor_(p.z)),
                     uint32_t(s)};
    seed = inthash4(k);
    if (!seed) seed = 1;
  }
  float operator()() {
    return float(seed *= 3039177861u) / float(std::numeric_limits<unsigned>::max());
  }
  int poisson(float mean) {
    float g = std::exp(-mean);
    int em = 0;
    float t = (*this)();
    while (t > g) {
      ++em;
      t *= (*this)();
    }
    return em;
  }
};

inline float wrap(float s, float period) {
  period = std::floor(period);
  if (period < 1.0f) period = 1.0f;
  return s - period * std::floor(s / period);
}

// The Gabor kernel w exp(-pi a^2 |x|^2) cos(2 pi omega.x + phi), 3-D and 2-D.
inline D1 kernel3(D1 w, V3 omega, D1 phi, float a, const DV& x) {
  D1 g = dexp((float(-kPi) * (a * a)) * ddot(x, x));
  D1 h = dcos(kTwoPi * ddot(x, omega) + phi);
  return w * g * h;
}
inline D1 kernel3(float w, V3 omega, float phi, float a, const DV& x) {
  D1 g = dexp((float(-kPi) * (a * a)) * ddot(x, x));
  D1 h = dcos(kTwoPi * ddot(x, omega) + phi);
  return w * g * h;
}
inline D1 kernel2(D1 w, const float omega[2], D1 phi, float a, D1 x0, D1 x1) {
  D1 g = dexp((float(-kPi) * (a * a)) * (x0 * x0 + x1 * x1));
  D1 h = dcos(kTwoPi * (x0 * omega[0] + x1 * omega[1]) + phi);
  return w * g * h;
}

void sample(Params& gp, Rng& rng, V3& omega, float& phi) {
  if (gp.anisotropic == 1) {
    omega = gp.omega;
  } else if (gp.anisotropic == 0) {
    float omega_t = kTwoPi * rng();
    float x = rng();
    float cos_p = -1.0f * (1.0f - x) + 1.0f * x;
    float sin_p = std::sqrt(std::fmax(0.0f, 1.0f - cos_p * cos_p));
    float st, ct;
    fast_sincos(omega_t, &st, &ct);
    omega = normalized(V3{ct * sin_p, st * sin_p, cos_p});
  } else {
    float omega_r = length(gp.omega);
    float omega_t = kTwoPi * rng();
    float st, ct;
    fast_sincos(omega_t, &st, &ct);
    omega = V3{ct, st, 0.0f} * omega_r;
  }
  phi = kTwoPi * rng();
}

// Paper eq. 6: slice the 3-D kernel by the plane at signed distance d.
inline void slice(D1 d, float w, float a, V3 omega, float phi, D1& w_s, float omega_s[2],
                  D1& phi_s) {
  w_s = w * dexp((float(-kPi) * (a * a)) * (d * d));
  omega_s[0] = omega.x;
  omega_s[1] = omega.y;
  phi_s = phi - kTwoPi * d * omega.z;
}

// Paper eq. 10: convolve a 2-D kernel with the footprint Gaussian (covariance `filter`).
inline void filter2(const M22& filter, D1 w, float a, const float omega[2], D1 phi, D1& w_f,
                    float& a_f, float omega_f[2], D1& phi_f) {
  M22 Sigma_f = filter;
  D1 c_G = w;
  float mu_G[2] = {omega[0], omega[1]};
  M22 Sigma_G = (a * a / kTwoPi) * M22{{{1, 0}, {0, 1}}};
  float c_F = 1.0f / (kTwoPi * std::sqrt(det(Sigma_f)));
  M22 Sigma_F = float(1.0 / (4.0 * M_PI * M_PI)) * inverse(Sigma_f);
  M22 Sigma_G_Sigma_F = Sigma_G + Sigma_F;
  float m[2];
  mult(inverse(Sigma_G_Sigma_F), mu_G, m);
  D1 c_GF = c_F * c_G * (1.0f / (kTwoPi * std::sqrt(det(Sigma_G_Sigma_F)))) *
            std::exp(-0.5f * (m[0] * mu_G[0] + m[1] * mu_G[1]));
  M22 Sigma_G_i = inverse(Sigma_G);
  M22 Sigma_GF = inverse(inverse(Sigma_F) + Sigma_G_i);
  float mu_GF[2];
  M22 Sigma_GF_Gi = Sigma_GF * Sigma_G_i;
  mult(Sigma_GF_Gi, mu_G, mu_GF);
  w_f = c_GF;
  a_f =
      std::sqrt(float(6.28318530717958647692 * double(std::sqrt(det(Sigma_GF))))); // 2 pi in double
  omega_f[0] = mu_GF[0];
  omega_f[1] = mu_GF[1];
  phi_f = phi;
}

D1 cell(Params& gp, V3 c_i, const DV& x_c_i, int seed) {
  V3 cs = c_i;
  if (gp.periodic)
    cs = {wrap(c_i.x, gp.period.x), wrap(c_i.y, gp.period.y), wrap(c_i.z, gp.period.z)};
  Rng rng(cs, seed);
  int n = rng.poisson(gp.lambda * gp.radius3);
  D1 sum{0, 0, 0};
  for (int i = 0; i < n; ++i) {
    float z_rng = rng(), y_rng = rng(), x_rng = rng();
    V3 x_i_c{x_rng, y_rng, z_rng};
    DV x_k_i = gp.radius * (x_c_i - x_i_c);
    float phi_i;
    V3 omega_i;
    sample(gp, rng, omega_i, phi_i);
    if (dot(x_k_i.v, x_k_i.v) < gp.radius2) {
      if (!gp.do_filter) {
        sum = sum + kernel3(gp.weight, omega_i, phi_i, gp.a, x_k_i);
      } else {
        V3 omega_i_t = mult(gp.local, omega_i);
        D1 d_i = -ddot(x_k_i, gp.N);
        D1 w_s, phi_s;
        float omega_s[2];
        slice(d_i, gp.weight, gp.a, omega_i_t, phi_i, w_s, omega_s, phi_s);
        D1 w_f, phi_f;
        float a_f, omega_f[2];
        filter2(gp.filter, w_s, gp.a, omega_s, phi_s, w_f, a_f, omega_f, phi_f);
        DV xt = mult(gp.local, x_k_i);
        D1 gk = kernel2(w_f, omega_f, phi_f, a_f, comp(xt, 0), comp(xt, 1));
        if (!std::isfinite(gk.v)) gk = kernel3(gp.weight, omega_i, phi_i, gp.a, x_k_i);
        sum = sum + gk;
      }
    }
  }
  return sum;
}

D1 grid(Params& gp, const DV& x_g, int seed) {
  // The cell: floor in float (no int conversion, so huge coordinates still find their cell).
  V3 fl{std::floor(x_g.v.x), std::floor(x_g.v.y), std::floor(x_g.v.z)};
  DV x_c = x_g - fl;
  D1 sum{0, 0, 0};
  for (int k = -1; k <= 1; ++k)
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i) {
        V3 c{float(i), float(j), float(k)};
        sum = sum + cell(gp, fl + c, x_c - c, seed);
      }
  return sum * gp.sqrt_lambda_inv;
}

void make_orthonormals(V3& v, V3& a, V3& b) {
  v = normalized(v);
  if (std::fabs(v.x) < 0.9f)
    a = V3{0.0f, v.z, -v.y};
  else
    a = V3{-v.z, 0.0f, v.x};
  a = normalized(a);
  b = cross(v, a);
}

// The pixel-footprint filter. Determined against OSL's output: the footprint covariance is a
// quarter of the Gram matrix of the xy parts of Dx(P) and Dy(P) ([[dx.dx, dx.dy], [dx.dy,
// dy.dy]] / 4), the impulses' directions and offsets are used in texture xy as they are (no
// rotation into a tangent frame) and the slicing distance is along z. That is exact whenever
// the footprint lies in the xy plane (always for the 2-D form noise("gabor", x, y), and for a
// point input whose derivatives have no z part) and when the filter is off. A footprint tilted
// out of that plane is not OSL's: the z parts of the derivatives are ignored (OSL 1.13.12 prints
// 0.0325879 for noise("gabor", point(u, v, u)) at the first point of `testshade -g 2 2`, Lobe
// -0.0102787, its value for point(u, v, 0)); OSL's tangent-frame handling is not reproduced.
void setup_filter(const DV& P, Params& gp) {
  V3 n = cross(P.dx, P.dy);
  if (dot(n, n) < 1.0e-6f) {
    gp.do_filter = false;
    return;
  }
  V3 t, b;
  make_orthonormals(n, t, b);
  gp.local = M33{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  gp.N = V3{0, 0, 1};
  M22 J{{{P.dx.x, P.dy.x}, {P.dx.y, P.dy.y}}};
  gp.filter = 0.25f * (transposed(J) * J);
  gp.det_filter = det(gp.filter);
  if (std::fabs(gp.det_filter) < 1.0e-18f) gp.do_filter = false;
}

} // namespace gabor_impl

extern "C" void lobe_gabor(const float* x, const float* dx, const float* dy, int nin,
                           const float* period, const lobe::shadeops::GaborOptions* opt, float* out,
                           float* odx, float* ody, int nout) {
  using namespace gabor_impl;
  Options o;
  if (opt) o = *opt;
  Params gp(o);
  DV P{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  float* pv = &P.v.x;
  float* px = &P.dx.x;
  float* py = &P.dy.x;
  for (int k = 0; k < nin && k < 3; ++k) {
    pv[k] = x[k];
    px[k] = dx ? dx[k] : 0.0f;
    py[k] = dy ? dy[k] : 0.0f;
  }
  if (period) {
    gp.periodic = true;
    gp.period = {period[0], nin > 1 ? period[1] : 0.0f, nin > 2 ? period[2] : 0.0f};
  }
  if (gp.do_filter) setup_filter(P, gp);
  DV xg = P * gp.radius_inv;
  float gabor_variance = 1.0f / (4.0f * std::sqrt(2.0f) * (gp.a * gp.a * gp.a));
  float scale = 1.0f / (3.0f * std::sqrt(gabor_variance));
  scale *= 0.5f;
  for (int j = 0; j < nout; ++j) {
    D1 r = grid(gp, xg, nout == 1 ? 0 : j) * scale;
    out[j] = r.v;
    if (odx) odx[j] = r.dx;
    if (ody) ody[j] = r.dy;
  }
}

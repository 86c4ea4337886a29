// The noise family: gradient ("perlin", signed in [-1,1]; "uperlin"/noise(), in [0,1]),
// "cell" (constant per integer cell, [0,1)), "hash" (per exact input, [0,1)) and the periodic
// variants, for 1 to 4 input dimensions and 1 or 3 output channels. Lobe's lattice hash and
// gradient set are its own (values differ from OSL's; the properties match: zero signed noise
// at lattice points, C2-continuous quintic interpolation, range, periodicity). Gradient noise
// also returns its analytic derivative so that Dx(noise(P)) follows the chain rule.
#include "shadeops.h"

#include "lobe/context.h"
#include "lobe/shading.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace {

uint32_t mix32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

uint32_t hash_ints(const int32_t* c, int n, uint32_t seed) {
  uint32_t h = mix32(seed * 0x9e3779b9u + 0x632be5abu);
  for (int k = 0; k < n; ++k) h = mix32(h ^ (uint32_t(c[k]) + 0x9e3779b9u * uint32_t(k + 1)));
  return h;
}

float unit_float(uint32_t h) { return float(h >> 8) * (1.0f / 16777216.0f); }

double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
double dfade(double t) { return 30 * t * t * (t * (t - 2) + 1); }

int wrap(int v, int period) {
  int m = v % period;
  return m < 0 ? m + period : m;
}

// Signed gradient noise at x (n dims), derivative in grad[0..n).
float perlin(const float* x, int n, const float* period, uint32_t seed, float* grad) {
  int32_t base[4];
  double f[4], u[4], du[4], g[4] = {0, 0, 0, 0}, value = 0;
  for (int k = 0; k < n; ++k) {
    double fl = std::floor(double(x[k]));
    base[k] = int32_t(fl);
    f[k] = double(x[k]) - fl;
    u[k] = fade(f[k]);
    du[k] = dfade(f[k]);
  }
  for (int corner = 0; corner < (1 << n); ++corner) {
    int32_t lat[4];
    double w = 1, d[4], dot = 0, grad_h[4];
    for (int k = 0; k < n; ++k) {
      int bit = (corner >> k) & 1;
      lat[k] = base[k] + bit;
      if (period) lat[k] = wrap(lat[k], std::max(1, int(std::lround(period[k]))));
      d[k] = f[k] - bit;
      w *= bit ? u[k] : 1 - u[k];
    }
    uint32_t h = hash_ints(lat, n, seed);
    for (int k = 0; k < n; ++k) {
      grad_h[k] = double((h >> (8 * k)) & 0xffu) / 127.5 - 1.0;
      dot += grad_h[k] * d[k];
    }
    value += w * dot;
    for (int j = 0; j < n; ++j) {
      double dw = 1; // d(w)/d(x_j)
      for (int k = 0; k < n; ++k) {
        int bit = (corner >> k) & 1;
        dw *= (k == j) ? (bit ? du[k] : -du[k]) : (bit ? u[k] : 1 - u[k]);
      }
      g[j] += w * grad_h[j] + dot * dw;
    }
  }
  double scale = n == 1 ? 2.0 : 1.0;
  value *= scale;
  bool clamped = value > 1 || value < -1;
  for (int k = 0; k < n; ++k) grad[k] = clamped ? 0.0f : float(g[k] * scale);
  return float(value > 1 ? 1 : (value < -1 ? -1 : value));
}

} // namespace

extern "C" {

// out[nout] = noise of `kind` at x[nin] (optionally periodic); grad, if non-null, receives
// d out[j] / d x[k] at grad[j * nin + k].
void lobe_noise(int kind, const float* x, int nin, const float* period, float* out, int nout,
                float* grad) {
  for (int j = 0; j < nout; ++j) {
    float gj[4] = {0, 0, 0, 0};
    uint32_t seed = uint32_t(j) * 0x51633e2du + 1u;
    float v = 0;
    if (kind == lobe::shadeops::kPerlin || kind == lobe::shadeops::kUPerlin) {
      v = perlin(x, nin, period, seed, gj);
      if (kind == lobe::shadeops::kUPerlin) {
        v = 0.5f * v + 0.5f;
        for (float& g : gj) g *= 0.5f;
      }
    } else {
      int32_t c[4];
      for (int k = 0; k < nin; ++k) {
        if (kind == lobe::shadeops::kCell) {
          c[k] = int32_t(std::floor(x[k]));
          if (period) c[k] = wrap(c[k], std::max(1, int(std::lround(period[k]))));
        } else {
          std::memcpy(&c[k], &x[k], 4);
        }
      }
      v = unit_float(hash_ints(c, nin, seed));
    }
    out[j] = v;
    if (grad)
      for (int k = 0; k < nin; ++k) grad[j * nin + k] = gj[k];
  }
}

// noise(name, ...) with a name known only at run time (OSL's genericnoise): dispatches on the
// name like the constant case in codegen ("gabor" is the gradient noise). An unknown name is a
// run-time error naming the source location; the result (and its gradient) is 0.
void lobe_noise_named(lobe::ShaderGlobals* sg, const char* name, const float* x, int nin,
                      const float* period, float* out, int nout, float* grad, const char* file,
                      int line) {
  std::string_view n = name ? name : "";
  int kind = n == "gabor" ? lobe::shadeops::kUPerlin : lobe::shadeops::noise_kind_from_name(n);
  if (kind >= 0) return lobe_noise(kind, x, nin, period, out, nout, grad);
  for (int j = 0; j < nout; ++j) out[j] = 0;
  if (grad)
    for (int k = 0; k < nout * nin; ++k) grad[k] = 0;
  if (sg && sg->context) {
    sg->context->errors++;
    sg->context->message("ERROR: Unknown noise type \"" + std::string(n) + "\": " + file + ":" +
                         std::to_string(line) + "\n");
  }
}

} // extern "C"

namespace lobe::shadeops {
int noise_kind_from_name(std::string_view name) {
  if (name == "perlin" || name == "snoise" || name == "simplex") return kPerlin;
  if (name == "uperlin" || name == "noise" || name == "usimplex") return kUPerlin;
  if (name == "cell" || name == "cellnoise") return kCell;
  if (name == "hash" || name == "hashnoise") return kHash;
  return -1;
}
} // namespace lobe::shadeops

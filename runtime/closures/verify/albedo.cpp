// Monte Carlo and adaptive-cubature albedo estimators.
#include "albedo.h"

#include "rng.h"

#include <array>
#include <cmath>
#include <queue>
#include <vector>

namespace lobe::verify {
namespace {

// 3-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr std::array<double, 3> kGlX = {-0.7745966692414834, 0.0, 0.7745966692414834};
constexpr std::array<double, 3> kGlW = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

struct Cell {
  double phi0, phi1, c0, c1;
  Color3d fine; // estimate from the four quadrants
  double error; // |coarse - fine|, max over channels
  bool operator<(const Cell& o) const { return error < o.error; }
};

class Integrator {
public:
  Integrator(const LobeView& lobe, const Vec3& wo, Transport mode)
      : lobe_(lobe), wo_(wo), mode_(mode) {
    double l = std::sqrt(double(wo.x) * wo.x + double(wo.y) * wo.y + double(wo.z) * wo.z);
    n_[0] = wo.x / l, n_[1] = wo.y / l, n_[2] = wo.z / l;
    // Tangents of wo's frame (Duff et al.), in double.
    double sign = std::copysign(1.0, n_[2]), a = -1.0 / (sign + n_[2]), b = n_[0] * n_[1] * a;
    t_[0] = 1.0 + sign * n_[0] * n_[0] * a, t_[1] = sign * b, t_[2] = -sign * n_[0];
    b_[0] = b, b_[1] = sign + n_[1] * n_[1] * a, b_[2] = -n_[1];
  }

  // 3x3 Gauss-Legendre product rule of eval().value over [phi0,phi1] x [c0,c1] of the
  // half-vector domain: m = (sin cos phi, sin sin phi, c) in wo's frame, c = wo.m in [0, 1],
  // wi = 2 c m - wo, dwi = 4 c dm = 4 c dphi dc.
  Color3d gauss(double phi0, double phi1, double c0, double c1) {
    Color3d sum;
    double hp = 0.5 * (phi1 - phi0), mp = 0.5 * (phi1 + phi0);
    double hc = 0.5 * (c1 - c0), mc = 0.5 * (c1 + c0);
    for (int j = 0; j < 3; ++j) {
      double c = mc + hc * kGlX[j];
      double s = std::sqrt(std::fmax(0.0, 1.0 - c * c));
      for (int i = 0; i < 3; ++i) {
        double phi = mp + hp * kGlX[i];
        double mx = s * std::cos(phi), my = s * std::sin(phi), w[3];
        for (int k = 0; k < 3; ++k) {
          double m = mx * t_[k] + my * b_[k] + c * n_[k];
          w[k] = 2.0 * c * m - n_[k];
        }
        Vec3 wi{static_cast<float>(w[0]), static_cast<float>(w[1]), static_cast<float>(w[2])};
        Vec3 v = lobe_.eval(wo_, wi, mode_).value;
        ++evals;
        if (finite_nonneg(v)) sum.add(v, kGlW[i] * kGlW[j] * 4.0 * c);
      }
    }
    return sum * (hp * hc);
  }

  Cell make_cell(double phi0, double phi1, double c0, double c1) {
    Color3d coarse = gauss(phi0, phi1, c0, c1);
    double pm = 0.5 * (phi0 + phi1), cm = 0.5 * (c0 + c1);
    Color3d fine = gauss(phi0, pm, c0, cm) + gauss(pm, phi1, c0, cm) + gauss(phi0, pm, cm, c1) +
                   gauss(pm, phi1, cm, c1);
    Color3d d = fine - coarse;
    double err = std::fmax(std::fabs(d.r), std::fmax(std::fabs(d.g), std::fabs(d.b)));
    return {phi0, phi1, c0, c1, fine, err};
  }

  uint64_t evals = 0;

private:
  const LobeView& lobe_;
  Vec3 wo_;
  Transport mode_;
  double n_[3], t_[3], b_[3];
};

} // namespace

AlbedoEstimate albedo_mc(const LobeView& lobe, const Vec3& wo, uint64_t samples, uint64_t seed,
                         Transport mode) {
  AlbedoEstimate r;
  r.samples = samples;
  Pcg32 rng(seed);
  Color3d sum, sum2;
  for (uint64_t k = 0; k < samples; ++k) {
    auto s = lobe.sample(wo, rng.next_vec3(), mode);
    if (!s) continue;
    if (!finite_nonneg(s->weight)) {
      ++r.nonfinite;
      continue;
    }
    sum.add(s->weight);
    sum2 += Color3d{double(s->weight.x) * s->weight.x, double(s->weight.y) * s->weight.y,
                    double(s->weight.z) * s->weight.z};
  }
  double n = static_cast<double>(samples);
  r.mean = sum * (1.0 / n);
  auto se = [&](double s1, double s2) {
    double var = std::fmax(0.0, s2 / n - (s1 / n) * (s1 / n));
    return std::sqrt(var / n);
  };
  r.std_error = {se(sum.r, sum2.r), se(sum.g, sum2.g), se(sum.b, sum2.b)};
  return r;
}

QuadratureResult albedo_quadrature(const LobeView& lobe, const Vec3& wo, Transport mode,
                                   const QuadratureOptions& opt) {
  Integrator in(lobe, wo, mode);
  std::priority_queue<Cell> heap;
  Color3d total;
  double err = 0;
  int ncos = 2 * opt.base_cos;
  double dphi = 2.0 * M_PI / opt.base_phi, dc = 1.0 / ncos;
  for (int j = 0; j < ncos; ++j)
    for (int i = 0; i < opt.base_phi; ++i) {
      Cell c = in.make_cell(i * dphi, (i + 1) * dphi, j * dc, (j + 1) * dc);
      total += c.fine;
      err += c.error;
      heap.push(c);
    }
  while (!heap.empty() && in.evals < opt.max_evals &&
         err > std::fmax(opt.abs_tol, opt.rel_tol * total.max())) {
    Cell c = heap.top();
    heap.pop();
    total = total - c.fine;
    err -= c.error;
    double pm = 0.5 * (c.phi0 + c.phi1), cm = 0.5 * (c.c0 + c.c1);
    for (Cell q : {in.make_cell(c.phi0, pm, c.c0, cm), in.make_cell(pm, c.phi1, c.c0, cm),
                   in.make_cell(c.phi0, pm, cm, c.c1), in.make_cell(pm, c.phi1, cm, c.c1)}) {
      total += q.fine;
      err += q.error;
      heap.push(q);
    }
  }
  return {total, std::fmax(err, 0.0), in.evals};
}

} // namespace lobe::verify

// Chi-square goodness-of-fit test: binning, adaptive cell integration, pooling, p-value.
#include "chi2.h"

#include "rng.h"
#include "stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace lobe::verify {
namespace {

struct Grid {
  int phi_res, cos_res;
  double cos_min, cos_max;
  int index(const Vec3& w) const {
    double c = std::clamp(static_cast<double>(w.z), -1.0, 1.0);
    if (c < cos_min || c > cos_max) return -1;
    double phi = std::atan2(static_cast<double>(w.y), static_cast<double>(w.x));
    if (phi < 0) phi += 2.0 * M_PI;
    int ip = std::min(phi_res - 1, static_cast<int>(phi / (2.0 * M_PI) * phi_res));
    int ic = std::min(cos_res - 1, static_cast<int>((c - cos_min) / (cos_max - cos_min) * cos_res));
    return ic * phi_res + ip;
  }
};

// The cos range follows the lobe's flags and the side wo is on: reflection stays on wo's side,
// transmission crosses; both: the whole sphere.
Grid make_grid(uint32_t flags, const Vec3& wo, const Chi2Options& opt) {
  bool refl = flags & kLobeReflect, trans = flags & kLobeTransmit;
  if (!refl && !trans) refl = trans = true;
  bool upper = refl, lower = trans;
  if (wo.z < 0) std::swap(upper, lower);
  Grid g{opt.phi_res, 0, lower ? -1.0 : 0.0, upper ? 1.0 : 0.0};
  g.cos_res = opt.cos_res * ((refl && trans) ? 2 : 1);
  return g;
}

// Adaptive integral of pdf() over one cell: doubles the sub-grid while the estimate moves by
// more than 1e-3 relative (peaky lobes need the finer grids, smooth ones stop at min_sub). A
// cell that received samples is never accepted as empty on a coarse grid: a narrow peak (a
// sharp lobe at grazing incidence) can fall between all the coarse sub-grid points.
double integrate_cell_adaptive(const LobeView& lobe, const Vec3& wo, double phi0, double phi1,
                               double c0, double c1, bool has_samples, const Chi2Options& opt) {
  int n = std::max(1, opt.min_sub);
  double prev = integrate_pdf_cell(lobe, wo, phi0, phi1, c0, c1, n);
  while (n < opt.max_sub) {
    n *= 2;
    double cur = integrate_pdf_cell(lobe, wo, phi0, phi1, c0, c1, n);
    bool converged =
        (cur == 0 && prev == 0) ? !has_samples : std::fabs(cur - prev) <= 1e-3 * std::fabs(cur);
    prev = cur;
    if (converged) break;
  }
  return prev;
}

struct Pooled {
  double stat = 0;
  int cells = 0;
};

// Chi-square statistic with cells expecting fewer than min_expected samples pooled together;
// a pool that stays too small joins the smallest regular cell.
Pooled pooled_statistic(const std::vector<double>& obs, const std::vector<double>& exp,
                        double min_expected) {
  std::vector<size_t> order(obs.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return exp[a] < exp[b]; });
  double pool_obs = 0, pool_exp = 0;
  Pooled out;
  size_t first_regular = order.size();
  for (size_t k = 0; k < order.size(); ++k) {
    size_t i = order[k];
    if (exp[i] < min_expected) {
      pool_obs += obs[i];
      pool_exp += exp[i];
      continue;
    }
    if (first_regular == order.size() && pool_exp < min_expected && pool_exp > 0) {
      pool_obs += obs[i]; // the too-small pool joins the smallest regular cell
      pool_exp += exp[i];
      first_regular = k;
      continue;
    }
    double d = obs[i] - exp[i];
    out.stat += d * d / exp[i];
    ++out.cells;
  }
  if (pool_exp > 0) {
    double d = pool_obs - pool_exp;
    out.stat += d * d / pool_exp;
    ++out.cells;
  }
  return out;
}

} // namespace

double integrate_pdf_cell(const LobeView& lobe, const Vec3& wo, double phi0, double phi1, double c0,
                          double c1, int n) {
  double dphi = (phi1 - phi0) / n, dc = (c1 - c0) / n, sum = 0;
  for (int j = 0; j < n; ++j) {
    double c = c0 + (j + 0.5) * dc;
    double s = std::sqrt(std::fmax(0.0, 1.0 - c * c));
    for (int i = 0; i < n; ++i) {
      double phi = phi0 + (i + 0.5) * dphi;
      Vec3 wi{static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
              static_cast<float>(c)};
      float p = lobe.pdf(wo, wi);
      if (std::isfinite(p) && p > 0) sum += p;
    }
  }
  return sum * dphi * dc;
}

Chi2Result chi2_test(const LobeView& lobe, const Vec3& wo, const Chi2Options& opt) {
  Chi2Result r;
  Grid g = make_grid(lobe.flags(), wo, opt);
  r.cos_cells = g.cos_res;
  r.cos_min = g.cos_min;
  r.cos_max = g.cos_max;
  size_t ncell = static_cast<size_t>(g.phi_res) * g.cos_res;
  r.observed.assign(ncell, 0.0);
  r.expected.assign(ncell, 0.0);

  Pcg32 rng(opt.seed);
  for (uint64_t k = 0; k < opt.samples; ++k) {
    auto s = lobe.sample(wo, rng.next_vec3(), opt.mode);
    if (!s) continue;
    ++r.valid;
    if (s->flags & kLobeSpecular) {
      ++r.specular;
      continue;
    }
    int idx = g.index(s->wi);
    if (idx < 0)
      ++r.outside;
    else
      r.observed[idx] += 1.0;
  }

  double dphi = 2.0 * M_PI / g.phi_res, dc = (g.cos_max - g.cos_min) / g.cos_res;
  for (int ic = 0; ic < g.cos_res; ++ic)
    for (int ip = 0; ip < g.phi_res; ++ip) {
      double c0 = g.cos_min + ic * dc, phi0 = ip * dphi;
      size_t idx = static_cast<size_t>(ic) * g.phi_res + ip;
      double integral = integrate_cell_adaptive(lobe, wo, phi0, phi0 + dphi, c0, c0 + dc,
                                                r.observed[idx] > 0, opt);
      r.pdf_integral += integral;
      r.expected[idx] = integral * opt.samples;
    }

  r.threshold = sidak_alpha(opt.significance, opt.n_tests);
  if (r.outside > 0) {
    r.message = std::to_string(r.outside) + " samples in a hemisphere the lobe flags exclude";
    return r;
  }
  for (size_t i = 0; i < ncell; ++i)
    if (r.expected[i] == 0 && r.observed[i] > std::max(1e-5 * opt.samples, 2.0)) {
      r.message = "samples where pdf() integrates to 0 (cell " + std::to_string(i) + ", " +
                  std::to_string(static_cast<uint64_t>(r.observed[i])) + " samples)";
      return r;
    }
  if (r.pdf_integral > 1.0 + 1e-3) {
    r.message = "pdf() integrates to " + std::to_string(r.pdf_integral) + " > 1";
    return r;
  }
  Pooled pooled = pooled_statistic(r.observed, r.expected, opt.min_expected);
  r.statistic = pooled.stat;
  r.dof = std::max(pooled.cells - 1, 1);
  r.p_value = (r.valid == r.specular) ? 1.0 : chi2_survival(r.statistic, r.dof);
  r.passed = r.p_value >= r.threshold;
  r.message = "chi2 " + std::to_string(r.statistic) + " dof " + std::to_string(r.dof) + " p " +
              std::to_string(r.p_value) + " (threshold " + std::to_string(r.threshold) +
              "), pdf integral " + std::to_string(r.pdf_integral);
  return r;
}

} // namespace lobe::verify

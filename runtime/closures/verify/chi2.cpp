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
  // Cell of w (-1: outside the grid); also returns w's phi and cos theta.
  int index(const Vec3& w, double& phi, double& c) const {
    c = std::clamp(static_cast<double>(w.z), -1.0, 1.0);
    if (c < cos_min || c > cos_max) return -1;
    phi = std::atan2(static_cast<double>(w.y), static_cast<double>(w.x));
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

// 3-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr double kGlX[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
constexpr double kGlW[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

// Bounding box (phi, cos theta) of the samples binned in one cell; empty: lo > hi.
struct SampleBox {
  double phi0 = INFINITY, phi1 = -INFINITY, c0 = INFINITY, c1 = -INFINITY;
  void add(double phi, double c) {
    phi0 = std::fmin(phi0, phi), phi1 = std::fmax(phi1, phi);
    c0 = std::fmin(c0, c), c1 = std::fmax(c1, c);
  }
  bool empty() const { return !(phi0 <= phi1); }
};

// Integral of pdf() over one cell by recursive adaptive cubature: a 3x3 Gauss-Legendre rule
// per region, a region split into quadrants while the quadrants' sum differs from the region's
// own estimate by more than the tolerance (divided by sqrt 2 per level: errors of many small
// regions add like random signs). The tolerance is a fraction k of the cell's own Poisson
// standard deviation, so integration error adds a negligible, bounded amount to the statistic
// (k = 0.05: at most ~0.0025 per cell against a per-cell mean of 1); at most kMaxDepth levels
// and kMaxEvals pdf() calls per cell.
// A lobe can be far narrower than a cell: at grazing incidence a sharp reflection lobe is a
// sliver ~2 wo.z alpha wide in azimuth (1.4e-4 rad at cos 0.0014, alpha 0.05, against cells
// 0.126 rad wide) that no node of the coarse rules touches. When the adaptive estimate makes
// the cell's observed count implausible (Poisson P(N >= observed) < kImplausible), the cell is
// integrated again as a partition: the bounding box of its samples (padded), refined down to
// at least kForceDepth levels, plus the up to four rectangles around it, adaptively. The
// samples only say where to look; the estimate is still the integral of pdf() over the whole
// cell, so a pdf that is really too small where the samples are is still caught.
class CellIntegrator {
public:
  CellIntegrator(const LobeView& lobe, const Vec3& wo) : lobe_(lobe), wo_(wo) {}

  // `samples`: the test's sample count; `observed`: samples binned in this cell; `k`: allowed
  // error in units of the cell's Poisson standard deviation sqrt(expected); `box`: where the
  // cell's samples lie.
  double integrate(double phi0, double phi1, double c0, double c1, double samples, double observed,
                   double k, const SampleBox& box) {
    evals_ = 0;
    Box b{phi0, phi1, c0, c1};
    double coarse = gauss(b);
    double expected = std::fmax(std::fmax(coarse * samples, observed), 1.0);
    double tol = k * std::sqrt(expected) / samples;
    double est = refine(b, coarse, tol, 0, 0);
    if (observed < 1 || box.empty() || !implausible(observed, est * samples)) return est;
    // Padded sample box, clipped to the cell, and the rectangles around it.
    double pp = 0.25 * (box.phi1 - box.phi0) + 1e-4 * (phi1 - phi0);
    double pc = 0.25 * (box.c1 - box.c0) + 1e-4 * (c1 - c0);
    Box s{std::fmax(phi0, box.phi0 - pp), std::fmin(phi1, box.phi1 + pp),
          std::fmax(c0, box.c0 - pc), std::fmin(c1, box.c1 + pc)};
    Box parts[5] = {s,
                    {phi0, s.phi0, c0, c1},
                    {s.phi1, phi1, c0, c1},
                    {s.phi0, s.phi1, c0, s.c0},
                    {s.phi0, s.phi1, s.c1, c1}};
    double sum = 0, t = tol / std::sqrt(5.0);
    for (int i = 0; i < 5; ++i) {
      const Box& p = parts[i];
      if (!(p.phi1 > p.phi0) || !(p.c1 > p.c0)) continue;
      sum += refine(p, gauss(p), t, 0, i == 0 ? kForceDepth : 0);
    }
    return sum;
  }

private:
  struct Box {
    double phi0, phi1, c0, c1;
  };
  static constexpr int kMaxDepth = 10, kForceDepth = 3;
  static constexpr long kMaxEvals = 1000000; // per cell: bounds the cost of a pathological cell
  static constexpr double kImplausible = 1e-4;

  // Poisson: P(N >= n | mean) = P(n, mean), the regularised lower incomplete gamma.
  static bool implausible(double n, double mean) {
    return mean <= 0 || gamma_p(n, mean) < kImplausible;
  }

  double gauss(const Box& b) {
    double hp = 0.5 * (b.phi1 - b.phi0), mp = 0.5 * (b.phi1 + b.phi0);
    double hc = 0.5 * (b.c1 - b.c0), mc = 0.5 * (b.c1 + b.c0), sum = 0;
    for (int j = 0; j < 3; ++j) {
      double c = mc + hc * kGlX[j], s = std::sqrt(std::fmax(0.0, 1.0 - c * c));
      for (int i = 0; i < 3; ++i) {
        double phi = mp + hp * kGlX[i];
        Vec3 wi{static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
                static_cast<float>(c)};
        float p = lobe_.pdf(wo_, wi);
        ++evals_;
        if (std::isfinite(p) && p > 0) sum += kGlW[i] * kGlW[j] * p;
      }
    }
    return sum * hp * hc;
  }

  // Refines while the quadrants disagree with the region's estimate, and unconditionally for
  // the first `force` levels.
  double refine(const Box& b, double coarse, double tol, int depth, int force) {
    double pm = 0.5 * (b.phi0 + b.phi1), cm = 0.5 * (b.c0 + b.c1);
    Box q[4] = {{b.phi0, pm, b.c0, cm},
                {pm, b.phi1, b.c0, cm},
                {b.phi0, pm, cm, b.c1},
                {pm, b.phi1, cm, b.c1}};
    double v[4], fine = 0;
    for (int k = 0; k < 4; ++k) fine += (v[k] = gauss(q[k]));
    if (depth >= kMaxDepth || evals_ > kMaxEvals) return fine;
    if (depth >= force && std::fabs(fine - coarse) <= tol) return fine;
    double sum = 0;
    for (int k = 0; k < 4; ++k) sum += refine(q[k], v[k], tol * M_SQRT1_2, depth + 1, force);
    return sum;
  }

  const LobeView& lobe_;
  Vec3 wo_;
  long evals_ = 0;
};

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
  std::vector<SampleBox> boxes(ncell);

  Pcg32 rng(opt.seed);
  for (uint64_t k = 0; k < opt.samples; ++k) {
    auto s = lobe.sample(wo, rng.next_vec3(), opt.mode);
    if (!s) continue;
    ++r.valid;
    if (s->flags & kLobeSpecular) {
      ++r.specular;
      continue;
    }
    double phi, c;
    int idx = g.index(s->wi, phi, c);
    if (idx < 0) {
      ++r.outside;
    } else {
      r.observed[idx] += 1.0;
      boxes[idx].add(phi, c);
    }
  }

  double dphi = 2.0 * M_PI / g.phi_res, dc = (g.cos_max - g.cos_min) / g.cos_res;
  CellIntegrator cells(lobe, wo);
  for (int ic = 0; ic < g.cos_res; ++ic)
    for (int ip = 0; ip < g.phi_res; ++ip) {
      double c0 = g.cos_min + ic * dc, phi0 = ip * dphi;
      size_t idx = static_cast<size_t>(ic) * g.phi_res + ip;
      double integral = cells.integrate(phi0, phi0 + dphi, c0, c0 + dc, double(opt.samples),
                                        r.observed[idx], opt.cell_tolerance, boxes[idx]);
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
  // The cell integrals are accurate to cell_tolerance Poisson deviations each, so the total
  // carries an error of about cell_tolerance / sqrt(samples) (errors of many cells adding like
  // random signs): allow 3 of those above the 1e-3 of float pdf() values.
  double integral_slack = 1e-3 + 3.0 * opt.cell_tolerance / std::sqrt(double(opt.samples));
  if (r.pdf_integral > 1.0 + integral_slack) {
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

// Generates the committed Kulla-Conty tables from this library's own lobes:
//   energy_tables_e.inc, energy_tables_eavg.inc (energy.h): directional albedo of the GGX and
//     Beckmann reflection lobes with Fresnel = 1;
//   energy_tables_dielectric_e.inc, energy_tables_dielectric_eavg.inc (energy_dielectric.h):
//     directional albedo of the rough dielectric lobe (reflection + refraction, exact Fresnel,
//     importance transport) from outside (eta) and inside (1/eta);
//   energy_tables_dielectric_aniso_*.inc: the same for anisotropic lobes, by azimuth too.
// The dielectric tables are made conservative: each cell's interpolation underestimate is
// measured against reference albedos inside it (72x72 strata), every node is raised by the
// largest of its cells', and E_avg is integrated from the raised interpolant.
// Estimator: stratified visible-normal samples; per normal the weight is G2/G1 per branch
// (reflection F, refraction 1 - F, both summed), accumulated in double precision.
//   energy_gen <output-dir>
#include "energy_dielectric.h"
#include "fresnel.h"
#include "microfacet_dist.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <thread>

namespace {

using namespace lobe::closures;
using lobe::Vec3;
constexpr int kEnergyN = 32; // must match energy.h

Vec3 wo_at(double mu) {
  mu = mu < 1e-4 ? 1e-4 : mu;
  return {static_cast<float>(std::sqrt(1.0 - mu * mu)), 0.0f, static_cast<float>(mu)};
}

// Albedo of one visible normal m: reflection weighted by F, refraction by 1 - F (eta <= 0:
// reflection only with F = 1).
double normal_weight(const MicrofacetDistribution& d, const Vec3& wo, const Vec3& m, float eta) {
  float c = dot(wo, m);
  if (!(c > 0.0f)) return 0.0;
  double F = eta > 0.0f ? fresnel_dielectric(c, eta) : 1.0;
  double g1 = d.G1(wo), sum = 0.0;
  Vec3 wr = reflect(wo, m);
  if (wr.z > 0.0f) sum += F * d.G2(wo, wr) / g1;
  Vec3 wt;
  if (F < 1.0 && refract(wo, m, eta, wt) && wt.z < 0.0f) sum += (1.0 - F) * d.G2(wo, wt) / g1;
  return sum;
}

double directional_albedo(const MicrofacetDistribution& d, const Vec3& wo, float eta, int strata) {
  double sum = 0.0;
  for (int a = 0; a < strata; ++a)
    for (int b = 0; b < strata; ++b) {
      float u1 = (a + 0.5f) / strata, u2 = (b + 0.5f) / strata;
      sum += normal_weight(d, wo, d.sample_visible(wo, u1, u2), eta);
    }
  return sum / (static_cast<double>(strata) * strata);
}
double directional_albedo(const MicrofacetDistribution& d, double mu, float eta, int strata) {
  return directional_albedo(d, wo_at(mu), eta, strata);
}

// wo at cosine mu whose azimuth has cos^2 = c.
Vec3 wo_at(double mu, double c) {
  mu = mu < 1e-4 ? 1e-4 : mu;
  double s = std::sqrt(1.0 - mu * mu);
  return {static_cast<float>(s * std::sqrt(c)), static_cast<float>(s * std::sqrt(1.0 - c)),
          static_cast<float>(mu)};
}

// Strata of the reference albedos the interpolation margins are measured against.
constexpr int kCheckStrata = 72;

// Runs fn(t) for t in [0, n) on two threads.
template <class F> void parallel_for(int n, F&& fn) {
  std::thread th([&] {
    for (int t = 1; t < n; t += 2) fn(t);
  });
  for (int t = 0; t < n; t += 2) fn(t);
  th.join();
}

// E_avg = 2 int E mu dmu over E linear between the n grid points mu = i/(n-1) (exact).
double average(const double* e, int n) {
  double avg = 0.0;
  for (int i = 0; i + 1 < n; ++i) {
    double m0 = static_cast<double>(i) / (n - 1), h = 1.0 / (n - 1);
    avg += 2.0 * h * (e[i] * (m0 / 2 + h / 6) + e[i + 1] * (m0 / 2 + h / 3));
  }
  return avg;
}

// The same for E linear in x = sqrt(mu) between nodes mu = (i/(n-1))^2: 2 int E mu dmu =
// 4 int E x^3 dx, by 8-point midpoint sub-intervals (E linear in x, x^3 smooth).
double average_sqrt(const double* e, int n) {
  double avg = 0.0, h = 1.0 / (n - 1);
  for (int i = 0; i + 1 < n; ++i)
    for (int s = 0; s < 8; ++s) {
      double t = (s + 0.5) / 8, x = (i + t) * h;
      avg += 4.0 * (e[i] + (e[i + 1] - e[i]) * t) * x * x * x * h / 8;
    }
  return avg;
}

void print_row(FILE* f, const double* e, int n, const char* indent) {
  std::fprintf(f, "%s{", indent);
  for (int i = 0; i < n; ++i)
    std::fprintf(f, "%.6ff,%s", e[i], i == n - 1 ? "" : (i % 8 == 7 ? "\n  " : " "));
  std::fputs("},\n", f);
}

// Fresnel = 1 reflection tables (energy.h).
void conductor_tables(FILE* fe, FILE* fa) {
  for (int dist = 0; dist < 2; ++dist) {
    std::fputs("{\n", fe);
    std::fputs("{", fa);
    for (int j = 0; j < kEnergyN; ++j) {
      double alpha = static_cast<double>(j) / (kEnergyN - 1);
      auto d = MicrofacetDistribution::make(static_cast<float>(alpha), static_cast<float>(alpha),
                                            dist == 1);
      double e[kEnergyN];
      for (int i = 0; i < kEnergyN; ++i)
        e[i] = alpha < kDeltaAlpha
                   ? 1.0
                   : directional_albedo(d, static_cast<double>(i) / (kEnergyN - 1), 0.0f, 128);
      print_row(fe, e, kEnergyN, " ");
      std::fprintf(fa, "%.6ff,%s", average(e, kEnergyN), j % 8 == 7 ? "\n " : " ");
    }
    std::fputs("},\n", fe);
    std::fputs("},\n", fa);
  }
}

// One distribution's dielectric tables, [side][eta][alpha][mu] and [side][eta][alpha].
struct DielectricBlock {
  double e[2][kDielEta][kDielAlpha][kDielMu];
  double avg[2][kDielEta][kDielAlpha];
  double margin = 0.0; // largest node raise
  bool beckmann = false;
  static float alpha_at(double s) { return static_cast<float>(s * s); }
  static double eta_at(double s) { return 1.0 + (kDielEtaMax - 1.0) * s * s; }
  double reference(int side, double mu, double sa, double se) const {
    float alpha = alpha_at(sa);
    if (alpha < kDeltaAlpha) return 1.0;
    double eta = eta_at(se);
    auto d = MicrofacetDistribution::make(alpha, alpha, beckmann);
    return directional_albedo(d, mu, static_cast<float>(side == 0 ? eta : 1.0 / eta), kCheckStrata);
  }
  // The trilinear look-up of energy_dielectric.h, in double.
  double lookup(int side, double su, double sa, double se) const {
    auto grid = [](double x, int n, int& i, double& t) {
      double y = std::clamp(x, 0.0, 1.0) * (n - 1);
      i = std::min(n - 2, static_cast<int>(y));
      t = y - i;
    };
    int i, j, k;
    double ti, tj, tk;
    grid(su, kDielMu, i, ti);
    grid(sa, kDielAlpha, j, tj);
    grid(se, kDielEta, k, tk);
    auto at = [&](int kk, int jj) {
      return e[side][kk][jj][i] + (e[side][kk][jj][i + 1] - e[side][kk][jj][i]) * ti;
    };
    auto al = [&](int kk) { return at(kk, j) + (at(kk, j + 1) - at(kk, j)) * tj; };
    return al(k) + (al(k + 1) - al(k)) * tk;
  }
  void compute(bool beck) {
    beckmann = beck;
    for (int side = 0; side < 2; ++side)
      for (int k = 0; k < kDielEta; ++k) {
        double eta = diel_grid_eta(k);
        float e_rel = static_cast<float>(side == 0 ? eta : 1.0 / eta);
        for (int j = 0; j < kDielAlpha; ++j) {
          float alpha = static_cast<float>(diel_grid_alpha(j));
          auto d = MicrofacetDistribution::make(alpha, alpha, beckmann);
          for (int i = 0; i < kDielMu; ++i)
            e[side][k][j][i] =
                alpha < kDeltaAlpha ? 1.0 : directional_albedo(d, diel_grid_mu(i), e_rel, 64);
        }
      }
    // Interpolation underestimate per cell (at the cell centre and the centres of its faces
    // towards lower alpha and eta), then every node raised by the largest of its cells'.
    static thread_local double cell[kDielEta - 1][kDielAlpha - 1][kDielMu - 1];
    for (int side = 0; side < 2; ++side) {
      for (int k = 0; k + 1 < kDielEta; ++k)
        for (int j = 0; j + 1 < kDielAlpha; ++j)
          for (int i = 0; i + 1 < kDielMu; ++i) {
            double m = 0.0;
            for (double fa : {0.0, 0.5})
              for (double fe : {0.0, 0.5}) {
                double su = (i + 0.5) / (kDielMu - 1), sa = (j + fa) / (kDielAlpha - 1),
                       se = (k + fe) / (kDielEta - 1);
                m = std::max(m, reference(side, su * su, sa, se) - lookup(side, su, sa, se));
              }
            cell[k][j][i] = m;
          }
      double raised[kDielEta][kDielAlpha][kDielMu];
      for (int k = 0; k < kDielEta; ++k)
        for (int j = 0; j < kDielAlpha; ++j)
          for (int i = 0; i < kDielMu; ++i) {
            double m = 0.0;
            for (int dk = -1; dk <= 0; ++dk)
              for (int dj = -1; dj <= 0; ++dj)
                for (int di = -1; di <= 0; ++di) {
                  int kk = k + dk, jj = j + dj, ii = i + di;
                  if (kk >= 0 && kk < kDielEta - 1 && jj >= 0 && jj < kDielAlpha - 1 && ii >= 0 &&
                      ii < kDielMu - 1)
                    m = std::max(m, cell[kk][jj][ii]);
                }
            margin = std::max(margin, m);
            raised[k][j][i] = std::min(1.0, e[side][k][j][i] + (m > 0.0 ? m + 2e-5 : 0.0));
          }
      for (int k = 0; k < kDielEta; ++k)
        for (int j = 0; j < kDielAlpha; ++j) {
          for (int i = 0; i < kDielMu; ++i) e[side][k][j][i] = raised[k][j][i];
          avg[side][k][j] = average_sqrt(e[side][k][j], kDielMu);
        }
    }
  }
};

// One distribution's anisotropic tables, [side][eta][ax][ay][c][mu] (see energy_dielectric.h).
struct AnisoBlock {
  double e[2][kAnEta][kAnA][kAnA][kAnC][kAnMu];
  uint16_t q[2][kAnEta][kAnA][kAnA][kAnC][kAnMu];
  double avg[2][kAnEta][kAnA][kAnA];
  double margin = 0.0;
  bool beckmann = false;
  static constexpr int kDims = 5;
  static constexpr int kN[kDims] = {kAnEta, kAnA, kAnA, kAnC, kAnMu};
  double& at(double (&t)[kAnEta][kAnA][kAnA][kAnC][kAnMu], const int* n) {
    return t[n[0]][n[1]][n[2]][n[3]][n[4]];
  }
  // Reference at continuous grid coordinates g (in node units).
  double reference(int side, const double* g, int strata) const {
    auto sq = [](double x, int n) {
      double s = x / (n - 1);
      return s * s;
    };
    double eta = 1.0 + (kDielEtaMax - 1.0) * sq(g[0], kAnEta);
    float ax = static_cast<float>(sq(g[1], kAnA)), ay = static_cast<float>(sq(g[2], kAnA));
    double c = g[3] / (kAnC - 1), mu = sq(g[4], kAnMu);
    if (std::max(ax, ay) < kDeltaAlpha) return 1.0;
    auto d = MicrofacetDistribution::make(ax, ay, beckmann);
    return directional_albedo(d, wo_at(mu, c), static_cast<float>(side == 0 ? eta : 1.0 / eta),
                              strata);
  }
  double lookup(const double (&t)[kAnEta][kAnA][kAnA][kAnC][kAnMu], const double* g) const {
    int i0[kDims];
    double f[kDims];
    for (int d = 0; d < kDims; ++d) {
      i0[d] = std::min(kN[d] - 2, static_cast<int>(g[d]));
      f[d] = g[d] - i0[d];
    }
    double sum = 0.0;
    for (int corner = 0; corner < (1 << kDims); ++corner) {
      double w = 1.0;
      int n[kDims];
      for (int d = 0; d < kDims; ++d) {
        int b = (corner >> d) & 1;
        n[d] = i0[d] + b;
        w *= b ? f[d] : 1.0 - f[d];
      }
      sum += w * t[n[0]][n[1]][n[2]][n[3]][n[4]];
    }
    return sum;
  }
  void compute(bool beck) {
    beckmann = beck;
    static double cell[kAnEta - 1][kAnA - 1][kAnA - 1][kAnC - 1][kAnMu - 1];
    for (int side = 0; side < 2; ++side) {
      parallel_for(kAnEta, [&](int k) {
        for (int jx = 0; jx < kAnA; ++jx)
          for (int jy = 0; jy < kAnA; ++jy)
            for (int l = 0; l < kAnC; ++l)
              for (int i = 0; i < kAnMu; ++i) {
                double g[kDims] = {double(k), double(jx), double(jy), double(l), double(i)};
                e[side][k][jx][jy][l][i] = reference(side, g, 64);
              }
      });
      // Margins at each cell's centre and two more points inside it.
      parallel_for(kAnEta - 1, [&](int k) {
        for (int jx = 0; jx + 1 < kAnA; ++jx)
          for (int jy = 0; jy + 1 < kAnA; ++jy)
            for (int l = 0; l + 1 < kAnC; ++l)
              for (int i = 0; i + 1 < kAnMu; ++i) {
                double m = 0.0;
                // Centre, the azimuth faces (E is steepest across c at grazing), two points
                // along mu, and two off-centre points.
                const double pts[7][kDims] = {{0.5, 0.5, 0.5, 0.5, 0.5}, {0.5, 0.5, 0.5, 0.0, 0.5},
                                              {0.5, 0.5, 0.5, 1.0, 0.5}, {0.5, 0.5, 0.5, 0.5, 0.2},
                                              {0.5, 0.5, 0.5, 0.5, 0.8}, {0.2, 0.7, 0.3, 0.8, 0.35},
                                              {0.8, 0.3, 0.7, 0.2, 0.65}};
                for (const auto& p : pts) {
                  double g[kDims] = {k + p[0], jx + p[1], jy + p[2], l + p[3], i + p[4]};
                  m = std::max(m, reference(side, g, kCheckStrata) - lookup(e[side], g));
                }
                cell[k][jx][jy][l][i] = m;
              }
      });
      static double raised[kAnEta][kAnA][kAnA][kAnC][kAnMu];
      for (int idx = 0; idx < kAnEta * kAnA * kAnA * kAnC * kAnMu; ++idx) {
        int n[kDims], r = idx;
        for (int d = kDims - 1; d >= 0; --d) n[d] = r % kN[d], r /= kN[d];
        double m = 0.0;
        for (int corner = 0; corner < (1 << kDims); ++corner) {
          int c[kDims];
          bool ok = true;
          for (int d = 0; d < kDims; ++d) {
            c[d] = n[d] - ((corner >> d) & 1);
            ok = ok && c[d] >= 0 && c[d] < kN[d] - 1;
          }
          if (ok) m = std::max(m, cell[c[0]][c[1]][c[2]][c[3]][c[4]]);
        }
        margin = std::max(margin, m);
        at(raised, n) = std::min(1.0, at(e[side], n) + (m > 0.0 ? m + 2e-5 : 0.0));
      }
      // Quantise (rounding up) and integrate E_avg from the interpolant of what is stored:
      // azimuth average over phi in [0, pi/2] (E linear in c = cos^2 phi), mu by average_sqrt.
      for (int idx = 0; idx < kAnEta * kAnA * kAnA * kAnC * kAnMu; ++idx) {
        int n[kDims], r = idx;
        for (int d = kDims - 1; d >= 0; --d) n[d] = r % kN[d], r /= kN[d];
        double v = std::ceil(at(raised, n) * 65535.0);
        q[side][n[0]][n[1]][n[2]][n[3]][n[4]] = static_cast<uint16_t>(std::min(v, 65535.0));
        at(e[side], n) = q[side][n[0]][n[1]][n[2]][n[3]][n[4]] / 65535.0;
      }
      for (int k = 0; k < kAnEta; ++k)
        for (int jx = 0; jx < kAnA; ++jx)
          for (int jy = 0; jy < kAnA; ++jy) {
            constexpr int kPhi = 512;
            double sum = 0.0;
            for (int p = 0; p < kPhi; ++p) {
              double phi = (p + 0.5) / kPhi * (3.14159265358979323846 / 2), c = std::cos(phi);
              double gc = c * c * (kAnC - 1);
              int l = std::min(kAnC - 2, static_cast<int>(gc));
              double t = gc - l, row[kAnMu];
              for (int i = 0; i < kAnMu; ++i)
                row[i] = e[side][k][jx][jy][l][i] * (1 - t) + e[side][k][jx][jy][l + 1][i] * t;
              sum += average_sqrt(row, kAnMu);
            }
            avg[side][k][jx][jy] = sum / kPhi;
          }
    }
  }
};

double dielectric_tables(FILE* fe, FILE* fa) {
  static DielectricBlock blocks[2];
  std::thread t([] { blocks[1].compute(true); });
  blocks[0].compute(false);
  t.join();
  for (const DielectricBlock& b : blocks) {
    std::fputs("{\n", fe);
    std::fputs("{\n", fa);
    for (int side = 0; side < 2; ++side) {
      std::fputs(" {\n", fe);
      std::fputs(" {\n", fa);
      for (int k = 0; k < kDielEta; ++k) {
        std::fputs("  {\n", fe);
        for (int j = 0; j < kDielAlpha; ++j) print_row(fe, b.e[side][k][j], kDielMu, "   ");
        std::fputs("  },\n", fe);
        print_row(fa, b.avg[side][k], kDielAlpha, "  ");
      }
      std::fputs(" },\n", fe);
      std::fputs(" },\n", fa);
    }
    std::fputs("},\n", fe);
    std::fputs("},\n", fa);
  }
  return std::max(blocks[0].margin, blocks[1].margin);
}

void aniso_tables(FILE* fe, FILE* fa, double& margin) {
  static AnisoBlock blocks[2];
  blocks[0].compute(false);
  blocks[1].compute(true);
  margin = std::max(blocks[0].margin, blocks[1].margin);
  for (const AnisoBlock& b : blocks) {
    std::fputs("{\n", fe);
    std::fputs("{\n", fa);
    for (int side = 0; side < 2; ++side) {
      std::fputs(" {\n", fe);
      std::fputs(" {\n", fa);
      for (int k = 0; k < kAnEta; ++k) {
        std::fputs("  {\n", fe);
        std::fputs("  {\n", fa);
        for (int jx = 0; jx < kAnA; ++jx) {
          std::fputs("   {\n", fe);
          for (int jy = 0; jy < kAnA; ++jy) {
            std::fputs("    {", fe);
            for (int l = 0; l < kAnC; ++l) {
              std::fputs("{", fe);
              for (int i = 0; i < kAnMu; ++i)
                std::fprintf(fe, "%u,", static_cast<unsigned>(b.q[side][k][jx][jy][l][i]));
              std::fputs("},", fe);
            }
            std::fputs("},\n", fe);
          }
          std::fputs("   },\n", fe);
          print_row(fa, b.avg[side][k][jx], kAnA, "   ");
        }
        std::fputs("  },\n", fe);
        std::fputs("  },\n", fa);
      }
      std::fputs(" },\n", fe);
      std::fputs(" },\n", fa);
    }
    std::fputs("},\n", fe);
    std::fputs("},\n", fa);
  }
}

FILE* open_table(const std::string& dir, const char* name) {
  FILE* f = std::fopen((dir + "/" + name).c_str(), "w");
  if (f) std::fputs("// Generated by energy_gen.cpp; do not edit.\n", f);
  return f;
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: energy_gen <output-dir>\n");
    return 2;
  }
  std::string dir = argv[1];
  FILE* fe = open_table(dir, "energy_tables_e.inc");
  FILE* fa = open_table(dir, "energy_tables_eavg.inc");
  FILE* de = open_table(dir, "energy_tables_dielectric_e.inc");
  FILE* da = open_table(dir, "energy_tables_dielectric_eavg.inc");
  FILE* ae = open_table(dir, "energy_tables_dielectric_aniso_e.inc");
  FILE* aa = open_table(dir, "energy_tables_dielectric_aniso_eavg.inc");
  if (!fe || !fa || !de || !da || !ae || !aa) return 1;
  conductor_tables(fe, fa);
  double iso_margin = dielectric_tables(de, da), aniso_margin = 0.0;
  aniso_tables(ae, aa, aniso_margin);
  for (FILE* f : {fe, fa, de, da, ae, aa}) std::fclose(f);
  std::printf("largest interpolation margin: isotropic %.4g, anisotropic %.4g\n", iso_margin,
              aniso_margin);
  return 0;
}

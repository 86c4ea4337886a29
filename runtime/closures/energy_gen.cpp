// Generates the committed Kulla-Conty tables from this library's own lobes:
//   energy_tables_e.inc, energy_tables_eavg.inc (energy.h): directional albedo of the GGX and
//     Beckmann reflection lobes with Fresnel = 1;
//   energy_tables_dielectric_e.inc, energy_tables_dielectric_eavg.inc (energy_dielectric.h):
//     directional albedo of the rough dielectric lobe (reflection + refraction, exact Fresnel,
//     importance transport) from outside (eta) and inside (1/eta).
// Estimator: stratified visible-normal samples; per normal the weight is G2/G1 per branch
// (reflection F, refraction 1 - F, both summed), accumulated in double precision.
//   energy_gen <output-dir>
#include "energy_dielectric.h"
#include "fresnel.h"
#include "microfacet_dist.h"

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

double directional_albedo(const MicrofacetDistribution& d, double mu, float eta, int strata) {
  Vec3 wo = wo_at(mu);
  double sum = 0.0;
  for (int a = 0; a < strata; ++a)
    for (int b = 0; b < strata; ++b) {
      float u1 = (a + 0.5f) / strata, u2 = (b + 0.5f) / strata;
      sum += normal_weight(d, wo, d.sample_visible(wo, u1, u2), eta);
    }
  return sum / (static_cast<double>(strata) * strata);
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
  void compute(bool beckmann) {
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
          avg[side][k][j] = average_sqrt(e[side][k][j], kDielMu);
        }
      }
  }
};

void dielectric_tables(FILE* fe, FILE* fa) {
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
  if (!fe || !fa || !de || !da) return 1;
  conductor_tables(fe, fa);
  dielectric_tables(de, da);
  for (FILE* f : {fe, fa, de, da}) std::fclose(f);
  return 0;
}

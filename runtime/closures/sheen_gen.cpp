// Generates the sheen tables (sheen.h): for the Charlie microfibre distribution
//   D(m) = (2 + 1/r) sin(theta_m)^(1/r) / (2 pi),
// 1. the projected area P(mu, r) = int D(m) max(0, wo.m) dm (Smith: 1 + Lambda = P / mu), by
//    Gauss-Legendre quadrature in theta_m with the azimuthal integral in closed form, split at
//    theta_m = pi/2 - theta_o where that closed form changes branch;
// 2. the directional albedo E(mu, r) of the lobe sheen.h evaluates (height-correlated Smith
//    with the P table as sheen.h interpolates it), by Gauss-Legendre quadrature over wi.
// Both are made conservative for the look-up between nodes: P nodes are scaled up by the
// interpolation underestimate of the cells around them (a smaller P would mean more energy
// than the exact masking allows) and E nodes raised by theirs (layering attenuates the base by
// E, so an E that is too small would create energy). The largest margins are printed in the
// generated files.
//   sheen_gen <output-dir>   (writes sheen_tables_p.inc and sheen_tables_e.inc)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr int kMu = 65, kR = 33; // must match sheen.h
constexpr double kRMin = 0.01, kRMax = 1.0;
const double kPiD = 3.14159265358979323846;

double r_at(double t) { return kRMin * std::pow(kRMax / kRMin, t); }
double t_of(double r) { return std::log(r / kRMin) / std::log(kRMax / kRMin); }
// P nodes: x = sqrt(1 - mu) = i / (kMu - 1). E nodes: s = sqrt(mu) = i / (kMu - 1).
double p_mu(int i) {
  double x = double(i) / (kMu - 1);
  return 1.0 - x * x;
}
double e_mu(int i) {
  double s = double(i) / (kMu - 1);
  return s * s;
}

struct GaussLegendre {
  std::vector<double> x, w;
  explicit GaussLegendre(int n) : x(n), w(n) {
    for (int i = 0; i < n; ++i) {
      double z = std::cos(kPiD * (i + 0.75) / (n + 0.5)), dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = z;
        for (int k = 2; k <= n; ++k) {
          double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1.0);
        double dz = p1 / dp;
        z -= dz;
        if (std::fabs(dz) < 1e-15) break;
      }
      x[i] = z;
      w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
  }
  // int_a^b f over `panels` equal panels.
  template <class F> double integrate(double a, double b, int panels, F&& f) const {
    double sum = 0.0, h = (b - a) / panels;
    for (int p = 0; p < panels; ++p) {
      double c = a + (p + 0.5) * h;
      for (size_t i = 0; i < x.size(); ++i) sum += w[i] * f(c + 0.5 * h * x[i]);
    }
    return sum * 0.5 * h;
  }
};

const GaussLegendre& gl() {
  static const GaussLegendre g(24);
  return g;
}

double charlie(double sin_m, double r) {
  return (2.0 + 1.0 / r) * std::pow(sin_m, 1.0 / r) / (2.0 * kPiD);
}

// int_0^2pi max(0, cos_o cos_m + sin_o sin_m cos phi) dphi.
double azimuthal(double mu, double theta_m) {
  double a = mu * std::cos(theta_m),
         b = std::sqrt(std::max(0.0, 1.0 - mu * mu)) * std::sin(theta_m);
  if (b <= a) return 2.0 * kPiD * a;
  double phi0 = std::acos(std::clamp(-a / b, -1.0, 1.0));
  return 2.0 * (a * phi0 + b * std::sin(phi0));
}

double projected_area(double mu, double r) {
  double k = kPiD / 2 - std::acos(std::clamp(mu, 0.0, 1.0));
  auto f = [&](double t) { return charlie(std::sin(t), r) * std::sin(t) * azimuthal(mu, t); };
  return gl().integrate(0.0, k, 8, f) + gl().integrate(k, kPiD / 2, 8, f);
}

// The bilinear look-ups sheen.h does, in double.
struct Tables {
  double p[kR][kMu], e[kR][kMu];
  static void index(double v, int n, int& i, double& f) {
    double x = std::clamp(v, 0.0, 1.0) * (n - 1);
    i = std::min(n - 2, static_cast<int>(x));
    f = x - i;
  }
  static double lerp2(const double (&t)[kR][kMu], double x, double tr) {
    int i, j;
    double fx, fr;
    index(x, kMu, i, fx);
    index(tr, kR, j, fr);
    double a = t[j][i] + (t[j][i + 1] - t[j][i]) * fx;
    double b = t[j + 1][i] + (t[j + 1][i + 1] - t[j + 1][i]) * fx;
    return a + (b - a) * fr;
  }
  double P(double mu, double tr) const { return lerp2(p, std::sqrt(std::max(0.0, 1.0 - mu)), tr); }
  double E(double mu, double tr) const { return lerp2(e, std::sqrt(std::max(0.0, mu)), tr); }
};

// Directional albedo of f cos_i = D(h) cos_i / (4 (P_o cos_i + P_i cos_o - cos_o cos_i)).
double albedo(const Tables& t, double mu_o, double r) {
  mu_o = std::max(mu_o, 1e-6);
  double tr = t_of(r), so = std::sqrt(1.0 - mu_o * mu_o), po = t.P(mu_o, tr);
  // cos_i = s^2 (refines grazing wi, where the lobe peaks for small r); phi over [0, pi] twice.
  auto over_s = [&](double s) {
    double mu_i = s * s, si = std::sqrt(std::max(0.0, 1.0 - mu_i * mu_i)), pi_ = t.P(mu_i, tr);
    auto over_phi = [&](double phi) {
      double hx = so + si * std::cos(phi), hy = si * std::sin(phi), hz = mu_o + mu_i;
      double len = std::sqrt(hx * hx + hy * hy + hz * hz), cz = hz / len;
      double sm = std::sqrt(std::max(0.0, 1.0 - cz * cz));
      return charlie(sm, r) * mu_i / (4.0 * (po * mu_i + pi_ * mu_o - mu_o * mu_i));
    };
    return 2.0 * gl().integrate(0.0, kPiD, 12, over_phi) * 2.0 * s;
  };
  return gl().integrate(0.0, 1.0, 12, over_s);
}

void print_table(FILE* f, const double (&t)[kR][kMu]) {
  for (int j = 0; j < kR; ++j) {
    std::fputs(" {", f);
    for (int i = 0; i < kMu; ++i)
      std::fprintf(f, "%.7ff,%s", t[j][i], i == kMu - 1 ? "" : (i % 8 == 7 ? "\n  " : " "));
    std::fputs("},\n", f);
  }
}

// Runs fn(j) for j in [0, n) on two threads.
template <class F> void parallel_rows(int n, F&& fn) {
  std::thread th([&] {
    for (int j = 1; j < n; j += 2) fn(j);
  });
  for (int j = 0; j < n; j += 2) fn(j);
  th.join();
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: sheen_gen <output-dir>\n");
    return 2;
  }
  static Tables t;
  parallel_rows(kR, [](int j) {
    for (int i = 0; i < kMu; ++i) t.p[j][i] = projected_area(p_mu(i), r_at(double(j) / (kR - 1)));
  });
  // Interpolation margins per cell, sampled inside it and on its edges; every node then takes
  // the largest margin of the cells around it, so each cell's interpolant is raised by at least
  // its own margin.
  static double cell[kR - 1][kMu - 1];
  auto spread = [](double(&nodes)[kR][kMu], bool relative) {
    double worst = 0.0;
    for (int j = 0; j < kR; ++j)
      for (int i = 0; i < kMu; ++i) {
        double m = 0.0;
        for (int dj = -1; dj <= 0; ++dj)
          for (int di = -1; di <= 0; ++di)
            if (j + dj >= 0 && j + dj < kR - 1 && i + di >= 0 && i + di < kMu - 1)
              m = std::max(m, cell[j + dj][i + di]);
        worst = std::max(worst, m);
        nodes[j][i] =
            relative ? nodes[j][i] * (1.0 + m + 1e-6) : std::min(1.0, nodes[j][i] + m + 1e-6);
      }
    return worst;
  };
  parallel_rows(kR - 1, [](int j) {
    for (int i = 0; i + 1 < kMu; ++i) {
      double m = 0.0;
      for (double fx : {0.0, 0.25, 0.5, 0.75, 1.0})
        for (double fr : {0.0, 0.25, 0.5, 0.75, 1.0}) {
          double x = (i + fx) / (kMu - 1), tr = (j + fr) / (kR - 1), mu = 1.0 - x * x;
          m = std::max(m, projected_area(mu, r_at(tr)) / t.P(mu, tr) - 1.0);
        }
      cell[j][i] = m;
    }
  });
  double p_under = spread(t.p, true);

  parallel_rows(kR, [](int j) {
    for (int i = 0; i < kMu; ++i) t.e[j][i] = albedo(t, e_mu(i), r_at(double(j) / (kR - 1)));
  });
  parallel_rows(kR - 1, [](int j) {
    for (int i = 0; i + 1 < kMu; ++i) {
      double m = 0.0;
      for (double fs : {0.25, 0.5, 0.75})
        for (double fr : {0.0, 0.5, 1.0}) {
          double s = (i + fs) / (kMu - 1), tr = (j + fr) / (kR - 1), mu = s * s;
          m = std::max(m, albedo(t, mu, r_at(tr)) - t.E(mu, tr));
        }
      cell[j][i] = m;
    }
  });
  double e_under = spread(t.e, false);

  for (int k = 0; k < 2; ++k) {
    std::string name = k == 0 ? "/sheen_tables_p.inc" : "/sheen_tables_e.inc";
    FILE* f = std::fopen((std::string(argv[1]) + name).c_str(), "w");
    if (!f) return 1;
    std::fputs("// Generated by sheen_gen.cpp; do not edit.\n", f);
    if (k == 0)
      std::fprintf(
          f, "// Scaled per node by 1 + its cells' interpolation underestimate (at most %.3g).\n",
          p_under);
    else
      std::fprintf(f,
                   "// Raised per node by its cells' interpolation underestimate (at most %.3g).\n",
                   e_under);
    print_table(f, k == 0 ? t.p : t.e);
    std::fclose(f);
  }
  std::printf("P margin %.3g, E margin %.3g\n", p_under, e_under);
  return 0;
}

// `lobe brdf EXPR`: look at one closure. Without query options it prints a report (albedo
// table, white furnace, chi-square, consistency, reciprocity, stress/NaN counts) and, with
// --plot PREFIX, writes PREFIX_polar.png (the lobe in the plane of incidence for several view
// angles) and PREFIX_albedo.png (directional albedo against angle) through gnuplot. Query
// mode for scripts: --eval, --sample, --albedo, printed as CSV or JSON.
//
// `lobe brdf --shader NAME [--param NAME VALUE]...` does the same for a compiled material: the
// shader (found on the search path, stdlib_shaders/ included, or by path) is compiled with its
// instance values, run at a point with N = Ng = (0,0,1), dPdu = (1,0,0), I = -wo, and its Ci
// closure is flattened into a Bsdf that evaluates through the material's JIT closure kernels.
#include "command.h"

#include "diag/diagnostics.h"

#include "albedo.h"
#include "chi2.h"
#include "closure_expr.h"
#include "closure_lobe.h"
#include "consistency.h"
#include "reciprocity.h"
#include "rng.h"
#include "stress.h"

#include "lobe/bsdf.h"
#include "lobe/context.h"
#include "lobe/install.h"
#include "lobe/shadingsys.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using namespace lobe;
using namespace lobe::verify;

namespace {

struct Options {
  std::string expr;
  std::string shader;                    // --shader: a material instead of a closure call
  std::vector<std::string> params;       // --param name value (pairs)
  std::vector<std::string> include_dirs; // -I
  uint64_t samples = 200000;
  std::string plot;
  std::vector<std::string> evals, samples_u;
  std::vector<double> albedo_angles;
  std::string wo_text;
  double theta = 45;
  std::string format = "csv";
  std::string mode = "radiance";
};

std::vector<double> numbers(const std::string& s) {
  std::vector<double> v;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    double d = std::strtod(item.c_str(), &end);
    if (end == item.c_str()) return {};
    v.push_back(d);
  }
  return v;
}

Vec3 vec(const std::vector<double>& v, size_t at) {
  return {float(v[at]), float(v[at + 1]), float(v[at + 2])};
}

// Three finite numbers from v[at] on, not all zero (a direction normalize() can take).
bool finite_direction(const std::vector<double>& v, size_t at) {
  Vec3 d = vec(v, at);
  for (float c : {d.x, d.y, d.z})
    if (!std::isfinite(c)) return false;
  return d.x != 0 || d.y != 0 || d.z != 0;
}

// The message, then the expression with a caret under the place (the diagnostics' caret
// renderer), indented by two spaces.
void print_expr_error(const std::string& expr, const ExprError& e) {
  std::string out = "lobe brdf: error: " + e.message + "\n";
  std::string carets = diag::caret_under(expr, e.pos);
  for (size_t b = 0; b < carets.size();) {
    size_t n = carets.find('\n', b);
    out.append("  ").append(carets, b, n + 1 - b);
    b = n + 1;
  }
  std::fputs(out.c_str(), stderr);
}

float lum(const Vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// --- query mode -------------------------------------------------------------------------------

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  void print(const std::string& format) const {
    if (format == "json") {
      nlohmann::ordered_json out = nlohmann::ordered_json::array();
      for (const auto& r : rows) {
        nlohmann::ordered_json o;
        for (size_t i = 0; i < columns.size(); ++i) o[columns[i]] = r[i];
        out.push_back(o);
      }
      std::printf("%s\n", out.dump(2).c_str());
      return;
    }
    for (size_t i = 0; i < columns.size(); ++i)
      std::printf("%s%s", i ? "," : "", columns[i].c_str());
    std::printf("\n");
    for (const auto& r : rows) {
      for (size_t i = 0; i < r.size(); ++i) std::printf("%s%.9g", i ? "," : "", r[i]);
      std::printf("\n");
    }
  }
};

int run_query(const Options& o, const LobeView& lobe, const Vec3& wo, Transport mode) {
  Table t;
  if (!o.evals.empty()) {
    t.columns = {"wo_x", "wo_y", "wo_z", "wi_x", "wi_y", "wi_z", "r", "g", "b", "pdf"};
    for (const std::string& s : o.evals) {
      std::vector<double> v = numbers(s);
      if (v.size() != 6) {
        std::fprintf(stderr, "lobe brdf: --eval wants wo_x,wo_y,wo_z,wi_x,wi_y,wi_z: '%s'\n",
                     s.c_str());
        return 2;
      }
      if (!finite_direction(v, 0) || !finite_direction(v, 3)) {
        std::fprintf(stderr, "lobe brdf: --eval: directions must be finite and non-zero: '%s'\n",
                     s.c_str());
        return 1;
      }
      Vec3 a = normalize(vec(v, 0)), b = normalize(vec(v, 3));
      BsdfEval e = lobe.eval(a, b, mode);
      t.rows.push_back(
          {a.x, a.y, a.z, b.x, b.y, b.z, e.value.x, e.value.y, e.value.z, lobe.pdf(a, b)});
    }
  } else if (!o.samples_u.empty()) {
    t.columns = {"u1",  "u2",  "u3",  "ok",  "wi_x",  "wi_y", "wi_z",
                 "w_r", "w_g", "w_b", "pdf", "flags", "eta"};
    for (const std::string& s : o.samples_u) {
      std::vector<double> v = numbers(s);
      if (v.size() != 3) {
        std::fprintf(stderr, "lobe brdf: --sample wants u1,u2,u3: '%s'\n", s.c_str());
        return 2;
      }
      for (double u : v)
        if (!(u >= 0 && u < 1)) { // NaN included
          std::fprintf(stderr, "lobe brdf: --sample: random numbers must lie in [0, 1): '%s'\n",
                       s.c_str());
          return 1;
        }
      auto r = lobe.sample(wo, vec(v, 0), mode);
      if (!r)
        t.rows.push_back({v[0], v[1], v[2], 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
      else
        t.rows.push_back({v[0], v[1], v[2], 1, r->wi.x, r->wi.y, r->wi.z, r->weight.x, r->weight.y,
                          r->weight.z, r->pdf, double(r->flags), r->eta});
    }
  } else {
    t.columns = {"theta",  "mc_r",   "mc_g",  "mc_b",  "stderr_g", "quad_r",
                 "quad_g", "quad_b", "api_r", "api_g", "api_b"};
    for (double th : o.albedo_angles) {
      Vec3 w = direction_at(th * M_PI / 180.0);
      AlbedoEstimate mc = albedo_mc(lobe, w, o.samples, 1, mode);
      QuadratureResult q = albedo_quadrature(lobe, w, mode);
      Color3 api = lobe.albedo(w);
      t.rows.push_back({th, mc.mean.r, mc.mean.g, mc.mean.b, mc.std_error.g, q.integral.r,
                        q.integral.g, q.integral.b, api.x, api.y, api.z});
    }
  }
  t.print(o.format);
  return 0;
}

// --- a compiled material as a lobe -----------------------------------------------------------

// The Ci of a material at one point, seen from wo: shaded again (I = -wo) and flattened into a
// Bsdf whenever wo changes, since both the closure and the Bsdf's lobe selection depend on it.
class ShaderLobe : public LobeView {
public:
  explicit ShaderLobe(std::shared_ptr<const Material> m) : m_(std::move(m)) {}
  BsdfEval eval(const Vec3& wo, const Vec3& wi, Transport mode) const override {
    return at(wo).eval(wo, wi, mode);
  }
  float pdf(const Vec3& wo, const Vec3& wi) const override { return at(wo).pdf(wo, wi); }
  std::optional<BsdfSample> sample(const Vec3& wo, const Vec3& u, Transport mode) const override {
    return at(wo).sample(wo, u, mode);
  }
  Color3 albedo(const Vec3& wo) const override { return at(wo).albedo(wo); }
  uint32_t flags() const override {
    uint32_t f = 0;
    const Bsdf& b = at(Vec3{0, 0, 1});
    for (int i = 0; i < b.lobe_count(); ++i) f |= b.lobe(i).flags;
    return f;
  }
  // The closure tree printed as OSL prints it, for the report.
  std::string describe() const { return closure_to_string(shade(Vec3{0, 0, 1})); }

private:
  const ClosureNode* shade(const Vec3& wo) const {
    ctx_.reset();
    ShaderGlobals sg{};
    sg.context = &ctx_;
    sg.N = sg.Ng = Vec3{0, 0, 1};
    sg.dPdu = Vec3{1, 0, 0};
    sg.dPdv = Vec3{0, 1, 0};
    sg.I = Vec3{-wo.x, -wo.y, -wo.z};
    sg.u = sg.v = 0.5f;
    sg.raytype = kRayCamera;
    m_->shade(sg);
    return sg.Ci;
  }
  const Bsdf& at(const Vec3& wo) const {
    if (!built_ || !(wo == wo_)) {
      bsdf_.build(shade(wo), wo, Vec3{0, 0, 1}, m_->closure_kernels());
      wo_ = wo;
      built_ = true;
    }
    return bsdf_;
  }
  std::shared_ptr<const Material> m_;
  mutable ShadingContext ctx_;
  mutable Bsdf bsdf_;
  mutable Vec3 wo_;
  mutable bool built_ = false;
};

// What the report prints about the lobe: a name, an optional note, the IOR below the surface
// for the generalised reciprocity check.
struct Subject {
  std::string name;
  std::string note;
  double eta_below = 1.0;
};

// --- report and plots -------------------------------------------------------------------------

const double kTableAngles[] = {0, 15, 30, 45, 60, 75, 85, 89};

void report(const Options& o, const Subject& pc, const LobeView& lobe, Transport mode) {
  uint32_t f = lobe.flags();
  std::printf("closure   %s\nflags     %s%s%s%s%s\n", pc.name.c_str(),
              f & kLobeReflect ? "reflect " : "", f & kLobeTransmit ? "transmit " : "",
              f & kLobeDiffuse ? "diffuse " : "", f & kLobeGlossy ? "glossy " : "",
              f & kLobeSpecular ? "specular" : "");
  if (!pc.note.empty()) std::printf("note      %s\n", pc.note.c_str());
  std::printf("\nalbedo (%llu samples; quadrature of eval(); albedo() of the library)\n",
              static_cast<unsigned long long>(o.samples));
  std::printf("  theta   MC r     MC g     MC b     +-       quad g   albedo() g\n");
  double furnace = 0;
  for (double th : kTableAngles) {
    Vec3 w = direction_at(th * M_PI / 180.0);
    AlbedoEstimate mc = albedo_mc(lobe, w, o.samples, 1, Transport::Importance);
    QuadratureResult q = albedo_quadrature(lobe, w, Transport::Importance);
    furnace = std::max(furnace, mc.mean.max());
    std::printf("  %5.1f  %7.5f  %7.5f  %7.5f  %7.5f  %7.5f  %7.5f\n", th, mc.mean.r, mc.mean.g,
                mc.mean.b, mc.std_error.g, q.integral.g, lobe.albedo(w).y);
  }
  std::printf("\nwhite furnace   max albedo %.5f  %s\n", furnace,
              furnace <= 1.0 + 1e-3 ? "ok (<= 1)" : "FAIL (> 1)");

  std::printf("\nchi-square (%llu samples, 50x100 cells, significance 0.01)\n",
              static_cast<unsigned long long>(o.samples));
  std::vector<std::pair<std::string, Vec3>> incident = {
      {"30deg", direction_at(M_PI / 6)},
      {"60deg", direction_at(M_PI / 3)},
      {"grazing", normalize(Vec3{0.5f, 0.5f, 0.001f})}};
  if (f & kLobeTransmit) incident.push_back({"inside60", {0.866f, 0, -0.5f}});
  for (const auto& [name, w] : incident) {
    Chi2Options co;
    co.samples = o.samples;
    co.mode = mode;
    co.n_tests = static_cast<int>(incident.size());
    Chi2Result r = chi2_test(lobe, w, co);
    std::printf("  %-9s %s  %s\n", name.c_str(), r.passed ? "ok  " : "FAIL", r.message.c_str());
  }
  ConsistencyResult c = check_consistency(lobe, direction_at(0.7), o.samples / 4, 3, mode);
  std::printf("\nconsistency     %llu samples: %llu weight, %llu pdf, %llu invalid mismatches "
              "(max rel err %.2g)\n",
              static_cast<unsigned long long>(c.valid),
              static_cast<unsigned long long>(c.weight_mismatch),
              static_cast<unsigned long long>(c.pdf_mismatch),
              static_cast<unsigned long long>(c.invalid_values), c.max_weight_rel_err);
  ReciprocityResult rr = check_reciprocity(lobe, pc.eta_below, o.samples / 4, 5);
  std::printf("reciprocity     %llu pairs: %llu violations, %llu mode violations (max rel err "
              "%.2g)\n",
              static_cast<unsigned long long>(rr.checked),
              static_cast<unsigned long long>(rr.violations),
              static_cast<unsigned long long>(rr.mode_violations), rr.max_rel_err);
  StressResult s;
  stress_grid(lobe, pc.eta_below, s);
  stress_invalid_inputs(lobe, s);
  stress_random(lobe, o.samples, 7, s);
  std::printf("stress          %llu calls: %llu NaN/Inf/negative outputs, %llu bad answers to "
              "invalid input, %llu unsampled (eval > 0, pdf = 0)\n",
              static_cast<unsigned long long>(s.calls),
              static_cast<unsigned long long>(s.invalid_outputs),
              static_cast<unsigned long long>(s.invalid_inputs),
              static_cast<unsigned long long>(s.unsampled_mass));
  if (!s.first_failure.empty()) std::printf("  first: %s\n", s.first_failure.c_str());
}

// Writes the data files and the gnuplot script, and runs gnuplot. Returns false on failure.
bool plot(const Options& o, const Subject& pc, const LobeView& lobe, Transport mode) {
  std::string polar = o.plot + "_polar.dat", alb = o.plot + "_albedo.dat";
  const double views[] = {0, 30, 60, 80};
  {
    std::ofstream d(polar);
    for (double v : views) {
      Vec3 wo = direction_at(v * M_PI / 180.0);
      d << "# view " << v << " deg: x y (radius = luminance of f*|cos| in the plane)\n";
      for (int k = 0; k <= 720; ++k) {
        double a = -M_PI + 2 * M_PI * k / 720.0; // angle from +z, signed in the x-z plane
        Vec3 wi{float(std::sin(a)), 0.0f, float(std::cos(a))};
        float r = lum(lobe.eval(wo, wi, mode).value);
        d << r * std::sin(a) << " " << r * std::cos(a) << "\n";
      }
      d << "\n\n";
    }
    std::ofstream da(alb);
    da << "# theta mc_r mc_g mc_b quad_lum\n";
    for (int th = 0; th <= 89; th += 2) {
      Vec3 w = direction_at(th * M_PI / 180.0);
      AlbedoEstimate mc =
          albedo_mc(lobe, w, std::min<uint64_t>(o.samples, 50000), 1, Transport::Importance);
      QuadratureResult q = albedo_quadrature(lobe, w, Transport::Importance);
      da << th << " " << mc.mean.r << " " << mc.mean.g << " " << mc.mean.b << " "
         << 0.2126 * q.integral.r + 0.7152 * q.integral.g + 0.0722 * q.integral.b << "\n";
    }
  }
  std::string gp = o.plot + ".gp";
  {
    std::ofstream g(gp);
    g << "set terminal pngcairo size 900,700 noenhanced\n"
      << "set output '" << o.plot << "_polar.png'\n"
      << "set title \"" << pc.name << ": f*|cos| in the plane of incidence (view from +x)\"\n"
      << "set size ratio -1\nset grid\nset xzeroaxis\nset key outside right\n"
      << "plot for [i=0:3] '" << polar << "' index i with lines lw 2 title sprintf('view %d deg', "
      << "word('0 30 60 80', i+1) + 0)\n"
      << "set output '" << o.plot << "_albedo.png'\n"
      << "set title \"" << pc.name << ": directional albedo\"\n"
      << "set size noratio\nset xlabel 'view angle theta (deg)'\nset ylabel 'albedo'\n"
      << "set yrange [0:*]\n"
      << "plot '" << alb << "' using 1:2 with lines lc rgb 'red' title 'MC r', "
      << "'' using 1:3 with lines lc rgb 'green' title 'MC g', "
      << "'' using 1:4 with lines lc rgb 'blue' title 'MC b', "
      << "'' using 1:5 with points pt 7 lc rgb 'black' title 'quadrature (luminance)'\n";
  }
  std::string cmd = "gnuplot '" + gp + "'";
  if (std::system(cmd.c_str()) != 0) {
    std::fprintf(stderr, "lobe brdf: gnuplot failed (%s)\n", cmd.c_str());
    return false;
  }
  std::printf("\nplots: %s_polar.png %s_albedo.png\n", o.plot.c_str(), o.plot.c_str());
  return true;
}

// Compiles --shader with its --param values; null with the diagnostics in `err`.
std::unique_ptr<ShaderLobe> shader_lobe(const Options& o, std::string& err) {
  ShadingSystem ss;
  ss.options().include_dirs = o.include_dirs;
  if (std::string stdlib = lobe::stdlib_shader_dir(); !stdlib.empty())
    ss.options().include_dirs.push_back(stdlib);
  ShaderGroup g;
  ShaderGroup::Layer layer{o.shader, "material", {}};
  for (size_t i = 0; i + 1 < o.params.size(); i += 2)
    layer.values.push_back({"", o.params[i], o.params[i + 1]});
  g.layers.push_back(layer);
  DiagnosticList diags;
  std::shared_ptr<const Material> m = ss.compile(g, diags);
  for (const Diagnostic& d : diags) err += d.text + "\n";
  if (!m) {
    if (err.empty()) err = "lobe brdf: cannot compile shader '" + o.shader + "'\n";
    return nullptr;
  }
  if (!err.empty()) std::fprintf(stderr, "%s", err.c_str());
  err.clear();
  return std::make_unique<ShaderLobe>(std::move(m));
}

int run_brdf(int argc, char** argv) {
  Options o;
  CLI::App app{"Inspect a closure: report, plots, and eval/sample/albedo queries", "lobe brdf"};
  auto* expr = app.add_option("expr", o.expr,
                              "closure call, e.g. 'conductor_bsdf(N, U, 0.2, 0.2, "
                              "color(0.2,0.9,1.1), color(3.9,2.4,2.2), \"ggx\")'");
  auto* shader = app.add_option("--shader", o.shader,
                                "a material shader instead (name on the search path, incl. "
                                "stdlib_shaders/, or a file)");
  expr->excludes(shader);
  app.add_option("--param", o.params, "instance value for --shader: NAME VALUE (repeatable)")
      ->expected(2)
      ->allow_extra_args(false);
  app.add_option("-I", o.include_dirs, "search and #include directory for --shader");
  app.add_option("--samples", o.samples, "samples for Monte Carlo and chi-square");
  app.add_option("--plot", o.plot, "write PREFIX_polar.png and PREFIX_albedo.png (gnuplot)");
  app.add_option("--eval", o.evals, "query: wo_x,wo_y,wo_z,wi_x,wi_y,wi_z (repeatable)");
  app.add_option("--sample", o.samples_u, "query: u1,u2,u3 (repeatable), from --wo/--theta");
  app.add_option("--albedo", o.albedo_angles, "query: albedo at these view angles (degrees)");
  app.add_option("--wo", o.wo_text, "view direction x,y,z for --sample");
  app.add_option("--theta", o.theta, "view angle in degrees for --sample (default 45)");
  app.add_option("--format", o.format, "query output: csv or json")
      ->check(CLI::IsMember({"csv", "json"}));
  app.add_option("--mode", o.mode, "transport mode: radiance or importance")
      ->check(CLI::IsMember({"radiance", "importance"}));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (o.expr.empty() == o.shader.empty()) {
    std::fprintf(stderr, "lobe brdf: give a closure call or --shader NAME\n%s", app.help().c_str());
    return 2;
  }
  // Angles and directions are checked before anything is computed from them.
  if (!std::isfinite(o.theta) || o.theta < 0 || o.theta > 180) {
    std::fprintf(stderr, "lobe brdf: --theta must be an angle in [0, 180] degrees, not %g\n",
                 o.theta);
    return 1;
  }
  for (double th : o.albedo_angles)
    if (!std::isfinite(th) || th < 0 || th > 180) {
      std::fprintf(stderr, "lobe brdf: --albedo angles must lie in [0, 180] degrees, not %g\n", th);
      return 1;
    }
  if (o.samples == 0) {
    std::fprintf(stderr, "lobe brdf: --samples must be at least 1\n");
    return 1;
  }
  std::unique_ptr<LobeView> owned;
  Subject subject;
  if (!o.shader.empty()) {
    std::string err;
    std::unique_ptr<ShaderLobe> sl = shader_lobe(o, err);
    if (!sl) {
      std::fprintf(stderr, "%s", err.c_str());
      return 1;
    }
    subject.name = sl->describe();
    if (subject.name.empty()) subject.name = "(no closure)";
    subject.name = o.shader + ": " + subject.name;
    owned = std::move(sl);
  } else {
    ExprResult r = parse_closure_expr(o.expr);
    if (!r.closure) {
      print_expr_error(o.expr, r.error);
      return 1;
    }
    if (!closures::has_implementation(r.closure->params.id())) {
      std::fprintf(stderr, "lobe brdf: error: '%s' has no implementation in the closure library\n",
                   r.closure->key.c_str());
      return 1;
    }
    subject.name = r.closure->key;
    if (const char* w = closures::param_warning(r.closure->params.id(), r.closure->params.data()))
      subject.note = w;
    subject.eta_below = r.closure->eta_below;
    owned = std::make_unique<ClosureLobe>(r.closure->params, r.closure->strings);
  }
  const LobeView& lobe = *owned;
  // A closure reading a data file (measured_bsdf) that does not load has no lobe: asked about
  // it, that is an error, not a report of zeros.
  lobe.eval(direction_at(0.5), direction_at(0.5), Transport::Radiance);
  if (std::vector<std::string> bad = lobe::closure_data_errors(); !bad.empty()) {
    std::fprintf(stderr, "lobe brdf: error: %s\n", bad.front().c_str());
    return 1;
  }
  Transport mode = o.mode == "importance" ? Transport::Importance : Transport::Radiance;
  Vec3 wo = direction_at(o.theta * M_PI / 180.0);
  if (!o.wo_text.empty()) {
    std::vector<double> v = numbers(o.wo_text);
    if (v.size() != 3) {
      std::fprintf(stderr, "lobe brdf: --wo wants x,y,z\n");
      return 2;
    }
    if (!finite_direction(v, 0)) {
      std::fprintf(stderr, "lobe brdf: --wo must be finite and non-zero: '%s'\n",
                   o.wo_text.c_str());
      return 1;
    }
    wo = normalize(vec(v, 0));
  }
  if (!o.evals.empty() || !o.samples_u.empty() || !o.albedo_angles.empty())
    return run_query(o, lobe, wo, mode);
  report(o, subject, lobe, mode);
  if (!o.plot.empty() && !plot(o, subject, lobe, mode)) return 1;
  return 0;
}

} // namespace

LOBE_COMMAND(brdf, "inspect a closure: report, plots, eval/sample/albedo queries", run_brdf);

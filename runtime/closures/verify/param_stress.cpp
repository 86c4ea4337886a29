// Parameter-extreme stress of one closure, driven by the registry's parameter names and types.
#include "param_stress.h"

#include "closure_lobe.h"
#include "closure_registry.h"
#include "consistency.h"
#include "rng.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace lobe::verify {
namespace {

using registry::ArgType;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

std::string fmt(const char* name, float v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s=%g", name, v);
  return buf;
}

void float_variants(const closures::Params& base, const char* name,
                    std::vector<ParamVariant>& out) {
  const float values[] = {0.0f,        1e-7f, 5e-7f,     1e-4f,     1e-3f,     0.05f,
                          1.0f,        2.0f,  1 - 1e-5f, 1 + 1e-5f, 1 - 1e-4f, 1 + 1e-4f,
                          1.0f / 1.5f, 1.5f,  2.417f,    -1.0f,     1e6f,      kNaN};
  for (float v : values) {
    closures::Params p = base;
    p.set(name, v);
    out.push_back({fmt(name, v), p});
  }
}

void color_variants(const closures::Params& base, const char* name,
                    std::vector<ParamVariant>& out) {
  const Vec3 values[] = {{0, 0, 0},          {1, 1, 1},          {5, 10, 20},
                         {1e4f, 1e4f, 1e4f}, {kNaN, 0.5f, 0.5f}, {-1, 0.5f, 2}};
  for (const Vec3& v : values) {
    closures::Params p = base;
    p.set(name, v);
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s=(%g,%g,%g)", name, v.x, v.y, v.z);
    out.push_back({buf, p});
  }
}

// Anisotropic extremes of the notes: ax/ay in {0/0.5, 1e-4/1} (and swapped).
void pair_variants(const closures::Params& base, const registry::ClosureEntry& e,
                   std::vector<ParamVariant>& out) {
  static constexpr const char* kPairs[][2] = {
      {"roughness_x", "roughness_y"}, {"xalpha", "yalpha"}, {"ax", "ay"}};
  const float values[][2] = {{0, 0.5f}, {0.5f, 0}, {1e-4f, 1}, {1, 1e-4f}, {0, 0}};
  for (const auto& pr : kPairs) {
    bool found = false;
    for (const registry::ClosureParam& p : e.params) found |= std::string_view(p.name) == pr[0];
    if (!found) continue;
    for (const auto& v : values) {
      closures::Params p = base;
      p.set(pr[0], v[0]).set(pr[1], v[1]);
      out.push_back({fmt(pr[0], v[0]) + " " + fmt(pr[1], v[1]), p});
    }
  }
}

void other_variants(const closures::Params& base, const registry::ClosureParam& prm,
                    std::vector<ParamVariant>& out) {
  if (prm.type == ArgType::Int) {
    for (int v : {-1, 0, 1, 2, 3, 100}) {
      closures::Params p = base;
      p.set(prm.name, v);
      out.push_back({std::string(prm.name) + "=" + std::to_string(v), p});
    }
  } else if (prm.type == ArgType::String && std::string_view(prm.name) == "distribution") {
    for (const char* v : {"ggx", "beckmann", "", "nonsense"}) {
      closures::Params p = base;
      p.set(prm.name, v);
      out.push_back({std::string("distribution=\"") + v + "\"", p});
    }
  } else if (prm.type == ArgType::Vector && std::string_view(prm.name) != "N") {
    const Vec3 values[] = {{0, 0, 0}, {kNaN, 0, 0}, {0, 0, 1}, {0, 0, -3}, {0.5f, 0.5f, 0.5f}};
    for (const Vec3& v : values) {
      closures::Params p = base;
      p.set(prm.name, v);
      char buf[96];
      std::snprintf(buf, sizeof buf, "%s=(%g,%g,%g)", prm.name, v.x, v.y, v.z);
      out.push_back({buf, p});
    }
  }
}

} // namespace

std::vector<ParamVariant> param_variants(const closures::Params& base) {
  const registry::ClosureEntry& e = registry::closures()[base.id()];
  std::vector<ParamVariant> out;
  for (const registry::ClosureParam& prm : e.params) {
    if (prm.type == ArgType::Float)
      float_variants(base, prm.name, out);
    else if (prm.type == ArgType::Color)
      color_variants(base, prm.name, out);
    else
      other_variants(base, prm, out);
  }
  pair_variants(base, e, out);
  return out;
}

NormalCheck check_normals(const closures::Params& base, uint64_t pairs, uint64_t seed) {
  NormalCheck r;
  ClosureLobe ref(base);
  auto with_n = [&](const Vec3& n) {
    closures::Params p = base;
    p.set("N", n);
    return ClosureLobe(p);
  };
  const Vec3 degenerate[] = {{0, 0, 0}, {kNaN, 0, 1}, {kNaN, kNaN, kNaN}};
  const Vec3 unnormalised[] = {{0, 0, 2}, {0, 0, 1e-3f}, {0, 0, 1e5f}};
  Pcg32 rng(seed);
  for (uint64_t k = 0; k < pairs; ++k) {
    Vec3 wo = uniform_sphere(rng.next_double(), rng.next_double());
    Vec3 wi = uniform_sphere(rng.next_double(), rng.next_double());
    Vec3 u = rng.next_vec3();
    for (const Vec3& n : degenerate) {
      ClosureLobe l = with_n(n);
      BsdfEval e = l.eval(wo, wi, Transport::Radiance);
      if (!is_zero(e.value) || e.pdf != 0 || l.pdf(wo, wi) != 0 ||
          l.sample(wo, u, Transport::Radiance)) {
        ++r.degenerate_violations;
        if (r.first_failure.empty()) r.first_failure = "degenerate N gave a value or a sample";
      }
    }
    BsdfEval e0 = ref.eval(wo, wi, Transport::Radiance);
    for (const Vec3& n : unnormalised) {
      BsdfEval e = with_n(n).eval(wo, wi, Transport::Radiance);
      double err = std::max(rel_diff(e.pdf, e0.pdf),
                            rel_diff(max_component(e.value), max_component(e0.value)));
      if (err > 1e-4) {
        ++r.unnormalised_mismatch;
        if (r.first_failure.empty())
          r.first_failure = "unnormalised N (length " + std::to_string(length(n)) +
                            ") changed eval by " + std::to_string(err);
      }
    }
  }
  return r;
}

StressResult stress_params(const closures::Params& base, double eta_below, uint64_t random,
                           uint64_t seed) {
  StressResult total;
  for (const ParamVariant& v : param_variants(base)) {
    ClosureLobe l(v.params);
    StressResult r;
    stress_grid(l, eta_below, r);
    stress_invalid_inputs(l, r);
    if (random) stress_random(l, random, seed, r);
    if (!r.first_failure.empty()) r.first_failure = "[" + v.name + "] " + r.first_failure;
    total.merge(r);
  }
  return total;
}

} // namespace lobe::verify

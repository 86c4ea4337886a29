// A small slice of BSDF_NOTES' stress grid over every BSDF registry entry: extreme
// roughness, IOR, angles, normals and random numbers must give finite, non-negative outputs,
// and a sample always has pdf > 0. (The full grid is the verify suite's.)
#include "closure_registry.h"
#include "closures.h"
#include "params.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace lobe::closures {
namespace {

bool has_param(const registry::ClosureEntry& e, const char* name) {
  for (const auto& p : e.params)
    if (std::string(p.name) == name) return true;
  return false;
}

void expect_sane(const Params& p, const Vec3& wo, const Vec3& wi, const Vec3& u,
                 const std::string& what) {
  BsdfEval e = eval(p.id(), p.data(), wo, wi);
  ASSERT_TRUE(is_finite(e.value) && e.value.x >= 0 && e.value.y >= 0 && e.value.z >= 0) << what;
  ASSERT_TRUE(std::isfinite(e.pdf) && e.pdf >= 0) << what;
  auto s = sample(p.id(), p.data(), wo, u);
  if (s) {
    ASSERT_TRUE(is_finite(s->weight) && s->weight.x >= 0 && s->weight.y >= 0) << what;
    ASSERT_TRUE(std::isfinite(s->pdf) && s->pdf > 0) << what;
    ASSERT_TRUE(is_finite(s->wi)) << what;
  }
  Color3 a = albedo(p.id(), p.data(), wo);
  ASSERT_TRUE(is_finite(a) && a.x >= 0) << what;
}

TEST(StressSmoke, ExtremeInputsStayFinite) {
  const float alphas[] = {0.0f, 1e-7f, 5e-7f, 1e-4f, 1e-3f, 0.05f, 1.0f, 2.0f};
  const float etas[] = {1.0f, 1.00001f, 0.99999f, 1.0f / 1.5f, 1.5f, 2.417f};
  const float cosines[] = {0.0f, -0.0f, 1e-8f, -1e-8f, 1e-4f, 0.5f, -0.5f, 1.0f - 1e-7f, 1.0f};
  const Vec3 us[] = {
      {0, 0, 0}, {0x1.fffffep-1f, 0x1.fffffep-1f, 0x1.fffffep-1f}, {0.3f, 0.9f, 0.5f}};
  const Vec3 normals[] = {{0, 0, 1}, {0, 0, 0}, {0, 0, 3}, {NAN, 0, 1}};
  for (const registry::ClosureEntry& e : registry::closures()) {
    if (!(e.flags & (registry::kReflect | registry::kTransmit)) ||
        std::string(e.key) == "measured_bsdf")
      continue;
    for (float a : alphas) {
      for (float eta : etas) {
        for (const Vec3& n : normals) {
          Params p(e.key);
          p.set("N", n);
          for (const char* k : {"xalpha", "yalpha", "alpha", "roughness_x", "roughness_y",
                                "roughness", "ax", "ay", "sigma"})
            if (has_param(e, k)) p.set(k, a);
          for (const char* k : {"eta", "ior"})
            if (has_param(e, k)) p.set(k, eta);
          if (has_param(e, "exponent")) p.set("exponent", a * 1000.0f);
          if (has_param(e, "refract")) p.set("refract", 2);
          if (has_param(e, "transmission_tint")) p.set("transmission_tint", 1.0f);
          if (has_param(e, "extinction")) p.set("extinction", Vec3{1e4f, 5.0f, 0.0f});
          for (float co : cosines) {
            for (float ci : cosines) {
              Vec3 wo{std::sqrt(std::max(0.0f, 1 - co * co)), 0, co};
              Vec3 wi{-std::sqrt(std::max(0.0f, 1 - ci * ci)) * 0.6f,
                      std::sqrt(std::max(0.0f, 1 - ci * ci)) * 0.8f, ci};
              for (const Vec3& u : us)
                expect_sane(p, wo, wi, u,
                            std::string(e.key) + " a=" + std::to_string(a) +
                                " eta=" + std::to_string(eta) + " co=" + std::to_string(co) +
                                " ci=" + std::to_string(ci));
            }
          }
        }
      }
    }
  }
}

} // namespace
} // namespace lobe::closures

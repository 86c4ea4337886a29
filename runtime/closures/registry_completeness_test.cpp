// Every registry entry has an implementation (a lobe in dispatch.h, or handling in
// Bsdf::build for emission/transparency/holdout/background/debug/layer), at run time; the
// static_asserts generated in dispatch.h check the same at compile time (every BSDF entry has
// a Closure<> with a lobe, every Closure<> a registry row with its layout). Also: each BSDF
// lobe's flags agree with its registry flags, and every entry with bitcode names its kernels.
#include "closure_registry.h"
#include "closures.h"
#include "params.h"

#include <string>

#include <gtest/gtest.h>

namespace lobe::closures {
namespace {

TEST(RegistryCompleteness, EveryEntryHasAnImplementation) {
  int n = 0;
  for (const registry::ClosureEntry& e : registry::closures()) {
    EXPECT_TRUE(has_implementation(registry::id_of(e.key))) << e.key;
    ++n;
  }
  EXPECT_EQ(n, closure_id::kCount);
  EXPECT_FALSE(has_implementation(-1));
  EXPECT_FALSE(has_implementation(n));
}

TEST(RegistryCompleteness, LobeFlagsAgreeWithRegistry) {
  for (const registry::ClosureEntry& e : registry::closures()) {
    int id = registry::id_of(e.key);
    if (!(e.flags & (registry::kReflect | registry::kTransmit)) || id == closure_id::measured_bsdf)
      continue;
    Params p(e.key);
    p.set("N", Vec3{0, 0, 1});
    if (id == closure_id::dielectric_bsdf || id == closure_id::generalized_schlick_bsdf)
      p.set("transmission_tint", 1.0f);
    if (id == closure_id::microfacet) p.set("refract", 2).set("eta", 1.5f);
    uint32_t f = lobe_flags(id, p.data());
    ASSERT_NE(f, 0u) << e.key;
    EXPECT_EQ((f & kLobeReflect) != 0, (e.flags & registry::kReflect) != 0) << e.key;
    EXPECT_EQ((f & kLobeTransmit) != 0, (e.flags & registry::kTransmit) != 0) << e.key;
    EXPECT_EQ((f & kLobeSpecular) != 0,
              (e.flags & registry::kDelta) != 0 || id == closure_id::dielectric_bsdf ||
                  id == closure_id::microfacet || id == closure_id::generalized_schlick_bsdf ||
                  id == closure_id::conductor_bsdf)
        << e.key; // rough lobes default to roughness 0: delta
  }
}

// Kernel symbols: "lobe_closure_<key>_<fn>" for every BSDF entry with bitcode, none for the
// others (measured_bsdf is native-only).
TEST(RegistryCompleteness, KernelSymbolsFollowTheKeys) {
  for (const registry::ClosureEntry& e : registry::closures()) {
    int id = registry::id_of(e.key);
    const char* s = registry::kernel_symbol(id, registry::Kernel::sample);
    bool bsdf = (e.flags & (registry::kReflect | registry::kTransmit)) != 0;
    if (!bsdf || id == closure_id::measured_bsdf) {
      EXPECT_EQ(s, nullptr) << e.key;
      continue;
    }
    ASSERT_NE(s, nullptr) << e.key;
    EXPECT_EQ(std::string(s), "lobe_closure_" + std::string(e.key) + "_sample");
  }
  EXPECT_STREQ(registry::kernel_symbol(closure_id::conductor_bsdf, registry::Kernel::pdf),
               "lobe_closure_conductor_bsdf_pdf");
  EXPECT_EQ(registry::kernel_symbol(-1, registry::Kernel::eval), nullptr);
}

} // namespace
} // namespace lobe::closures

// Every registry entry has an implementation (a lobe in dispatch.h, or handling in
// Bsdf::build for emission/transparency/holdout/background/debug/layer), and every
// implementation names a registry entry (static_asserts in params.h make the converse a
// compile error). Also: each BSDF lobe's flags agree with its registry flags.
#include "closure_registry.h"
#include "closures.h"
#include "params.h"

#include <gtest/gtest.h>

namespace lobe::closures {
namespace {

TEST(RegistryCompleteness, EveryEntryHasAnImplementation) {
  int n = 0;
  for (const registry::ClosureEntry& e : registry::closures()) {
    EXPECT_TRUE(has_implementation(registry::id_of(e.key))) << e.key;
    ++n;
  }
  EXPECT_EQ(n, 30);
  EXPECT_FALSE(has_implementation(-1));
  EXPECT_FALSE(has_implementation(n));
}

TEST(RegistryCompleteness, LobeFlagsAgreeWithRegistry) {
  for (const registry::ClosureEntry& e : registry::closures()) {
    int id = registry::id_of(e.key);
    if (!(e.flags & (registry::kReflect | registry::kTransmit)) || id == kMeasuredId) continue;
    Params p(e.key);
    p.set("N", Vec3{0, 0, 1});
    if (id == kDielectricId || id == kGeneralizedSchlickId) p.set("transmission_tint", 1.0f);
    if (id == kMicrofacetId) p.set("refract", 2).set("eta", 1.5f);
    uint32_t f = lobe_flags(id, p.data());
    ASSERT_NE(f, 0u) << e.key;
    EXPECT_EQ((f & kLobeReflect) != 0, (e.flags & registry::kReflect) != 0) << e.key;
    EXPECT_EQ((f & kLobeTransmit) != 0, (e.flags & registry::kTransmit) != 0) << e.key;
    EXPECT_EQ((f & kLobeSpecular) != 0, (e.flags & registry::kDelta) != 0 || id == kDielectricId ||
                                            id == kMicrofacetId || id == kGeneralizedSchlickId ||
                                            id == kConductorId)
        << e.key; // rough lobes default to roughness 0: delta
  }
}

} // namespace
} // namespace lobe::closures

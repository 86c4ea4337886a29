// Registry invariants: unique keys, keyword rules, and the parameter-block layout rule
// (checked against offsets worked out by hand).
#include "closure_registry.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace lobe::registry {
namespace {

TEST(ClosureRegistry, KeysAreUniqueAndIdsMatchOrder) {
  std::set<std::string> keys;
  int i = 0;
  for (const ClosureEntry& e : closures()) {
    EXPECT_TRUE(keys.insert(e.key).second) << e.key;
    EXPECT_EQ(id_of(e.key), i) << e.key;
    EXPECT_EQ(find_by_key(e.key), &e);
    ++i;
  }
  EXPECT_EQ(id_of("no_such_closure"), -1);
  EXPECT_EQ(find_by_key("no_such_closure"), nullptr);
}

TEST(ClosureRegistry, KeywordsFollowPositionalsAndHaveDefaults) {
  for (const ClosureEntry& e : closures()) {
    bool seen_keyword = false;
    for (const ClosureParam& p : e.params) {
      if (p.keyword) {
        seen_keyword = true;
        EXPECT_NE(p.default_value, nullptr) << e.key << "." << p.name;
      } else {
        EXPECT_FALSE(seen_keyword) << e.key << ": positional after keyword " << p.name;
      }
    }
  }
}

TEST(ClosureRegistry, OverloadsDifferInPositionalCount) {
  auto positional = [](const ClosureEntry& e) {
    int n = 0;
    for (const ClosureParam& p : e.params) n += p.keyword ? 0 : 1;
    return n;
  };
  for (const ClosureEntry& a : closures())
    for (const ClosureEntry& b : closures())
      if (&a != &b && std::string(a.name) == b.name) {
        EXPECT_NE(positional(a), positional(b)) << a.key << " vs " << b.key;
      }
}

TEST(ClosureRegistry, OscNamesPresent) {
  for (const char* k : {"diffuse",
                        "oren_nayar",
                        "translucent",
                        "phong",
                        "ward",
                        "microfacet",
                        "reflection",
                        "refraction",
                        "transparent",
                        "emission",
                        "background",
                        "oren_nayar_diffuse_bsdf",
                        "burley_diffuse_bsdf",
                        "dielectric_bsdf",
                        "conductor_bsdf",
                        "generalized_schlick_bsdf",
                        "translucent_bsdf",
                        "transparent_bsdf",
                        "sheen_bsdf",
                        "uniform_edf",
                        "layer",
                        "holdout",
                        "debug"})
    EXPECT_GE(id_of(k), 0) << k;
}

// microfacet(string dist, N, U, xalpha, yalpha, eta, int refract, "energy_compensation",
// "label"): pointer at 0, N at 8..20, U at 20..32, floats 32/36/40, int 44, int 48, pointer
// aligned up to 56, size 64.
TEST(ClosureRegistry, MicrofacetLayoutByHand) {
  const ClosureEntry* e = find_by_key("microfacet");
  ASSERT_NE(e, nullptr);
  const size_t expected[] = {0, 8, 20, 32, 36, 40, 44, 48, 56};
  ASSERT_EQ(e->params.size(), std::size(expected));
  for (size_t i = 0; i < std::size(expected); ++i)
    EXPECT_EQ(param_offset(e->params, i), expected[i]) << i;
  EXPECT_EQ(param_block_size(e->params), 64u);
}

// diffuse(N, "label"): N at 0, label at 16 (12 rounded up to 8), size 24.
TEST(ClosureRegistry, DiffuseLayoutByHand) {
  const ClosureEntry* e = find_by_key("diffuse");
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(param_offset(e->params, 0), 0u);
  EXPECT_EQ(param_offset(e->params, 1), 16u);
  EXPECT_EQ(param_block_size(e->params), 24u);
  EXPECT_EQ(param_block_size(find_by_key("holdout")->params), 0u);
}

} // namespace
} // namespace lobe::registry

// Shared settings and helpers of the closure property suites. The same test sources build
// twice: closure_properties_test (quick level, default suite) and closure_properties_heavy_test
// (full grids and 1e6-sample chi-square, CTest label `heavy`), selected by LOBE_VERIFY_FULL.
#pragma once

#include "closure_lobe.h"
#include "closure_registry.h"
#include "configs.h"

#include <string>
#include <vector>

namespace lobe::verify::suite {

struct Settings {
  Level level;
  uint64_t chi2_samples;
  double chi2_cell_tolerance; // expected samples of integration error per cell
  uint64_t consistency_samples;
  uint64_t albedo_samples;
  uint64_t quadrature_evals;
  uint64_t reciprocity_pairs;
  uint64_t stress_random;
  uint64_t param_stress_random;
};

// Test-name prefixes differ between the two executables, so CTest sees distinct names.
// (LOBE_TEST / LOBE_INSTANTIATE expand the prefix before gtest pastes it.)
#ifdef LOBE_VERIFY_FULL
#define LOBE_SUITE_PREFIX Heavy
#else
#define LOBE_SUITE_PREFIX Quick
#endif
#define LOBE_CAT2(a, b) a##b
#define LOBE_CAT(a, b) LOBE_CAT2(a, b)
#define LOBE_TEST_(suite, name) TEST(suite, name)
#define LOBE_TEST(suite, name) LOBE_TEST_(LOBE_CAT(LOBE_SUITE_PREFIX, suite), name)
#define LOBE_INSTANTIATE_(prefix, ...) INSTANTIATE_TEST_SUITE_P(prefix, __VA_ARGS__)
#define LOBE_INSTANTIATE(...) LOBE_INSTANTIATE_(LOBE_SUITE_PREFIX, __VA_ARGS__)

#ifdef LOBE_VERIFY_FULL
inline constexpr Settings kSettings{Level::Full, 1000000, 0.05,   200000, 1000000,
                                    3000000,     100000,  100000, 1000};
#else
inline constexpr Settings kSettings{Level::Quick, 100000, 0.05, 10000, 50000,
                                    400000,       5000,   5000, 0};
#endif

// Registry ids of every testable closure (a BSDF entry with an implementation).
inline std::vector<int> testable_ids() {
  std::vector<int> ids;
  for (int id = 0; id < static_cast<int>(registry::closures().size()); ++id)
    if (is_testable(id)) ids.push_back(id);
  return ids;
}

// gtest parameter names: the registry key.
inline std::string key_name(int id) { return registry::closures()[id].key; }

} // namespace lobe::verify::suite

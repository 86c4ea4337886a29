// Parameter extremes for one registry entry (the notes' stress grid, applied by parameter name
// and type): every float through {0, 1e-7, 5e-7, 1e-4, 1e-3, 0.05, 1, 2, 1 +- 1e-5, 1 +- 1e-4,
// 1/1.5, 1.5, 2.417, -1, 1e6, NaN}, roughness pairs (0, 0.5) and (1e-4, 1), colours through
// {0, 1, (5, 10, 20), 1e4, NaN}, ints through {-1, 0, 1, 2, 3, 100}, distribution strings
// through {ggx, beckmann, "", "nonsense"}, tangents zero, NaN and parallel to N. Each variant
// runs the direction stress grid. Degenerate normals (zero, NaN) must give zero values and no
// sample; an unnormalised normal must give the same values as the normalised one.
#pragma once

#include "closures.h"
#include "stress.h"

#include <string>
#include <vector>

namespace lobe::verify {

struct ParamVariant {
  std::string name; // "roughness_x=1e-07"
  closures::Params params;
};

// Variants of `base` (parameters set one at a time), excluding the normal N.
std::vector<ParamVariant> param_variants(const closures::Params& base);

struct NormalCheck {
  uint64_t degenerate_violations = 0; // zero/NaN N gave a value or a sample
  uint64_t unnormalised_mismatch = 0; // N scaled or denormalised changed eval beyond 1e-4
  std::string first_failure;
  bool ok() const { return degenerate_violations == 0 && unnormalised_mismatch == 0; }
};

// The N checks for a block whose N is (0,0,1): zero, NaN and unnormalised replacements.
NormalCheck check_normals(const closures::Params& base, uint64_t pairs, uint64_t seed);

// Every variant through stress_grid (+ `random` random triples each); merged result.
StressResult stress_params(const closures::Params& base, double eta_below, uint64_t random,
                           uint64_t seed);

} // namespace lobe::verify

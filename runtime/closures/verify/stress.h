// The stress grid of BSDF_NOTES.md for one lobe: extreme directions (cos theta in {+-0,
// +-1e-8, 1e-4, 0.5, 1 - 1e-7, 1, nextafter(1, 2)}, horizon, below the surface, the exact
// mirror and refraction of wo), extreme random numbers (u in {0, 1/2, 1 - 2^-24}), invalid
// inputs (NaN, zero-length and infinite directions) and bulk random directions. Every output
// must be finite and >= 0, a returned sample must have pdf > 0, and invalid inputs must give
// zero values and no sample. (Parameter extremes are the adapters' business: closure_lobe.h.)
#pragma once

#include "lobe_view.h"

#include <cstdint>
#include <string>

namespace lobe::verify {

struct StressResult {
  uint64_t calls = 0;
  uint64_t invalid_outputs = 0; // NaN/Inf/negative values, samples with pdf <= 0 or bad wi
  uint64_t invalid_inputs = 0;  // NaN/zero input that gave a non-zero value or a sample
  uint64_t unsampled_mass = 0;  // eval > 0 where pdf == 0 on a non-delta lobe (MIS bias)
  std::string first_failure;
  bool ok() const { return invalid_outputs == 0 && invalid_inputs == 0; }
  void merge(const StressResult& o);
};

// The deterministic grid of extreme directions and random numbers. eta_below (the IOR below
// the surface relative to above) is used to build the exact refraction of wo.
void stress_grid(const LobeView& lobe, double eta_below, StressResult& out);
// NaN, zero-length and infinite wo / wi.
void stress_invalid_inputs(const LobeView& lobe, StressResult& out);
// `n` random (wo, wi, u) triples, directions uniform over the whole sphere.
void stress_random(const LobeView& lobe, uint64_t n, uint64_t seed, StressResult& out);

// One eval+pdf call and one sample call, checked against the contract (used by all three).
void stress_eval(const LobeView& lobe, const Vec3& wo, const Vec3& wi, StressResult& out);
void stress_sample(const LobeView& lobe, const Vec3& wo, const Vec3& u, StressResult& out);

} // namespace lobe::verify

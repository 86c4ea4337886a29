// The parameter grids the property suites run over, derived from the registry entry's
// parameter names so that a new closure is covered without anyone writing a test:
//   roughness pairs (roughness_x/y, xalpha/yalpha, ax/ay): alpha in {0.05, 0.125, 0.5} and
//     anisotropic (0.2, 0.05); a single `alpha` likewise; diffuse `roughness`/`sigma` in
//     {0, 0.5, 1}; `distribution` in {ggx, beckmann}; a float `eta`/`ior` in {1.5, 1/1.5};
//     microfacet `refract` in {0, 1, 2}; Phong `exponent` in {1, 20, 200};
//   incident directions at 0, 30, 60, 85 degrees and grazing ((0.5, 0.5, 0.001) normalised),
//     plus, for transmissive closures, from inside at 30 and 60 degrees (TIR for eta 1.5).
// The quick level (default suite) takes a small corner of each axis. docs/verification.md
// lists the resulting configurations.
#pragma once

#include "closures.h"

#include <string>
#include <vector>

namespace lobe::verify {

enum class Level { Quick, Full };

struct Incident {
  std::string name; // "30deg", "grazing", "inside60"
  Vec3 wo;
};

struct ClosureConfig {
  std::string name; // "conductor_bsdf ggx a=0.05"
  closures::Params params;
  double eta_below = 1.0; // IOR below the surface relative to above (reciprocity)
  bool lossless = false;  // a furnace config: albedo must stay >= 0.99
  std::vector<Incident> incident;
};

// True for entries the property suites cover: a BSDF (reflect/transmit flags) with an
// implementation in the closure library.
bool is_testable(int id);

// Every configuration for closure `id` at `level` (empty if the entry is not testable).
std::vector<ClosureConfig> configs_for(int id, Level level);

// Lossless furnace configurations (energy compensation on, Fresnel = 1): conductors with a
// huge extinction coefficient and generalised Schlick with f0 = f90 = 1, at every roughness.
std::vector<ClosureConfig> lossless_configs(Level level);

// The incident directions of a level; `inside` adds the ones below the surface.
std::vector<Incident> incident_set(Level level, bool inside);

} // namespace lobe::verify

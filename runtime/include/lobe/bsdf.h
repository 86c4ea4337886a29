// The flattened closure of one shading point, and what a light-transport integrator asks of it.
//
// A closure tree (sums and weights of components, layer()) is flattened into a list of
// weighted lobes. The mixture samples one lobe with probability proportional to
// luminance(weight x albedo) and reports the mixture's pdf (the selection-weighted sum over
// all non-delta lobes), so multiple importance sampling stays correct. Zero-weight lobes are
// never created.
//
// Conventions: all directions point away from the surface, world space, normalised. `wo` is
// towards the viewer (-I), `wi` towards the light. eval() returns f(wo, wi) * |cos(N, wi)|,
// already multiplied by the lobe weights. Delta lobes (perfect mirror/refraction) never
// contribute to eval()/pdf(); sample() returns them flagged kLobeSpecular, with `pdf` the
// discrete probability of having picked that lobe and `weight` the throughput factor.
// Nothing returned is ever NaN or Inf, and every value is >= 0.
#pragma once

#include "lobe/shading.h"
#include "lobe/vec.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace lobe {

enum class Transport : uint8_t { Radiance, Importance };

enum LobeFlags : uint32_t {
  kLobeReflect = 1u << 0,
  kLobeTransmit = 1u << 1,
  kLobeDiffuse = 1u << 2,
  kLobeGlossy = 1u << 3,
  kLobeSpecular = 1u << 4, // a delta lobe
};

// The result types and flags are the closure library's own: each lobe (runtime/closures/)
// returns them, in its local frame, and the Bsdf its weighted mixture in world space.
struct BsdfEval {
  Color3 value;  // f * |cos theta_i|, weighted
  float pdf = 0; // solid-angle pdf of sample() producing wi
};

// A lobe that has no sample for its inputs returns pdf 0 (the Bsdf: std::nullopt).
struct BsdfSample {
  Vec3 wi;
  Color3 weight;      // value / pdf (for delta lobes: the throughput factor)
  float pdf = 0;      // > 0 always
  uint32_t flags = 0; // LobeFlags of the lobe that was sampled
  float eta = 1;      // relative IOR crossed by a transmission sample (1 for reflection)
};

// The closure functions of one material, JIT-compiled (Material::closure_kernels()): opaque
// here, pass it to Bsdf::build. Its definition is internal (lobe/detail/closure_kernels.h).
struct ClosureKernels;

// One weighted lobe: a registry component plus its weight and a pointer to its parameter
// block (owned by the ShadingContext arena the closure was built in).
struct Lobe {
  int32_t id = -1;
  Color3 weight;
  const unsigned char* params = nullptr;
  float select_weight = 0; // luminance(weight * albedo(wo)), set by build()
  uint32_t flags = 0;      // LobeFlags of this lobe (set by build())
};

class Bsdf {
public:
  static constexpr int kMaxLobes = 16;
  // Room for one lobe set up by build() (its frame and the lobe's own constants).
  static constexpr size_t kLobeStateBytes = 256, kLobeStateAlign = 16;

  // Flattens `closure` (may be null: black) for a point with geometric normal `Ng`, viewed
  // from `wo`. Emission, transparency, holdout and debug components are collected separately.
  // `kernels` (may be null: the native library) evaluates and samples the lobes. Each lobe is
  // set up here, once (frame, parameter clamping, Fresnel averages), and eval/sample/albedo
  // read it.
  // `backfacing`: the point is seen from the back of its surface and the renderer turned the
  // shader's N and Ng to face the viewer (as OSL's testrender does). OSL's own closures then
  // take their eta across the side N faces (a shader passes 1/eta from inside, as OSL's do);
  // closures whose IOR is the object's inside over outside (MaterialX's dielectric_bsdf and
  // generalized_schlick_bsdf) are set up with N turned back to Ng's side (Ng: the surface's
  // outward geometric normal, not turned), so they stay physical, as testrender treats them.
  void build(const ClosureNode* closure, const Vec3& wo, const Vec3& Ng,
             const ClosureKernels* kernels = nullptr, bool backfacing = false);

  BsdfEval eval(const Vec3& wo, const Vec3& wi, Transport mode = Transport::Radiance) const;
  float pdf(const Vec3& wo, const Vec3& wi) const;
  // u: three uniform numbers in [0,1); the first selects the lobe and is re-used.
  std::optional<BsdfSample> sample(const Vec3& wo, const Vec3& u,
                                   Transport mode = Transport::Radiance) const;
  // Directional albedo estimate (sum over lobes of weight * albedo(wo)).
  Color3 albedo(const Vec3& wo) const;

  int lobe_count() const { return n_lobes_; }
  const Lobe& lobe(int i) const { return lobes_[i]; }
  bool has_non_delta() const;
  bool has_delta() const; // a perfect mirror or refraction lobe

  Color3 emission;     // radiance emitted towards wo
  Color3 transparency; // pass-through weight (transparent closures)
  Color3 holdout;
  Color3 background; // background() closure weight (environment shaders)
  const char* debug_tag = nullptr;
  Color3 debug_weight;

private:
  friend struct BsdfBuilder; // bsdf.cpp: flattens the closure tree into lobes_
  const void* state(int i) const { return states_[i]; }
  Color3 lobe_albedo(int i, const Vec3& wo) const;

  // Lobe slots not initialised on construction: build() writes the first n_lobes_, and the
  // rest are never read (a path's Bsdf is made on its stack; zeroing all slots showed).
  union Slots {
    Slots() {}
    Lobe& operator[](int i) { return at[i]; }
    const Lobe& operator[](int i) const { return at[i]; }
    Lobe at[kMaxLobes];
  };
  Slots lobes_;
  alignas(kLobeStateAlign) unsigned char states_[kMaxLobes][kLobeStateBytes];
  int n_lobes_ = 0;
  float total_select_ = 0;
  Vec3 ng_; // normalised geometric normal, (0,0,0) when unknown: no side test
  const ClosureKernels* kernels_ = nullptr;
  bool backfacing_ = false;
};

// Human-readable form of a closure tree in OSL's print format:
// `(w0, w1, w2) * name ((Nx, Ny, Nz), arg, "kw", value)`, terms joined by "\n\t+ ".
std::string closure_to_string(const ClosureNode* closure);

// The data files closures read (measured_bsdf's MERL tables) that failed to load, each once, in
// the order first tried: "measured_bsdf: cannot open measured BRDF 'x.binary'" (or a short
// header, a wrong size, NaN cells, ...).
// A closure whose file failed gives no lobe (it renders black), so a renderer reports these.
std::vector<std::string> closure_data_errors();

} // namespace lobe

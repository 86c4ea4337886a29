// Registry entries that are not BSDF lobes: Bsdf::build collects them into its fields
// (emission, transparency, holdout, background, debug) or combines closures with them
// (layer), and the media describe what lies under the surface (no surface contribution:
// Lobe renders no volumes or subsurface transport, docs/closures.md). Entries without
// parameters (emission(), transparent(), holdout(), background()) need nothing here.
#pragma once

#include "params.h"

namespace lobe::closures {

struct EmittanceParams {
  Color3 emittance;
};
struct DebugParams {
  Str tag;
};
struct LayerParams {
  const ClosureNode* top;
  const ClosureNode* base;
};
struct SubsurfaceParams {
  float eta, g;
  Color3 mfp, albedo;
  Str label;
};
struct AnisotropicVdfParams {
  Color3 albedo, extinction;
  float anisotropy;
  Str label;
};
struct MediumVdfParams {
  Color3 albedo;
  float transmission_depth;
  Color3 transmission_color;
  float anisotropy, ior;
  int priority;
  Str label;
};

// uniform_edf(emittance): radiance = weight * emittance.
template <> struct Closure<closure_id::uniform_edf> {
  using Params = EmittanceParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, emittance)};
};
// debug(tag): an AOV.
template <> struct Closure<closure_id::debug> {
  using Params = DebugParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, tag)};
};
// layer(top, base): the base attenuated by the top's albedo (bsdf.cpp).
template <> struct Closure<closure_id::layer> {
  using Params = LayerParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, top), offsetof(Params, base)};
};
template <> struct Closure<closure_id::subsurface> {
  using Params = SubsurfaceParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, eta), offsetof(Params, g),
                                        offsetof(Params, mfp), offsetof(Params, albedo),
                                        offsetof(Params, label)};
};
template <> struct Closure<closure_id::anisotropic_vdf> {
  using Params = AnisotropicVdfParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, albedo), offsetof(Params, extinction),
                                        offsetof(Params, anisotropy), offsetof(Params, label)};
};
template <> struct Closure<closure_id::medium_vdf> {
  using Params = MediumVdfParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, albedo),
                                        offsetof(Params, transmission_depth),
                                        offsetof(Params, transmission_color),
                                        offsetof(Params, anisotropy),
                                        offsetof(Params, ior),
                                        offsetof(Params, priority),
                                        offsetof(Params, label)};
};

} // namespace lobe::closures

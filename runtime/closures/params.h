// Parameter blocks of every closure as plain C++ structs, laid out exactly as the registry
// says (closure_registry.h: natural alignment, positional parameters then keywords). The
// static_asserts below check each struct against the registry table at compile time, so a
// registry edit that is not mirrored here does not build.
#pragma once

#include "closure_table.h"
#include "lobe/shading.h"
#include "lobe/vec.h"

#include <cstddef>

namespace lobe::closures {

using Str = const char*; // interned string (distribution names, labels, file names)

struct DiffuseParams {
  Vec3 N;
  Str label;
}; // diffuse, translucent
struct OrenNayarParams {
  Vec3 N;
  float sigma;
  Str label;
};
struct OrenNayarDiffuseParams {
  Vec3 N;
  Color3 albedo;
  float roughness;
  int energy_compensation;
  Str label;
};
struct AlbedoRoughnessParams {
  Vec3 N;
  Color3 albedo;
  float roughness;
  Str label;
};
struct AlbedoParams {
  Vec3 N;
  Color3 albedo;
  Str label;
}; // translucent_bsdf
struct PhongParams {
  Vec3 N;
  float exponent;
  Str label;
}; // phong, blinn_phong
struct WardParams {
  Vec3 N, T;
  float ax, ay;
  Str label;
};
struct MicrofacetParams {
  Str distribution;
  Vec3 N, U;
  float xalpha, yalpha, eta;
  int refract;
  int energy_compensation;
  Str label;
};
struct ReflectionParams {
  Vec3 N;
  float eta;
  Str label;
}; // reflection(N, eta), refraction
struct ConductorParams {
  Vec3 N, U;
  float roughness_x, roughness_y;
  Color3 ior, extinction;
  Str distribution;
  float thinfilm_thickness, thinfilm_ior;
  int energy_compensation;
  Str label;
};
struct DielectricParams {
  Vec3 N, U;
  Color3 reflection_tint, transmission_tint;
  float roughness_x, roughness_y, ior;
  Str distribution;
  float thinfilm_thickness, thinfilm_ior;
  int energy_compensation;
  Str label;
};
struct GeneralizedSchlickParams {
  Vec3 N, U;
  Color3 reflection_tint, transmission_tint;
  float roughness_x, roughness_y;
  Color3 f0, f90;
  float exponent;
  Str distribution;
  float thinfilm_thickness, thinfilm_ior;
  int energy_compensation;
  Str label;
};
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
struct ToonParams {
  Vec3 N;
  Color3 albedo, specular;
  float shininess;
  int bands;
  float softness;
  Str label;
};
struct MeasuredParams {
  Vec3 N;
  Str filename;
  Color3 tint;
  Str label;
};

struct SubsurfaceParams {
  float eta, g;
  Color3 mfp, albedo;
  Str label;
};
struct SubsurfaceBssrdfParams {
  Vec3 N;
  Color3 albedo;
  float transmission_depth;
  Color3 transmission_color;
  float anisotropy;
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

template <class P> const P& as_params(const unsigned char* p) {
  return *reinterpret_cast<const P*>(p);
}

// Registry ids, resolved at compile time.
#define LOBE_ID(name, key) inline constexpr int name = registry::table::index_of(key)
LOBE_ID(kDiffuseId, "diffuse");
LOBE_ID(kOrenNayarId, "oren_nayar");
LOBE_ID(kOrenNayarDiffuseId, "oren_nayar_diffuse_bsdf");
LOBE_ID(kBurleyId, "burley_diffuse_bsdf");
LOBE_ID(kTranslucentId, "translucent");
LOBE_ID(kTranslucentBsdfId, "translucent_bsdf");
LOBE_ID(kPhongId, "phong");
LOBE_ID(kBlinnPhongId, "blinn_phong");
LOBE_ID(kWardId, "ward");
LOBE_ID(kMicrofacetId, "microfacet");
LOBE_ID(kReflectionId, "reflection");
LOBE_ID(kRefractionId, "refraction");
LOBE_ID(kConductorId, "conductor_bsdf");
LOBE_ID(kDielectricId, "dielectric_bsdf");
LOBE_ID(kGeneralizedSchlickId, "generalized_schlick_bsdf");
LOBE_ID(kSheenId, "sheen_bsdf");
LOBE_ID(kTransparentId, "transparent");
LOBE_ID(kTransparentBsdfId, "transparent_bsdf");
LOBE_ID(kEmissionId, "emission");
LOBE_ID(kUniformEdfId, "uniform_edf");
LOBE_ID(kBackgroundId, "background");
LOBE_ID(kHoldoutId, "holdout");
LOBE_ID(kDebugId, "debug");
LOBE_ID(kLayerId, "layer");
LOBE_ID(kToonId, "toon");
LOBE_ID(kMeasuredId, "measured_bsdf");
LOBE_ID(kSubsurfaceId, "subsurface");
LOBE_ID(kSubsurfaceBssrdfId, "subsurface_bssrdf");
LOBE_ID(kAnisotropicVdfId, "anisotropic_vdf");
LOBE_ID(kMediumVdfId, "medium_vdf");
#undef LOBE_ID
static_assert(kDiffuseId >= 0 && kOrenNayarId >= 0 && kOrenNayarDiffuseId >= 0 && kBurleyId >= 0 &&
                  kTranslucentId >= 0 && kTranslucentBsdfId >= 0 && kPhongId >= 0 &&
                  kBlinnPhongId >= 0 && kWardId >= 0 && kMicrofacetId >= 0 && kReflectionId >= 0 &&
                  kRefractionId >= 0 && kConductorId >= 0 && kDielectricId >= 0 &&
                  kGeneralizedSchlickId >= 0 && kSheenId >= 0 && kTransparentId >= 0 &&
                  kTransparentBsdfId >= 0 && kEmissionId >= 0 && kUniformEdfId >= 0 &&
                  kBackgroundId >= 0 && kHoldoutId >= 0 && kDebugId >= 0 && kLayerId >= 0 &&
                  kToonId >= 0 && kMeasuredId >= 0 && kSubsurfaceId >= 0 &&
                  kSubsurfaceBssrdfId >= 0 && kAnisotropicVdfId >= 0 && kMediumVdfId >= 0,
              "every implementation names a registry entry");

// True if the registry entry `key` has exactly these parameter offsets and a block size that
// the struct fits.
template <size_t K>
constexpr bool layout_is(const char* key, const size_t (&offsets)[K], size_t struct_size) {
  int id = registry::table::index_of(key);
  if (id < 0) return false;
  auto params = registry::table::kClosures[id].params;
  if (params.size() != K) return false;
  for (size_t i = 0; i < K; ++i)
    if (registry::param_offset(params, i) != offsets[i]) return false;
  return registry::param_block_size(params) == (struct_size + 7) / 8 * 8;
}

#define O(S, f) offsetof(S, f)
static_assert(layout_is("diffuse", {O(DiffuseParams, N), O(DiffuseParams, label)},
                        sizeof(DiffuseParams)));
static_assert(layout_is("translucent", {O(DiffuseParams, N), O(DiffuseParams, label)},
                        sizeof(DiffuseParams)));
static_assert(layout_is("oren_nayar",
                        {O(OrenNayarParams, N), O(OrenNayarParams, sigma),
                         O(OrenNayarParams, label)},
                        sizeof(OrenNayarParams)));
static_assert(layout_is("oren_nayar_diffuse_bsdf",
                        {O(OrenNayarDiffuseParams, N), O(OrenNayarDiffuseParams, albedo),
                         O(OrenNayarDiffuseParams, roughness),
                         O(OrenNayarDiffuseParams, energy_compensation),
                         O(OrenNayarDiffuseParams, label)},
                        sizeof(OrenNayarDiffuseParams)));
static_assert(layout_is("burley_diffuse_bsdf",
                        {O(AlbedoRoughnessParams, N), O(AlbedoRoughnessParams, albedo),
                         O(AlbedoRoughnessParams, roughness), O(AlbedoRoughnessParams, label)},
                        sizeof(AlbedoRoughnessParams)));
static_assert(layout_is("sheen_bsdf",
                        {O(AlbedoRoughnessParams, N), O(AlbedoRoughnessParams, albedo),
                         O(AlbedoRoughnessParams, roughness), O(AlbedoRoughnessParams, label)},
                        sizeof(AlbedoRoughnessParams)));
static_assert(layout_is("translucent_bsdf",
                        {O(AlbedoParams, N), O(AlbedoParams, albedo), O(AlbedoParams, label)},
                        sizeof(AlbedoParams)));
static_assert(layout_is("phong",
                        {O(PhongParams, N), O(PhongParams, exponent), O(PhongParams, label)},
                        sizeof(PhongParams)));
static_assert(layout_is("blinn_phong",
                        {O(PhongParams, N), O(PhongParams, exponent), O(PhongParams, label)},
                        sizeof(PhongParams)));
static_assert(layout_is("ward",
                        {O(WardParams, N), O(WardParams, T), O(WardParams, ax), O(WardParams, ay),
                         O(WardParams, label)},
                        sizeof(WardParams)));
static_assert(layout_is("microfacet",
                        {O(MicrofacetParams, distribution), O(MicrofacetParams, N),
                         O(MicrofacetParams, U), O(MicrofacetParams, xalpha),
                         O(MicrofacetParams, yalpha), O(MicrofacetParams, eta),
                         O(MicrofacetParams, refract), O(MicrofacetParams, energy_compensation),
                         O(MicrofacetParams, label)},
                        sizeof(MicrofacetParams)));
static_assert(layout_is("reflection",
                        {O(ReflectionParams, N), O(ReflectionParams, eta),
                         O(ReflectionParams, label)},
                        sizeof(ReflectionParams)));
static_assert(layout_is("refraction",
                        {O(ReflectionParams, N), O(ReflectionParams, eta),
                         O(ReflectionParams, label)},
                        sizeof(ReflectionParams)));
static_assert(layout_is("conductor_bsdf",
                        {O(ConductorParams, N), O(ConductorParams, U),
                         O(ConductorParams, roughness_x), O(ConductorParams, roughness_y),
                         O(ConductorParams, ior), O(ConductorParams, extinction),
                         O(ConductorParams, distribution), O(ConductorParams, thinfilm_thickness),
                         O(ConductorParams, thinfilm_ior), O(ConductorParams, energy_compensation),
                         O(ConductorParams, label)},
                        sizeof(ConductorParams)));
static_assert(layout_is("dielectric_bsdf",
                        {O(DielectricParams, N), O(DielectricParams, U),
                         O(DielectricParams, reflection_tint),
                         O(DielectricParams, transmission_tint), O(DielectricParams, roughness_x),
                         O(DielectricParams, roughness_y), O(DielectricParams, ior),
                         O(DielectricParams, distribution), O(DielectricParams, thinfilm_thickness),
                         O(DielectricParams, thinfilm_ior),
                         O(DielectricParams, energy_compensation), O(DielectricParams, label)},
                        sizeof(DielectricParams)));
static_assert(layout_is(
    "generalized_schlick_bsdf",
    {O(GeneralizedSchlickParams, N), O(GeneralizedSchlickParams, U),
     O(GeneralizedSchlickParams, reflection_tint), O(GeneralizedSchlickParams, transmission_tint),
     O(GeneralizedSchlickParams, roughness_x), O(GeneralizedSchlickParams, roughness_y),
     O(GeneralizedSchlickParams, f0), O(GeneralizedSchlickParams, f90),
     O(GeneralizedSchlickParams, exponent), O(GeneralizedSchlickParams, distribution),
     O(GeneralizedSchlickParams, thinfilm_thickness), O(GeneralizedSchlickParams, thinfilm_ior),
     O(GeneralizedSchlickParams, energy_compensation), O(GeneralizedSchlickParams, label)},
    sizeof(GeneralizedSchlickParams)));
static_assert(layout_is("uniform_edf", {O(EmittanceParams, emittance)}, sizeof(EmittanceParams)));
static_assert(layout_is("debug", {O(DebugParams, tag)}, sizeof(DebugParams)));
static_assert(layout_is("layer", {O(LayerParams, top), O(LayerParams, base)}, sizeof(LayerParams)));
static_assert(layout_is("toon",
                        {O(ToonParams, N), O(ToonParams, albedo), O(ToonParams, specular),
                         O(ToonParams, shininess), O(ToonParams, bands), O(ToonParams, softness),
                         O(ToonParams, label)},
                        sizeof(ToonParams)));
static_assert(layout_is("measured_bsdf",
                        {O(MeasuredParams, N), O(MeasuredParams, filename), O(MeasuredParams, tint),
                         O(MeasuredParams, label)},
                        sizeof(MeasuredParams)));
static_assert(layout_is("subsurface",
                        {O(SubsurfaceParams, eta), O(SubsurfaceParams, g), O(SubsurfaceParams, mfp),
                         O(SubsurfaceParams, albedo), O(SubsurfaceParams, label)},
                        sizeof(SubsurfaceParams)));
static_assert(layout_is("subsurface_bssrdf",
                        {O(SubsurfaceBssrdfParams, N), O(SubsurfaceBssrdfParams, albedo),
                         O(SubsurfaceBssrdfParams, transmission_depth),
                         O(SubsurfaceBssrdfParams, transmission_color),
                         O(SubsurfaceBssrdfParams, anisotropy), O(SubsurfaceBssrdfParams, label)},
                        sizeof(SubsurfaceBssrdfParams)));
static_assert(layout_is("anisotropic_vdf",
                        {O(AnisotropicVdfParams, albedo), O(AnisotropicVdfParams, extinction),
                         O(AnisotropicVdfParams, anisotropy), O(AnisotropicVdfParams, label)},
                        sizeof(AnisotropicVdfParams)));
static_assert(layout_is("medium_vdf",
                        {O(MediumVdfParams, albedo), O(MediumVdfParams, transmission_depth),
                         O(MediumVdfParams, transmission_color), O(MediumVdfParams, anisotropy),
                         O(MediumVdfParams, ior), O(MediumVdfParams, priority),
                         O(MediumVdfParams, label)},
                        sizeof(MediumVdfParams)));
#undef O

} // namespace lobe::closures

// The closure table itself: every closure a shader can call, with its parameters, in id order.
//
// Kept in a header as constexpr data so that the runtime's C++ parameter structs can
// static_assert their layout against it (runtime/closures/params.h); everything else reads it
// through closure_registry.h. Columns of a ClosureParam: name, type, keyword?, keyword default
// (literal text), one-line doc. Every BSDF also accepts OSL's "label" keyword (kept, unused).
// Flags say what a closure contributes (see closure_registry.h).
#pragma once

#include "closure_registry.h"

namespace lobe::registry::table {

using T = ArgType;
inline constexpr const char* kLabelDoc = "lobe label for light path expressions (unused)";
#define LOBE_LABEL                                                                                 \
  { "label", T::String, true, "\"\"", kLabelDoc }
#define LOBE_LABEL_PRINTED                                                                         \
  { "label", T::String, true, "\"\"", kLabelDoc, true }
#define LOBE_EC(def)                                                                               \
  { "energy_compensation", T::Int, true, def, "1: Kulla-Conty multiple scattering" }
#define LOBE_THINFILM                                                                              \
  {"thinfilm_thickness", T::Float, true, "0", "thin film thickness in nm (accepted, ignored)"}, {  \
    "thinfilm_ior", T::Float, true, "1.5", "thin film IOR (accepted, ignored)"                     \
  }

inline constexpr ClosureParam kDiffuse[] = {{"N", T::Vector, false, nullptr, "shading normal"},
                                            LOBE_LABEL_PRINTED};
inline constexpr ClosureParam kNormalOnly[] = {{"N", T::Vector, false, nullptr, "shading normal"},
                                               LOBE_LABEL};
inline constexpr ClosureParam kOrenNayar[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"sigma", T::Float, false, nullptr, "roughness: std. dev. of facet slope angle, radians"},
    LOBE_LABEL};
inline constexpr ClosureParam kOrenNayarDiffuseBsdf[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"albedo", T::Color, false, nullptr, "single-scattering albedo"},
    {"roughness", T::Float, false, nullptr, "roughness in [0, 1]"},
    LOBE_EC("0"),
    LOBE_LABEL};
inline constexpr ClosureParam kNormalAlbedoRoughness[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"albedo", T::Color, false, nullptr, "albedo"},
    {"roughness", T::Float, false, nullptr, "roughness in [0, 1]"},
    LOBE_LABEL};
inline constexpr ClosureParam kNormalAlbedo[] = {{"N", T::Vector, false, nullptr, "shading normal"},
                                                 {"albedo", T::Color, false, nullptr, "albedo"},
                                                 LOBE_LABEL};
inline constexpr ClosureParam kPhong[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"exponent", T::Float, false, nullptr, "Phong exponent (>= 0)"},
    LOBE_LABEL_PRINTED};
inline constexpr ClosureParam kBlinnPhong[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"exponent", T::Float, false, nullptr, "Blinn-Phong exponent (>= 0)"},
    LOBE_LABEL};
inline constexpr ClosureParam kWard[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"T", T::Vector, false, nullptr, "tangent (x roughness direction)"},
    {"ax", T::Float, false, nullptr, "roughness along T"},
    {"ay", T::Float, false, nullptr, "roughness along N x T"},
    LOBE_LABEL};
inline constexpr ClosureParam kMicrofacet[] = {
    {"distribution", T::String, false, nullptr, "\"ggx\" or \"beckmann\""},
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"U", T::Vector, false, nullptr, "tangent (x roughness direction)"},
    {"xalpha", T::Float, false, nullptr, "roughness along U"},
    {"yalpha", T::Float, false, nullptr, "roughness along N x U"},
    {"eta", T::Float, false, nullptr, "relative IOR inside/outside"},
    {"refract", T::Int, false, nullptr, "0: reflect, 1: refract, 2: both"},
    LOBE_EC("1"),
    LOBE_LABEL};
inline constexpr ClosureParam kReflection[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"eta", T::Float, false, nullptr, "IOR for dielectric Fresnel; 0: no Fresnel (a mirror)"},
    LOBE_LABEL};
inline constexpr ClosureParam kRefraction[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"eta", T::Float, false, nullptr, "relative IOR inside/outside"},
    LOBE_LABEL};
inline constexpr ClosureParam kConductor[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"U", T::Vector, false, nullptr, "tangent"},
    {"roughness_x", T::Float, false, nullptr, "alpha along U"},
    {"roughness_y", T::Float, false, nullptr, "alpha along N x U"},
    {"ior", T::Color, false, nullptr, "real part of the complex IOR per channel"},
    {"extinction", T::Color, false, nullptr, "imaginary part k (eta = n - ik)"},
    {"distribution", T::String, false, nullptr, "\"ggx\" or \"beckmann\""},
    LOBE_THINFILM,
    LOBE_EC("1"),
    LOBE_LABEL};
inline constexpr ClosureParam kDielectric[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"U", T::Vector, false, nullptr, "tangent"},
    {"reflection_tint", T::Color, false, nullptr, "multiplies reflection"},
    {"transmission_tint", T::Color, false, nullptr, "multiplies transmission (0: no refraction)"},
    {"roughness_x", T::Float, false, nullptr, "alpha along U"},
    {"roughness_y", T::Float, false, nullptr, "alpha along N x U"},
    {"ior", T::Float, false, nullptr, "IOR inside/outside"},
    {"distribution", T::String, false, nullptr, "\"ggx\" or \"beckmann\""},
    LOBE_THINFILM,
    LOBE_EC("1"),
    LOBE_LABEL};
inline constexpr ClosureParam kGeneralizedSchlick[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"U", T::Vector, false, nullptr, "tangent"},
    {"reflection_tint", T::Color, false, nullptr, "multiplies reflection"},
    {"transmission_tint", T::Color, false, nullptr, "multiplies transmission (0: no refraction)"},
    {"roughness_x", T::Float, false, nullptr, "alpha along U"},
    {"roughness_y", T::Float, false, nullptr, "alpha along N x U"},
    {"f0", T::Color, false, nullptr, "reflectance at normal incidence"},
    {"f90", T::Color, false, nullptr, "reflectance at grazing incidence"},
    {"exponent", T::Float, false, nullptr, "Schlick exponent (5: classic Schlick)"},
    {"distribution", T::String, false, nullptr, "\"ggx\" or \"beckmann\""},
    LOBE_THINFILM,
    LOBE_EC("1"),
    LOBE_LABEL};
inline constexpr ClosureParam kEmittance[] = {
    {"emittance", T::Color, false, nullptr, "emitted radiance"}};
inline constexpr ClosureParam kDebugTag[] = {{"tag", T::String, false, nullptr, "AOV name"}};
inline constexpr ClosureParam kLayerArgs[] = {
    {"top", T::Closure, false, nullptr, "top layer (e.g. a coat)"},
    {"base", T::Closure, false, nullptr, "base, attenuated by the top's albedo"}};
inline constexpr ClosureParam kToon[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"albedo", T::Color, false, nullptr, "diffuse band colour"},
    {"specular", T::Color, false, nullptr, "specular highlight colour"},
    {"shininess", T::Float, false, nullptr, "Blinn exponent of the highlight"},
    {"bands", T::Int, true, "3", "number of diffuse bands (>= 1)"},
    {"softness", T::Float, true, "0.05", "width of the band edges in [0, 1]"},
    LOBE_LABEL};
inline constexpr ClosureParam kMeasured[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"filename", T::String, false, nullptr, "MERL .binary file"},
    {"tint", T::Color, true, "1 1 1", "multiplies the measured values"},
    LOBE_LABEL};

// Media (OSL's subsurface and MaterialX's VDFs and BSSRDF): OSL's testrender prints "label"
// for the MaterialX ones, so Lobe does too.
inline constexpr ClosureParam kSubsurface[] = {
    {"eta", T::Float, false, nullptr, "index of refraction of the medium"},
    {"g", T::Float, false, nullptr, "scattering anisotropy in [-1, 1]"},
    {"mfp", T::Color, false, nullptr, "mean free path per channel"},
    {"albedo", T::Color, false, nullptr, "single-scattering albedo"},
    LOBE_LABEL};
inline constexpr ClosureParam kSubsurfaceBssrdf[] = {
    {"N", T::Vector, false, nullptr, "shading normal"},
    {"albedo", T::Color, false, nullptr, "single-scattering albedo of the medium"},
    {"transmission_depth", T::Float, false, nullptr,
     "distance at which white light has become transmission_color"},
    {"transmission_color", T::Color, false, nullptr, "white light after transmission_depth"},
    {"anisotropy", T::Float, false, nullptr, "scattering anisotropy in [-1, 1]"},
    LOBE_LABEL_PRINTED};
inline constexpr ClosureParam kAnisotropicVdf[] = {
    {"albedo", T::Color, false, nullptr, "single-scattering albedo"},
    {"extinction", T::Color, false, nullptr, "extinction coefficient per unit length"},
    {"anisotropy", T::Float, false, nullptr, "Henyey-Greenstein g in [-1, 1]"},
    LOBE_LABEL_PRINTED};
inline constexpr ClosureParam kMediumVdf[] = {
    {"albedo", T::Color, false, nullptr, "single-scattering albedo"},
    {"transmission_depth", T::Float, false, nullptr,
     "distance at which white light has become transmission_color"},
    {"transmission_color", T::Color, false, nullptr, "white light after transmission_depth"},
    {"anisotropy", T::Float, false, nullptr, "Henyey-Greenstein g in [-1, 1]"},
    {"ior", T::Float, false, nullptr, "index of refraction of the medium"},
    {"priority", T::Int, false, nullptr, "nesting priority of overlapping media"},
    LOBE_LABEL_PRINTED};

#undef LOBE_LABEL
#undef LOBE_LABEL_PRINTED
#undef LOBE_EC
#undef LOBE_THINFILM

inline constexpr uint32_t kR = kReflect, kRT = kReflect | kTransmit;

// key, name, params, flags, doc. Order = ids; append new entries at the end when possible.
inline constexpr ClosureEntry kClosures[] = {
    {"diffuse", "diffuse", kDiffuse, kR, "Lambertian reflection, f = 1/pi"},
    {"oren_nayar", "oren_nayar", kOrenNayar, kR, "Oren-Nayar rough diffuse (qualitative model)"},
    {"oren_nayar_diffuse_bsdf", "oren_nayar_diffuse_bsdf", kOrenNayarDiffuseBsdf, kR,
     "Fujii Oren-Nayar; energy-preserving (EON) with energy_compensation"},
    {"burley_diffuse_bsdf", "burley_diffuse_bsdf", kNormalAlbedoRoughness, kR,
     "Disney/Burley diffuse with retro-reflection"},
    {"translucent", "translucent", kNormalOnly, kTransmit, "Lambertian transmission"},
    {"translucent_bsdf", "translucent_bsdf", kNormalAlbedo, kTransmit,
     "Lambertian transmission with albedo"},
    {"phong", "phong", kPhong, kR, "modified Phong, (n+2)/(2pi) normalisation"},
    {"blinn_phong", "blinn_phong", kBlinnPhong, kR, "Lobe: normalised Blinn-Phong microfacet lobe"},
    {"ward", "ward", kWard, kR, "anisotropic Ward, energy-conserving normalisation"},
    {"microfacet", "microfacet", kMicrofacet, kRT, "GGX/Beckmann microfacet, dielectric Fresnel"},
    {"reflection", "reflection", kReflection, kR | kDelta, "mirror with Fresnel(eta)"},
    {"refraction", "refraction", kRefraction, kTransmit | kDelta, "perfect refraction"},
    {"conductor_bsdf", "conductor_bsdf", kConductor, kR, "microfacet metal, complex Fresnel"},
    {"dielectric_bsdf", "dielectric_bsdf", kDielectric, kRT, "microfacet glass/coat"},
    {"generalized_schlick_bsdf", "generalized_schlick_bsdf", kGeneralizedSchlick, kRT,
     "microfacet with generalised Schlick Fresnel"},
    {"sheen_bsdf", "sheen_bsdf", kNormalAlbedoRoughness, kR, "Charlie microfibre sheen"},
    {"transparent", "transparent", {}, kTransparent, "straight pass-through"},
    {"transparent_bsdf", "transparent_bsdf", {}, kTransparent, "straight pass-through"},
    {"emission", "emission", {}, kEmission, "uniform emission, radiance = weight"},
    {"uniform_edf", "uniform_edf", kEmittance, kEmission, "uniform emission"},
    {"background", "background", {}, kBackground, "environment radiance = weight"},
    {"holdout", "holdout", {}, kHoldout, "holdout (matte) weight"},
    {"debug", "debug", kDebugTag, registry::kDebug, "an AOV, no light transport"},
    {"layer", "layer", kLayerArgs, registry::kLayer,
     "top over base, base scaled by 1 - albedo(top)"},
    {"toon", "toon", kToon, kR, "Lobe: banded cartoon diffuse + specular"},
    {"measured_bsdf", "measured_bsdf", kMeasured, kR, "Lobe: MERL measured isotropic BRDF"},
    {"subsurface", "subsurface", kSubsurface, registry::kMedium,
     "OSL's BSSRDF; no surface contribution (Lobe renders no subsurface transport)"},
    {"subsurface_bssrdf", "subsurface_bssrdf", kSubsurfaceBssrdf, kR,
     "approximated by Lambertian reflection with the albedo"},
    {"anisotropic_vdf", "anisotropic_vdf", kAnisotropicVdf, registry::kMedium,
     "Henyey-Greenstein medium; no surface contribution"},
    {"medium_vdf", "medium_vdf", kMediumVdf, registry::kMedium,
     "dielectric medium (glass, liquids); no surface contribution"},
};

// Id of a key at compile time (-1 if absent), for the closure library's dispatch.
constexpr int index_of(std::string_view key) {
  for (size_t i = 0; i < std::size(kClosures); ++i)
    if (key == kClosures[i].key) return static_cast<int>(i);
  return -1;
}

} // namespace lobe::registry::table

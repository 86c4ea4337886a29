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
using registry::kBackground, registry::kDebug, registry::kEmission, registry::kHoldout,
    registry::kLayer, registry::kMedium, registry::kTransparent;

// The table: X(key, parameters, flags, doc), one row per closure, in id order (an entry's id
// is its row; append new closures at the end when possible). `key` is the name shaders call,
// the family file's `Closure<closure_id::key>` specialisation, and the stem of the kernel
// symbols (LOBE_KERNEL_SYMBOL); `doc` is the line of the generated reference (docs/closures.md).
// Everything else about a closure is derived from this one list: ids (closure_id), the entries
// (kClosures), the dispatch switch and layout checks (runtime/closures/dispatch.h), the
// bitcode entry points (bitcode.cpp) and the kernel symbols the JIT links (kernel_symbol()).
#define LOBE_CLOSURE_TABLE(X)                                                                      \
  X(diffuse, kDiffuse, kR, "Lambertian reflection, f = 1/pi")                                      \
  X(oren_nayar, kOrenNayar, kR, "Oren-Nayar rough diffuse (qualitative model)")                    \
  X(oren_nayar_diffuse_bsdf, kOrenNayarDiffuseBsdf, kR,                                            \
    "Fujii Oren-Nayar; energy-preserving (EON) with energy_compensation")                          \
  X(burley_diffuse_bsdf, kNormalAlbedoRoughness, kR,                                               \
    "Disney/Burley diffuse with retro-reflection")                                                 \
  X(translucent, kNormalOnly, kTransmit, "Lambertian transmission")                                \
  X(translucent_bsdf, kNormalAlbedo, kTransmit, "Lambertian transmission with albedo")             \
  X(phong, kPhong, kR, "modified Phong, (n+2)/(2pi) normalisation")                                \
  X(blinn_phong, kBlinnPhong, kR, "Lobe: normalised Blinn-Phong microfacet lobe")                  \
  X(ward, kWard, kR, "anisotropic Ward, energy-conserving normalisation")                          \
  X(microfacet, kMicrofacet, kRT, "GGX/Beckmann microfacet, dielectric Fresnel")                   \
  X(reflection, kReflection, kR | kDelta, "mirror with Fresnel(eta); eta 0: no Fresnel")           \
  X(refraction, kRefraction, kTransmit | kDelta, "perfect refraction")                             \
  X(conductor_bsdf, kConductor, kR, "microfacet metal, complex Fresnel")                           \
  X(dielectric_bsdf, kDielectric, kRT | kSidedIor, "microfacet glass/coat")                        \
  X(generalized_schlick_bsdf, kGeneralizedSchlick, kRT | kSidedIor,                                \
    "microfacet with generalised Schlick Fresnel")                                                 \
  X(sheen_bsdf, kNormalAlbedoRoughness, kR, "Charlie microfibre sheen")                            \
  X(transparent, {}, kTransparent, "straight pass-through")                                        \
  X(transparent_bsdf, {}, kTransparent, "straight pass-through")                                   \
  X(emission, {}, kEmission, "uniform emission, radiance = weight")                                \
  X(uniform_edf, kEmittance, kEmission, "uniform emission")                                        \
  X(background, {}, kBackground, "environment radiance = weight")                                  \
  X(holdout, {}, kHoldout, "holdout (matte) weight")                                               \
  X(debug, kDebugTag, kDebug, "an AOV, no light transport")                                        \
  X(layer, kLayerArgs, kLayer, "top over base, base scaled by 1 - albedo(top)")                    \
  X(toon, kToon, kR, "Lobe: banded cartoon diffuse + specular")                                    \
  X(measured_bsdf, kMeasured, kR | kNativeOnly, "Lobe: MERL measured isotropic BRDF")              \
  X(subsurface, kSubsurface, kMedium,                                                              \
    "OSL's BSSRDF; no surface contribution (Lobe renders no subsurface transport)")                \
  X(subsurface_bssrdf, kSubsurfaceBssrdf, kR,                                                      \
    "approximated by Lambertian reflection with the albedo")                                       \
  X(anisotropic_vdf, kAnisotropicVdf, kMedium,                                                     \
    "Henyey-Greenstein medium; no surface contribution")                                           \
  X(medium_vdf, kMediumVdf, kMedium, "dielectric medium (glass, liquids); no surface contribution")

inline constexpr ClosureEntry kClosures[] = {
#define LOBE_ROW(key, params, flags, doc) {#key, #key, params, flags, doc},
    LOBE_CLOSURE_TABLE(LOBE_ROW)
#undef LOBE_ROW
};

// Id of a key at compile time (-1 if absent).
constexpr int index_of(std::string_view key) {
  for (size_t i = 0; i < std::size(kClosures); ++i)
    if (key == kClosures[i].key) return static_cast<int>(i);
  return -1;
}

} // namespace lobe::registry::table

namespace lobe::registry {

// Registry ids by key, at compile time: closure_id::conductor_bsdf. kCount: the number of
// built-in entries (ids of closures a renderer registers follow, closure_plugin.h).
namespace closure_id {
enum : int {
#define LOBE_ID(key, ...) key,
  LOBE_CLOSURE_TABLE(LOBE_ID)
#undef LOBE_ID
      kCount
};
} // namespace closure_id
static_assert(closure_id::kCount == std::size(table::kClosures));

} // namespace lobe::registry

// Closures a renderer adds: a name, parameters and the lobe's eval / pdf / sample (and
// optionally albedo), registered once before anything is compiled.
//
//   lobe::CustomClosure c;
//   c.name = "my_diffuse";
//   c.params = {{"N", lobe::ClosureParamType::Vector}, {"albedo", lobe::ClosureParamType::Color}};
//   c.lobe_flags = lobe::kLobeReflect | lobe::kLobeDiffuse;
//   c.eval = my_eval; c.pdf = my_pdf; c.sample = my_sample;   // see ClosureEvalFn etc.
//   std::string err;
//   int id = lobe::register_closure(c, &err);                   // -1: err says why
//
// From then on the closure is a registry entry like the built-in ones (docs/closures.md,
// "Closures a renderer registers"): the type checker knows its signature, so shaders call it
// by name, with positional arguments and `"keyword", value` pairs, and a shader's own
// `closure color my_diffuse(normal N, color albedo) [[ int builtin = 1 ]];` prototype defers
// to it (as prototypes of built-in closures do); generated code builds a ClosureComponent whose
// parameter block holds the arguments in registry layout; it prints as OSL prints closures;
// and a Bsdf (lobe/bsdf.h) built from a closure tree containing it calls these functions for
// its lobe, weighted, mixed and sampled with the others. Registered closures run natively: a
// material's JIT closure kernels (ClosureKernels) never cover them, and the Bsdf falls back to
// these functions for them.
//
// Rules: register before any ShadingSystem compiles or any Bsdf is built, from one thread
// (registration is not synchronised with compiling or shading); registrations last for the
// process. Names must be new (not a built-in closure nor one registered before).
#pragma once

#include "lobe/bsdf.h"
#include "lobe/vec.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lobe {

// A parameter's type as shaders see it; in the parameter block: int and float 4 bytes, color
// and vector (also normal, point) 12 bytes, at 4-byte alignment; string 8 bytes (an interned
// `const char*`) and closure 8 bytes (a `const ClosureNode*`), at 8-byte alignment. Parameters
// are laid out in declaration order (positional ones first, then keywords), each at its
// alignment; closure_param_offset() tells where.
enum class ClosureParamType : uint8_t { Int, Float, Color, Vector, String, Closure };

struct ClosureParamDecl {
  std::string name;
  ClosureParamType type = ClosureParamType::Float;
  // A keyword parameter: optional, given as `"name", value` after the positional arguments,
  // and `default_value` (literal text: "0", "0.5", "1 1 1", "\"\"") when not given.
  bool keyword = false;
  std::string default_value;
  std::string doc;
};

// The lobe's functions. `params` is the component's parameter block (above); directions are
// world space, unit length, pointing away from the surface: wo towards the viewer, wi towards
// the light (the conventions of lobe/bsdf.h). `user` is CustomClosure::user.
//   eval:   value = f(wo, wi) |cos(N, wi)| (before the closure's weight) and the pdf with which
//           sample() produces wi (solid angle); value 0 and pdf 0 where the lobe has none.
//   pdf:    that same pdf alone.
//   sample: u in [0,1)^3; a direction wi with weight = value / pdf and that pdf, and the
//           LobeFlags of what was sampled (eta for transmission); pdf 0 for no sample.
//   albedo: the directional albedo at wo (used to weight the choice between lobes and by
//           layer()); optional, a lobe without one counts as albedo 1.
// What the functions return is sanitised as the built-in lobes' is (non-finite or negative
// values become 0, a sample with a non-finite or zero pdf is no sample).
using ClosureEvalFn = BsdfEval (*)(const unsigned char* params, const Vec3& wo, const Vec3& wi,
                                   Transport mode, void* user);
using ClosurePdfFn = float (*)(const unsigned char* params, const Vec3& wo, const Vec3& wi,
                               void* user);
using ClosureSampleFn = BsdfSample (*)(const unsigned char* params, const Vec3& wo, const Vec3& u,
                                       Transport mode, void* user);
using ClosureAlbedoFn = Color3 (*)(const unsigned char* params, const Vec3& wo, void* user);

struct CustomClosure {
  std::string name; // what shaders call: letters, digits and '_', not starting with a digit
  std::vector<ClosureParamDecl> params;
  // LobeFlags of the lobe: kLobeReflect and/or kLobeTransmit (at least one), plus kLobeDiffuse
  // or kLobeGlossy (kLobeSpecular, a delta lobe, is not supported for registered closures).
  uint32_t lobe_flags = kLobeReflect | kLobeDiffuse;
  std::string doc; // one line, for listings
  ClosureEvalFn eval = nullptr;
  ClosurePdfFn pdf = nullptr;
  ClosureSampleFn sample = nullptr;
  ClosureAlbedoFn albedo = nullptr; // optional
  void* user = nullptr;
};

// Registers `c` and returns its closure id (what ClosureComponent::id holds for it), or -1
// with the reason in `*error`: an empty or invalid name, a name in use, a missing function,
// flags without reflection or transmission, a positional parameter after a keyword, or the
// registry full (128 closures in all).
int register_closure(const CustomClosure& c, std::string* error = nullptr);

// Byte offset of parameter `param` in the blocks of closure `closure` (a registered or
// built-in name), or -1 if either is unknown.
long closure_param_offset(std::string_view closure, std::string_view param);

} // namespace lobe

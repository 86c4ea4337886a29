// The C-ABI functions JIT-compiled shader code calls, and the one table that names them.
//
// Each entry is (symbol name, address, signature). The signature string is the return type
// followed by the parameter types: v void, i int32, l int64, f float, p pointer, derived from
// the function's C type (shadeop_sig.h; the prototypes are shadeop_decls.h, which every
// defining file includes). Codegen declares functions from this table and the JIT resolves
// them from it (an absolute-symbol map: no dlsym), so a shadeop is declared exactly once. Pointer
// arguments carry triples/matrices (float*, components in order), strings (interned const char*)
// and contexts.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace lobe::math {
enum class Fn : int32_t; // runtime/mathlib/mathops.h
}

namespace lobe::shadeops {

struct ShadeOpSymbol {
  const char* name;
  void* address;
  const char* sig;
};

std::span<const ShadeOpSymbol> shadeop_symbols();
const ShadeOpSymbol* find_shadeop(std::string_view name);

// The math builtins' shadeops (ops_math.cpp): each math::Fn has a value function and, for
// derivatives, a slope (unary) or dual (binary) function. Their names come from here only.
enum class MathForm { Value = 0, Slope = 1, Dual = 2 };
const char* math_shadeop(math::Fn f, MathForm form);
std::span<const ShadeOpSymbol> math_shadeop_symbols(); // included in shadeop_symbols()

// Texture lookup options gathered from a texture call's keyword arguments; codegen fills this
// struct by field offset and passes its address to lobe_texture / lobe_texture3d /
// lobe_environment.
struct TextureArgs {
  float blur[3] = {0, 0, 0};  // s, t, r ("blur" sets all three, "sblur" one)
  float width[3] = {1, 1, 1}; // s, t, r ("width" sets all three, "swidth" one)
  float fill = 0;
  int32_t firstchannel = 0;
  // s, t, r: "black", "clamp", "periodic", "mirror" or null (the file's default); "wrap" sets
  // all three, "swrap" one
  const char* wrap[3] = {nullptr, nullptr, nullptr};
  const char* interp = nullptr; // "closest", "linear", "cubic", "smartcubic"; other: smartcubic
  int32_t has_missing = 0;
  float missing[4] = {0, 0, 0,
                      0}; // "missingcolor": used (without an error) when the file is missing
  // "errormessage": the string the lookup writes (null: none): "" when it succeeds, else why it
  // failed (then no error is reported), as OSL.
  const char** errormessage = nullptr;
  // The lookup's call site (its layer and op), for OpenImageIO's per-thread tile cache: lookups
  // from one site keep their own, so that a shader reading several places or files in turn does
  // not evict the tile its other lookups read next (results do not depend on it).
  int32_t site = 0;
  // "subimage": an index, or a name (non-null: the name, which wins)
  int32_t subimage = 0;
  const char* subimagename = nullptr;
};

// Noise kinds for lobe_noise (noise("name", ...) and the named functions).
enum NoiseKind : int {
  kPerlin = 0,
  kUPerlin = 1,
  kCell = 2,
  kHash = 3,
  kSimplex = 4,
  kUSimplex = 5
};
// Gabor noise options: the keyword arguments of noise("gabor", ...) / pnoise("gabor", ...)
// ("anisotropic" int, "do_filter" int, "direction" vector, "bandwidth" float, "impulses"
// float), with OSL's defaults; codegen fills this struct by field offset and passes its address
// to lobe_gabor / lobe_noise_named_d.
struct GaborOptions {
  int32_t anisotropic = 0; // 0 isotropic, 1 anisotropic (fixed direction), 2 hybrid
  int32_t do_filter = 1;
  float direction[3] = {1, 0, 0};
  float bandwidth = 1.0f; // clamped to [0.01, 100]
  float impulses = 16.0f; // per cell, clamped to [1, 32]
};

// -1: unknown, or "simplex"/"usimplex" when `periodic` (OSL has no periodic simplex noise, so
// pnoise("simplex", ...) is an unknown noise type).
int noise_kind_from_name(std::string_view name, bool periodic);

// Length units for transformu, in metres ("m"/"meter"/"meters", "cm", "mm", "km", "in"/"inch",
// "ft"/"foot"/"feet", "mi"/"mile", and "common", Lobe's renderer units: metres); 0: unknown.
double unit_scale(std::string_view name);

} // namespace lobe::shadeops

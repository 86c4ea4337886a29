// The one closure registry: every closure a shader can call, declared once.
//
// A leaf: no math, no LLVM. Read by the compiler's type checker (names, overloads, argument
// types, keyword arguments), by the runtime (parameter-block layout, dispatch), by codegen
// (how to pack a `closure` op's arguments), by the docs generator and by the test that every
// entry has an implementation and every implementation an entry.
//
// Parameter blocks: a closure component's arguments are stored in a block laid out in the
// order of `params` (positional parameters first, then keywords), each at its natural
// alignment: Int/Float 4 bytes, Color/Vector 12 bytes (align 4), String/Closure 8 bytes (a
// pointer: an interned `const char*` / a `const ClosureNode*`). param_offset() and
// param_block_size() compute it; the runtime's C++ parameter structs static_assert against it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace lobe::registry {

enum class ArgType : uint8_t {
  Int,
  Float,
  Color,
  Vector, // vector, normal or point argument (OSL accepts any triple here)
  String,
  Closure,
};

struct ClosureParam {
  const char* name;
  ArgType type;
  bool keyword;              // optional `"name", value` argument after the positional ones
  const char* default_value; // keywords only: literal text ("0", "1 1 1", "\"\"")
  const char* doc;
  // Keywords only: printed even at its default value. OSL prints every parameter its renderer
  // registered; its reference renderer registers "label" for diffuse and phong and no other
  // keyword, so those two print `"label", ""` and Lobe's other keywords print only when set.
  bool always_printed = false;
};

// What a closure contributes; the runtime routes components by these.
enum Flags : uint32_t {
  kReflect = 1u << 0,     // BSDF lobe with reflection
  kTransmit = 1u << 1,    // BSDF lobe with transmission
  kDelta = 1u << 2,       // a Dirac lobe (perfect mirror/refraction)
  kEmission = 1u << 3,    // emission()/uniform_edf
  kBackground = 1u << 4,  // background()
  kTransparent = 1u << 5, // transparent()/transparent_bsdf: pass-through
  kHoldout = 1u << 6,     // holdout()
  kDebug = 1u << 7,       // debug(tag): an AOV, no light transport
  kLayer = 1u << 8,       // layer(top, base): a combinator over two closures
  kMedium = 1u << 9,      // describes the medium under the surface (VDFs, subsurface()): no
                          // surface contribution in Lobe, which renders no volumes
  kNativeOnly = 1u << 10, // a BSDF lobe only the native library has (measured_bsdf reads
                          // files): no bitcode kernel, the Bsdf calls the native code
  kSidedIor = 1u << 11,   // its IOR is the object's inside over outside from either side
                          // (MaterialX's convention; OSL's own microfacet/refraction/reflection
                          // take eta across the side N faces): Bsdf::build's `backfacing`
                          // turns its N back to the outside
};

struct ClosureEntry {
  const char* key;  // unique; equals `name` unless two entries share a name (none do today)
  const char* name; // the name shaders call
  std::span<const ClosureParam> params;
  uint32_t flags;
  const char* doc; // one line for generated docs
};

// All entries, in id order: an entry's id is its index here and is what a ClosureComponent
// stores at run time. The built-in table (closure_table.h) comes first; closures a renderer
// registers (lobe/closure_plugin.h, through add_closure) follow it.
std::span<const ClosureEntry> closures();
const ClosureEntry* find_by_key(std::string_view key);
int id_of(std::string_view key); // -1 if absent

// Adds an entry after the built-in ones and returns its id; its strings and parameters are
// copied. -1 (and `error`) for a key that exists or when kMaxClosures are registered. Not
// thread-safe: register before anything compiles or shades (spans from closures() taken
// earlier stay valid: the storage never moves).
inline constexpr size_t kMaxClosures = 128;
int add_closure(const ClosureEntry& entry, const char** error = nullptr);

// The five functions the closure bitcode defines for a BSDF entry (runtime/closures/
// bitcode.cpp) and the JIT links (runtime/jit/closure_kernels.cpp). Their symbol names come
// from this one macro on both sides: "lobe_closure_" key "_" fn.
#define LOBE_KERNEL_SYMBOL(key, fn) "lobe_closure_" #key "_" #fn
enum class Kernel : uint8_t { setup, eval, sample, pdf, albedo };
// The symbol of entry `id`'s kernel, or null when the entry has none (see has_kernel).
const char* kernel_symbol(int id, Kernel k);
// A BSDF lobe with bitcode: kReflect or kTransmit, and not kNativeOnly.
constexpr bool has_kernel(uint32_t flags) {
  return (flags & (kReflect | kTransmit)) != 0 && (flags & kNativeOnly) == 0;
}

constexpr size_t arg_size(ArgType t) {
  switch (t) {
  case ArgType::Int:
  case ArgType::Float:
    return 4;
  case ArgType::Color:
  case ArgType::Vector:
    return 12;
  case ArgType::String:
  case ArgType::Closure:
    return 8;
  }
  return 0;
}
constexpr size_t arg_align(ArgType t) {
  return (t == ArgType::String || t == ArgType::Closure) ? 8 : 4;
}
constexpr size_t param_offset(std::span<const ClosureParam> params, size_t index) {
  size_t off = 0;
  for (size_t i = 0;; ++i) {
    size_t a = arg_align(params[i].type);
    off = (off + a - 1) / a * a;
    if (i == index) return off;
    off += arg_size(params[i].type);
  }
}
constexpr size_t param_block_size(std::span<const ClosureParam> params) {
  if (params.empty()) return 0;
  size_t end = param_offset(params, params.size() - 1) + arg_size(params.back().type);
  return (end + 7) / 8 * 8;
}

} // namespace lobe::registry

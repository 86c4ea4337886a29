// The shading globals, declared once: the type checker declares from this list the globals
// shaders may name (compiler/sema), and lobe/shading.h builds from it the field table codegen
// reads offsets from (kGlobalFields: this list with each member's offset in ShaderGlobals).
// A leaf like the closure registry: names, types and flags, no ShaderGlobals and no LLVM.
//
// LOBE_SHADING_GLOBALS(X) has one X(member, type, flags, dx, dy) per global:
//   member  the ShaderGlobals field; its name is the name shaders use
//   type    its type in the language (Float, Point, Vector, Normal, Closure); the field holds
//           one float, three floats, or a closure pointer
//   flags   kGlobalNamed: shaders may name it (the derivative fields dIdx, dudx, ... only hold
//                         derivatives of other globals); kGlobalWritable: shaders may assign it
//   dx, dy  the members holding its screen-space derivatives, or nullptr (no derivatives:
//           zero, as for any global without)
// The order is the bit order of Material::globals_read; new globals go at the end.
#pragma once

#include <cstdint>
#include <string_view>

namespace lobe {

enum class GlobalType : uint8_t { Float, Point, Vector, Normal, Closure };

enum GlobalFlags : uint8_t {
  kGlobalNamed = 1u << 0,
  kGlobalWritable = 1u << 1,
};

// clang-format off
#define LOBE_SHADING_GLOBALS(X) \
  X(P,       Point,   kGlobalNamed | kGlobalWritable, "dPdx",  "dPdy")  \
  X(dPdx,    Vector,  kGlobalNamed,                   nullptr, nullptr) \
  X(dPdy,    Vector,  kGlobalNamed,                   nullptr, nullptr) \
  X(dPdz,    Vector,  kGlobalNamed,                   nullptr, nullptr) \
  X(I,       Vector,  kGlobalNamed | kGlobalWritable, "dIdx",  "dIdy")  \
  X(dIdx,    Vector,  0,                              nullptr, nullptr) \
  X(dIdy,    Vector,  0,                              nullptr, nullptr) \
  X(N,       Normal,  kGlobalNamed | kGlobalWritable, nullptr, nullptr) \
  X(Ng,      Normal,  kGlobalNamed,                   nullptr, nullptr) \
  X(u,       Float,   kGlobalNamed,                   "dudx",  "dudy")  \
  X(dudx,    Float,   0,                              nullptr, nullptr) \
  X(dudy,    Float,   0,                              nullptr, nullptr) \
  X(v,       Float,   kGlobalNamed,                   "dvdx",  "dvdy")  \
  X(dvdx,    Float,   0,                              nullptr, nullptr) \
  X(dvdy,    Float,   0,                              nullptr, nullptr) \
  X(dPdu,    Vector,  kGlobalNamed,                   nullptr, nullptr) \
  X(dPdv,    Vector,  kGlobalNamed,                   nullptr, nullptr) \
  X(time,    Float,   kGlobalNamed,                   nullptr, nullptr) \
  X(dtime,   Float,   kGlobalNamed,                   nullptr, nullptr) \
  X(dPdtime, Vector,  kGlobalNamed,                   nullptr, nullptr) \
  X(Ps,      Point,   kGlobalNamed,                   "dPsdx", "dPsdy") \
  X(Ci,      Closure, kGlobalNamed | kGlobalWritable, nullptr, nullptr) \
  X(dPsdx,   Vector,  0,                              nullptr, nullptr) \
  X(dPsdy,   Vector,  0,                              nullptr, nullptr)
// clang-format on

struct ShadingGlobal {
  const char* name;
  GlobalType type;
  uint8_t flags;
  const char* dx; // the global holding d/dx, or null
  const char* dy;
};

inline constexpr ShadingGlobal kShadingGlobals[] = {
#define LOBE_SHADING_GLOBAL_ROW(member, type, flags, dx, dy)                                       \
  {#member, GlobalType::type, flags, dx, dy},
    LOBE_SHADING_GLOBALS(LOBE_SHADING_GLOBAL_ROW)
#undef LOBE_SHADING_GLOBAL_ROW
};

// The global of that name, or null.
constexpr const ShadingGlobal* find_shading_global(std::string_view name) {
  for (const ShadingGlobal& g : kShadingGlobals)
    if (name == g.name) return &g;
  return nullptr;
}

} // namespace lobe

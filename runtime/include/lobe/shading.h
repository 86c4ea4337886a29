// What a compiled shader reads and writes: the shading globals and the closure tree.
//
// Both structs are shared byte-for-byte with JIT-compiled code, which addresses their fields
// by offset: keep them standard-layout. The globals are listed once, in lobe/shading_globals.h
// (read by the type checker too); kGlobalFields below is that list with each field's offset.
#pragma once

#include "lobe/shading_globals.h"
#include "lobe/vec.h"

#include <cstddef>
#include <cstdint>

namespace lobe {

struct ClosureNode;
class ShadingContext;

// Ray types, as bits of ShaderGlobals::raytype; raytype("name") tests the bit.
enum RayType : int32_t {
  kRayCamera = 1,
  kRayShadow = 2,
  kRayReflection = 4,
  kRayRefraction = 8,
  kRayDiffuse = 16,
  kRayGlossy = 32,
  kRaySubsurface = 64,
  kRayDisplacement = 128,
};

// The shading globals of one point. Directions follow OSL: I points from the eye towards P
// (the incoming ray direction); N and Ng as the renderer gives them (lobe render turns them
// towards the viewer, as OSL's testrender does; backfacing tells which side was hit).
struct ShaderGlobals {
  Vec3 P, dPdx, dPdy;  // position and its screen-space derivatives
  Vec3 dPdz;           // volumes only
  Vec3 I, dIdx, dIdy;  // incident ray direction
  Vec3 N;              // shading normal (writable in surface shaders)
  Vec3 Ng;             // geometric normal
  float u, dudx, dudy; // surface parameters and their derivatives
  float v, dvdx, dvdy;
  Vec3 dPdu, dPdv; // surface tangents
  float time, dtime;
  Vec3 dPdtime;
  Vec3 Ps, dPsdx, dPsdy; // light position (light shaders)
  float surfacearea;     // area of the emitting object (surfacearea())
  int32_t raytype;       // RayType bits of the ray that hit this point
  int32_t backfacing;    // 1 when I and Ng point the same way
  int32_t flip_handedness;
  const float* object2common; // 4x4 row-major, or null for identity
  const float* shader2common;
  void* renderstate;       // the renderer's; opaque to shaders
  ShadingContext* context; // closure allocation, messages, errors
  const ClosureNode* Ci;   // the surface closure (output)
};

// Field table for codegen: kShadingGlobals (lobe/shading_globals.h) with each member's
// place in ShaderGlobals, in the same order (index i is bit i of Material::globals_read).
enum class GlobalKind : uint8_t { Float, Int, Triple, Closure };
struct GlobalField {
  const char* name;
  GlobalKind kind;
  size_t offset;
  const char* dx; // name of the d/dx field, or null
  const char* dy; // name of the d/dy field, or null
};
constexpr GlobalKind global_kind(GlobalType t) {
  return t == GlobalType::Float     ? GlobalKind::Float
         : t == GlobalType::Closure ? GlobalKind::Closure
                                    : GlobalKind::Triple;
}
constexpr size_t global_bytes(GlobalType t) {
  return t == GlobalType::Float     ? sizeof(float)
         : t == GlobalType::Closure ? sizeof(const ClosureNode*)
                                    : 3 * sizeof(float);
}
inline constexpr GlobalField kGlobalFields[] = {
#define LOBE_GLOBAL_FIELD(member, type, flags, dx, dy)                                             \
  {#member, global_kind(GlobalType::type), offsetof(ShaderGlobals, member), dx, dy},
    LOBE_SHADING_GLOBALS(LOBE_GLOBAL_FIELD)
#undef LOBE_GLOBAL_FIELD
};
// Every global's member has the size its type says.
#define LOBE_GLOBAL_SIZE(member, type, flags, dx, dy)                                              \
  static_assert(sizeof(ShaderGlobals::member) == global_bytes(GlobalType::type), #member);
LOBE_SHADING_GLOBALS(LOBE_GLOBAL_SIZE)
#undef LOBE_GLOBAL_SIZE

// Closure tree nodes, built by shader code through the ShadingContext's arena.
// id >= 0: a component (registry id); kClosureAdd / kClosureMul: combinators;
// kClosureDeclared: a closure the shader declared itself (ClosureDeclared).
inline constexpr int32_t kClosureAdd = -1;
inline constexpr int32_t kClosureMul = -2;
inline constexpr int32_t kClosureDeclared = -3;

struct ClosureNode {
  int32_t id;
};
struct ClosureAdd : ClosureNode {
  const ClosureNode* a;
  const ClosureNode* b;
};
struct ClosureMul : ClosureNode {
  Color3 weight;
  const ClosureNode* closure;
};
// A component: its parameter block (registry layout) follows immediately, at offset
// sizeof(ClosureComponent), 8-byte aligned.
struct alignas(8) ClosureComponent : ClosureNode {
  Color3 weight; // (1,1,1) at creation; kept for renderer-built components
  const unsigned char* params() const { return reinterpret_cast<const unsigned char*>(this + 1); }
  unsigned char* params() { return reinterpret_cast<unsigned char*>(this + 1); }
};
static_assert(sizeof(ClosureComponent) == 16);

// A closure the shader declares itself, `closure color name(...) [[ int builtin = 1 ]]`, that
// no registry entry implements: it carries a description of its arguments (the positional ones
// in order, then the keywords the call gave, each once), so a renderer can at least report it
// by name. A renderer implements such a closure by registering it (lobe/closure_plugin.h,
// register_closure) before compiling: the prototype then resolves to the registry entry and
// the shader builds a ClosureComponent instead of this node. The description is owned by the
// ShadingSystem and outlives every closure pointing at it.
struct DeclaredClosureArg {
  enum class Base : uint8_t { Int, Float, Triple, Matrix, String, Closure };
  const char* keyword; // null for a positional argument
  Base base;
  int32_t arraylen; // 0: not an array
  uint32_t offset;  // byte offset in the value block
};
struct DeclaredClosureInfo {
  const char* name;
  const DeclaredClosureArg* args;
  uint32_t nargs;
  uint32_t block_size;
};
struct alignas(8) ClosureDeclared : ClosureNode {
  Color3 weight;
  const DeclaredClosureInfo* info;
  const unsigned char* values() const { return reinterpret_cast<const unsigned char*>(this + 1); }
  unsigned char* values() { return reinterpret_cast<unsigned char*>(this + 1); }
};
static_assert(sizeof(ClosureDeclared) == 24);

} // namespace lobe

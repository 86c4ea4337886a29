// What a compiled shader reads and writes: the shading globals and the closure tree.
//
// Both structs are shared byte-for-byte with JIT-compiled code, which addresses their fields
// by offset: keep them standard-layout, and change kGlobalFields with any field change.
#pragma once

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
// (the incoming ray direction), N and Ng face wherever the geometry says (backfacing tells).
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

// Field table for codegen: name as shaders see it, kind, byte offset.
enum class GlobalKind : uint8_t { Float, Int, Triple, Closure };
struct GlobalField {
  const char* name;
  GlobalKind kind;
  size_t offset;
  const char* dx; // name of the d/dx field, or null
  const char* dy; // name of the d/dy field, or null
};
inline constexpr GlobalField kGlobalFields[] = {
    {"P", GlobalKind::Triple, offsetof(ShaderGlobals, P), "dPdx", "dPdy"},
    {"dPdx", GlobalKind::Triple, offsetof(ShaderGlobals, dPdx), nullptr, nullptr},
    {"dPdy", GlobalKind::Triple, offsetof(ShaderGlobals, dPdy), nullptr, nullptr},
    {"dPdz", GlobalKind::Triple, offsetof(ShaderGlobals, dPdz), nullptr, nullptr},
    {"I", GlobalKind::Triple, offsetof(ShaderGlobals, I), "dIdx", "dIdy"},
    {"dIdx", GlobalKind::Triple, offsetof(ShaderGlobals, dIdx), nullptr, nullptr},
    {"dIdy", GlobalKind::Triple, offsetof(ShaderGlobals, dIdy), nullptr, nullptr},
    {"N", GlobalKind::Triple, offsetof(ShaderGlobals, N), nullptr, nullptr},
    {"Ng", GlobalKind::Triple, offsetof(ShaderGlobals, Ng), nullptr, nullptr},
    {"u", GlobalKind::Float, offsetof(ShaderGlobals, u), "dudx", "dudy"},
    {"dudx", GlobalKind::Float, offsetof(ShaderGlobals, dudx), nullptr, nullptr},
    {"dudy", GlobalKind::Float, offsetof(ShaderGlobals, dudy), nullptr, nullptr},
    {"v", GlobalKind::Float, offsetof(ShaderGlobals, v), "dvdx", "dvdy"},
    {"dvdx", GlobalKind::Float, offsetof(ShaderGlobals, dvdx), nullptr, nullptr},
    {"dvdy", GlobalKind::Float, offsetof(ShaderGlobals, dvdy), nullptr, nullptr},
    {"dPdu", GlobalKind::Triple, offsetof(ShaderGlobals, dPdu), nullptr, nullptr},
    {"dPdv", GlobalKind::Triple, offsetof(ShaderGlobals, dPdv), nullptr, nullptr},
    {"time", GlobalKind::Float, offsetof(ShaderGlobals, time), nullptr, nullptr},
    {"dtime", GlobalKind::Float, offsetof(ShaderGlobals, dtime), nullptr, nullptr},
    {"dPdtime", GlobalKind::Triple, offsetof(ShaderGlobals, dPdtime), nullptr, nullptr},
    {"Ps", GlobalKind::Triple, offsetof(ShaderGlobals, Ps), "dPsdx", "dPsdy"},
    {"Ci", GlobalKind::Closure, offsetof(ShaderGlobals, Ci), nullptr, nullptr},
};

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

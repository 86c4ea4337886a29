// What a renderer tells shaders about the scene: user data (per-primitive values bound to
// parameters declared `[[ int lockgeom = 0 ]]`), attributes (`getattribute`) and rays
// (`trace`).
//
// A renderer derives from RendererServices and sets ShadingContext::renderer on each thread's
// context. All calls happen during Material::shade, on the shading thread, so an
// implementation must be safe to call from several threads at once (const, no shared state
// written).
//
// Value layout, as in OSL: `val` points at `type.bytes()` bytes (elements × components
// scalars; int32 for Int, float for Float, triples and matrices, const char* for String). When
// `derivatives` is true (only for float-based types), two more planes of the same size follow
// with d/dx and d/dy; Lobe zeroes them before the call, so a renderer that knows no
// derivatives leaves them. Strings need only stay valid until the call returns (Lobe interns
// them). Return false when the name or type is unknown: `val` is then ignored.
#pragma once

#include "lobe/shading.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace lobe {

struct DataType {
  enum class Base : uint8_t { Int, Float, Color, Point, Vector, Normal, Matrix, String };
  Base base = Base::Float;
  int arraylen = 0; // 0: not an array

  bool is_triple() const {
    return base == Base::Color || base == Base::Point || base == Base::Vector ||
           base == Base::Normal;
  }
  bool is_float_based() const { return base != Base::Int && base != Base::String; }
  int components() const { return is_triple() ? 3 : base == Base::Matrix ? 16 : 1; }
  int elements() const { return arraylen > 0 ? arraylen : 1; }
  size_t scalar_bytes() const { return base == Base::String ? sizeof(const char*) : 4; }
  size_t bytes() const { return size_t(elements()) * size_t(components()) * scalar_bytes(); }
  // "float", "color", "float[2]", "string", ...
  std::string str() const;
  // The reverse of str(); nullopt for anything else (closures, structs, "float[0]").
  static std::optional<DataType> parse(std::string_view text);
  bool operator==(const DataType&) const = default;
};

// trace()'s keyword arguments.
struct TraceOptions {
  float mindist = 0;         // the ray starts this far from P (world units, along R / |R|)
  float maxdist = 1e30f;     // and ends this far
  bool shade = false;        // "shade": OSL runs the hit's shader; Lobe's renderers do not
  const char* traceset = ""; // "traceset": a renderer-defined subset of the scene
};

// What trace() found; getmessage("trace", name, dest) reads it (ShadingContext::trace_hit).
struct TraceHit {
  bool traced = false; // a trace() ran in this shade
  bool hit = false;
  float hitdist = 0; // world distance from P to the hit
  Vec3 P, N, Ng;     // hit position, shading and geometric normal (unit)
  float u = 0, v = 0;
};

class RendererServices {
public:
  virtual ~RendererServices() = default;

  // User data named `name` of type `type` at this point (OSL's get_userdata). Asked for each
  // `lockgeom = 0` parameter that has no connection, when its layer starts; a `true` answer
  // overrides the instance value and the default.
  virtual bool get_userdata(const ShaderGlobals& sg, std::string_view name, DataType type,
                            bool derivatives, void* val) const {
    (void)sg, (void)name, (void)type, (void)derivatives, (void)val;
    return false;
  }

  // getattribute([object,] name, [index,] dest). `object` is "" when the shader names none
  // (the object being shaded); `index` is -1 unless the shader asked for one element of an
  // array attribute, and `type` is then the element's type. Lobe answers "osl:version",
  // "shader:shadername", "shader:layername" and "shader:groupname" itself, before asking.
  virtual bool get_attribute(const ShaderGlobals& sg, std::string_view object,
                             std::string_view name, int index, DataType type, bool derivatives,
                             void* val) const {
    (void)sg, (void)object, (void)name, (void)index, (void)type, (void)derivatives, (void)val;
    return false;
  }

  // The matrix from the named space to "common" at this point (OSL's get_matrix by name):
  // 16 floats, row-major, points as row vectors (p' = p * M). Asked for every space name but
  // "common" and "world" (the identity) before Lobe's defaults: "object" and "shader" from
  // ShaderGlobals, the camera spaces ("camera", "screen", "NDC", "raster") as the identity;
  // any other name is an unknown space unless the renderer knows it.
  virtual bool get_matrix(const ShaderGlobals& sg, std::string_view space, float* m) const {
    (void)sg, (void)space, (void)m;
    return false;
  }

  // The matrix from "common" to the named space, asked first when the space is a transform's
  // destination (OSL's get_inverse_matrix by name). Without an answer Lobe inverts get_matrix's.
  virtual bool get_inverse_matrix(const ShaderGlobals& sg, std::string_view space, float* m) const {
    (void)sg, (void)space, (void)m;
    return false;
  }

  // Whether the camera spaces that neither method above answers are the identity (true, Lobe's
  // default) or unknown spaces, an error (false: OSL's testshade, which knows them only as
  // destinations).
  virtual bool camera_spaces_default_to_identity() const { return true; }

  // trace(P, R, ...): casts a ray from P along the direction of R (R need not be unit length)
  // with the differentials of both; true when it hits something between opt.mindist and
  // opt.maxdist, with `hit`'s hitdist, P, N, Ng, u, v filled (Lobe sets `traced` and `hit`).
  virtual bool trace(const ShaderGlobals& sg, const TraceOptions& opt, const Vec3& P,
                     const Vec3& dPdx, const Vec3& dPdy, const Vec3& R, const Vec3& dRdx,
                     const Vec3& dRdy, TraceHit& hit) const {
    (void)sg, (void)opt, (void)P, (void)dPdx, (void)dPdy, (void)R, (void)dRdx, (void)dRdy,
        (void)hit;
    return false;
  }

  // getmessage("trace", name, dest), as OSL asks its renderer: an answer is the call's result,
  // `val` (the shader's variable, of `type`, followed by its d/dx and d/dy planes when
  // `derivatives`; strings written are interned by Lobe) written or not as the renderer
  // chooses, derivatives included (OSL leaves them to the renderer too). nullopt (the default)
  // leaves the query to Lobe, which answers from the TraceHit the last trace() of this shade
  // filled: "hit" (int), and after a hit "hitdist", "u", "v" (float), "P", "N", "Ng" (any
  // triple), with zero derivatives.
  virtual std::optional<bool> trace_message(const ShaderGlobals& sg, std::string_view name,
                                            DataType type, bool derivatives, void* val) const {
    (void)sg, (void)name, (void)type, (void)derivatives, (void)val;
    return std::nullopt;
  }
};

} // namespace lobe

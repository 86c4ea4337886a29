// Texture shadeops through OpenImageIO's TextureSystem (mip-mapped, filtered, cached; loaded on
// the first lookup, runtime/oiio/oiio_module.h):
// texture(file, s, t) with screen-space derivatives, texture3d(file, P), environment(file, R),
// gettextureinfo(file, query, dest).
// One TextureSystem per RuntimeEnv (so per ShadingSystem), created on first use. A missing
// file gives "missingcolor" when the shader supplies one, else 0 and a run-time error.
#include "env.h"
#include "lobe/context.h"
#include "oiio_module.h"
#include "shadeop_decls.h"
#include "shadeops.h"
#include "typed_value.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

using lobe::ShaderGlobals;
using lobe::shadeops::RuntimeEnv;
using lobe::shadeops::TextureArgs;

namespace lobe::shadeops {

RuntimeEnv::~RuntimeEnv() {
  if (texture_system) oiio::module()->destroy_texture_system(texture_system);
}

} // namespace lobe::shadeops

namespace {

// The env's texture system, created on first use (null, with the reason in `why`, when the
// OpenImageIO module cannot be loaded).
void* texsys(RuntimeEnv* env, const lobe::oiio::Api*& api, std::string& why) {
  api = lobe::oiio::module(&why);
  if (!api) return nullptr;
  std::call_once(env->texture_once,
                 [env, api] { env->texture_system = api->create_texture_system(); });
  return env->texture_system;
}

// The shade's order, by which a file that cannot be opened is told once (oiio::Api::texture_error).
uint64_t order_of(const ShaderGlobals* sg) { return sg && sg->context ? sg->context->order : 0; }

// After a failed lookup: the shader's missing colour (no error; an "errormessage" output is
// ""), or zeros and an error in OSL's words (`[RendererServices::texture] Could not open file
// "x.exr"`, `kind` naming the lookup: texture, texture3d or environment; nothing for a file
// OpenImageIO explained before), or the reason in the "errormessage" output instead
// ("unknown" when it was told before).
void missing(ShaderGlobals* sg, RuntimeEnv* env, std::string err, const TextureArgs* a,
             const char* file, int n, float* out, const char* kind) {
  for (int c = 0; c < n; ++c) out[c] = a->has_missing ? a->missing[std::min(c, 3)] : 0.0f;
  bool explained = err == lobe::oiio::kNoExplanation;
  // No reason given: the lookup of a file that opened failed otherwise (OpenImageIO said nothing).
  if (err.empty()) err = "texture lookup of \"" + std::string(file) + "\" failed";
  if (a->errormessage) { // with "missingcolor" the lookup counts as done: "" (as in OSL)
    *a->errormessage = env->strings.intern(a->has_missing ? "" : explained ? "unknown" : err);
    return;
  }
  if (a->has_missing || explained || !sg || !sg->context) return;
  sg->context->error("[RendererServices::" + std::string(kind) + "] " + err);
}

// After a lookup that succeeded: an "errormessage" output is "".
void found(RuntimeEnv* env, const TextureArgs* a) {
  if (a->errormessage) *a->errormessage = env->strings.intern("");
}

} // namespace

extern "C" {

// out[n] = filtered lookup; dds/ddt (may be null) receive d out / ds, d out / dt.
void lobe_texture(ShaderGlobals* sg, RuntimeEnv* env, const char* file, float s, float t,
                  float dsdx, float dtdx, float dsdy, float dtdy, int n, float* out, float* dds,
                  float* ddt, const TextureArgs* a) {
  const lobe::oiio::Api* api;
  std::string why;
  void* ts = texsys(env, api, why);
  if (ts && api->texture(ts, file, a, s, t, dsdx, dtdx, dsdy, dtdy, n, out, dds, ddt)) {
    found(env, a);
  } else {
    missing(sg, env, ts ? api->texture_error(ts, order_of(sg)) : why, a, file, n, out, "texture");
    if (dds) std::fill(dds, dds + n, 0.0f);
    if (ddt) std::fill(ddt, ddt + n, 0.0f);
  }
}

// p, dpdx, dpdy, dpdz: three floats each.
void lobe_texture3d(ShaderGlobals* sg, RuntimeEnv* env, const char* file, const float* p,
                    const float* dpdx, const float* dpdy, const float* dpdz, int n, float* out,
                    const TextureArgs* a) {
  const lobe::oiio::Api* api;
  std::string why;
  void* ts = texsys(env, api, why);
  if (ts && api->texture3d(ts, file, a, p, dpdx, dpdy, dpdz, n, out))
    found(env, a);
  else
    missing(sg, env, ts ? api->texture_error(ts, order_of(sg)) : why, a, file, n, out, "texture3d");
}

// As lobe_texture3d, for a direction r; the third derivative is unused (an environment is a
// function of direction only).
void lobe_environment(ShaderGlobals* sg, RuntimeEnv* env, const char* file, const float* r,
                      const float* drdx, const float* drdy, const float* /*unused*/, int n,
                      float* out, const TextureArgs* a) {
  const lobe::oiio::Api* api;
  std::string why;
  void* ts = texsys(env, api, why);
  if (ts && api->environment(ts, file, a, r, drdx, drdy, n, out))
    found(env, a);
  else
    missing(sg, env, ts ? api->texture_error(ts, order_of(sg)) : why, a, file, n, out,
            "environment");
}

// gettextureinfo(file, [s, t,] query, dest): OIIO's get_texture_info ("exists", "resolution",
// "channels", "type", "textureformat", "datawindow", "averagecolor", any image metadata...)
// into `dest` of type `code` (typed_value.h). With `udim`, a UDIM file name (`tex.<UDIM>.tx`)
// resolves to its tile at (s, t) first, as OSL does; other names ignore s and t. 1 when
// answered; a failure reports OIIO's error as OSL does: `Shader error [shader]: Invalid image
// file ...` with `shader` (a file name constant at -O2, which OSL looks up while compiling), else
// `[RendererServices::get_texture_info] ...`.
int lobe_gettextureinfo(ShaderGlobals* sg, RuntimeEnv* env, const char* shader, const char* file,
                        int udim, float s, float t, const char* query, int code, void* dest) {
  using namespace lobe::shadeops;
  int base = code_base(code);
  if (base < 0 || base > int(lobe::DataType::Base::String))
    return 0; // closures are no texture info
  const lobe::oiio::Api* api;
  std::string why;
  void* ts = texsys(env, api, why);
  return fetch_value(env, code, 0, dest, [&](void* val) {
    int r = ts ? api->texture_info(ts, file, udim != 0, s, t, query, base, code_arraylen(code), val)
               : -1;
    if (r >= 0) return r == 1;
    std::string err = ts ? api->texture_error(ts, order_of(sg)) : why;
    if (!err.empty() && sg && sg->context)
      sg->context->error(shader ? "Shader error [" + std::string(shader) + "]: " + err
                                : "[RendererServices::get_texture_info] " + err);
    return false;
  });
}

} // extern "C"

// Texture shadeops through OpenImageIO's TextureSystem (mip-mapped, filtered, cached):
// texture(file, s, t) with screen-space derivatives, texture3d(file, P), environment(file, R),
// gettextureinfo(file, query, dest).
// One TextureSystem per RuntimeEnv (so per ShadingSystem), created on first use. A missing
// file gives "missingcolor" when the shader supplies one, else 0 and a run-time error.
#include "env.h"
#include "lobe/context.h"
#include "shadeops.h"
#include "typed_value.h"

#include <Imath/ImathVec.h>
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

using lobe::ShaderGlobals;
using lobe::shadeops::RuntimeEnv;
using lobe::shadeops::TextureArgs;
namespace OIIO = OIIO_NAMESPACE;

namespace lobe::shadeops {

RuntimeEnv::~RuntimeEnv() {
  if (texture_system)
    OIIO::TextureSystem::destroy(static_cast<OIIO::TextureSystem*>(texture_system));
}

} // namespace lobe::shadeops

namespace {

OIIO::TextureSystem* texsys(RuntimeEnv* env) {
  std::call_once(env->texture_once,
                 [env] { env->texture_system = OIIO::TextureSystem::create(false); });
  return static_cast<OIIO::TextureSystem*>(env->texture_system);
}

OIIO::TextureOpt options(const TextureArgs* a) {
  OIIO::TextureOpt opt;
  opt.sblur = opt.tblur = opt.rblur = a->blur;
  opt.swidth = opt.twidth = opt.rwidth = a->width;
  opt.fill = a->fill;
  opt.firstchannel = a->firstchannel;
  if (a->wrap) opt.swrap = opt.twrap = opt.rwrap = OIIO::TextureOpt::decode_wrapmode(a->wrap);
  if (a->interp) {
    std::string m = a->interp;
    opt.interpmode = m == "closest"                     ? OIIO::TextureOpt::InterpClosest
                     : m == "linear" || m == "bilinear" ? OIIO::TextureOpt::InterpBilinear
                     : m == "cubic" || m == "bicubic"   ? OIIO::TextureOpt::InterpBicubic
                                                        : OIIO::TextureOpt::InterpSmartBicubic;
  }
  return opt;
}

// After a failed lookup: the shader's missing colour, or zeros and an error.
void missing(ShaderGlobals* sg, OIIO::TextureSystem* ts, const TextureArgs* a, const char* file,
             int n, float* out) {
  for (int c = 0; c < n; ++c) out[c] = a->has_missing ? a->missing[std::min(c, 3)] : 0.0f;
  std::string err = ts->geterror();
  if (a->has_missing || !sg || !sg->context) return;
  sg->context->error("texture \"" + std::string(file) +
                     "\": " + (err.empty() ? "cannot read" : err));
}

} // namespace

extern "C" {

// out[n] = filtered lookup; dds/ddt (may be null) receive d out / ds, d out / dt.
void lobe_texture(ShaderGlobals* sg, RuntimeEnv* env, const char* file, float s, float t,
                  float dsdx, float dtdx, float dsdy, float dtdy, int n, float* out, float* dds,
                  float* ddt, const TextureArgs* a) {
  OIIO::TextureSystem* ts = texsys(env);
  OIIO::TextureOpt opt = options(a);
  if (!ts->texture(OIIO::ustring(file), opt, s, t, dsdx, dtdx, dsdy, dtdy, n, out, dds, ddt)) {
    missing(sg, ts, a, file, n, out);
    if (dds) std::fill(dds, dds + n, 0.0f);
    if (ddt) std::fill(ddt, ddt + n, 0.0f);
  }
}

// p, dpdx, dpdy: three floats each.
void lobe_texture3d(ShaderGlobals* sg, RuntimeEnv* env, const char* file, const float* p,
                    const float* dpdx, const float* dpdy, int n, float* out, const TextureArgs* a) {
  OIIO::TextureSystem* ts = texsys(env);
  OIIO::TextureOpt opt = options(a);
  Imath::V3f P(p[0], p[1], p[2]), dx(dpdx[0], dpdx[1], dpdx[2]), dy(dpdy[0], dpdy[1], dpdy[2]),
      dz(0, 0, 0);
  if (!ts->texture3d(OIIO::ustring(file), opt, P, dx, dy, dz, n, out))
    missing(sg, ts, a, file, n, out);
}

void lobe_environment(ShaderGlobals* sg, RuntimeEnv* env, const char* file, const float* r,
                      const float* drdx, const float* drdy, int n, float* out,
                      const TextureArgs* a) {
  OIIO::TextureSystem* ts = texsys(env);
  OIIO::TextureOpt opt = options(a);
  Imath::V3f R(r[0], r[1], r[2]), dx(drdx[0], drdx[1], drdx[2]), dy(drdy[0], drdy[1], drdy[2]);
  if (!ts->environment(OIIO::ustring(file), opt, R, dx, dy, n, out))
    missing(sg, ts, a, file, n, out);
}

} // extern "C"

extern "C" {

// gettextureinfo(file, query, dest): OIIO's get_texture_info ("exists", "resolution",
// "channels", "type", "textureformat", "datawindow", "averagecolor", any image metadata...)
// into `dest` of type `code` (typed_value.h). 1 when answered; a failure reports OIIO's
// error, as OSL does.
int lobe_gettextureinfo(ShaderGlobals* sg, RuntimeEnv* env, const char* file, const char* query,
                        int code, void* dest) {
  using namespace lobe::shadeops;
  // Lobe's base types in order: int float color point vector normal matrix string.
  static const OIIO::TypeDesc kTypes[] = {
      OIIO::TypeDesc::INT, OIIO::TypeDesc::FLOAT, OIIO::TypeColor,  OIIO::TypePoint,
      OIIO::TypeVector,    OIIO::TypeNormal,      OIIO::TypeMatrix, OIIO::TypeDesc::STRING};
  int base = code_base(code);
  if (base < 0 || base >= int(std::size(kTypes))) return 0; // closures are no texture info
  OIIO::TypeDesc t = kTypes[base];
  if (code_arraylen(code) > 0) t.arraylen = code_arraylen(code);
  OIIO::TextureSystem* ts = texsys(env);
  return fetch_value(env, code, 0, dest, [&](void* val) {
    if (ts->get_texture_info(OIIO::ustring(file ? file : ""), 0, OIIO::ustring(query ? query : ""),
                             t, val))
      return true;
    std::string err = ts->geterror();
    if (!err.empty() && sg && sg->context) {
      sg->context->error("[RendererServices::get_texture_info] " + err);
    }
    return false;
  });
}

} // extern "C"

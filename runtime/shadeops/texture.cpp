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

// "automip": an image without MIP levels gets them built on first use, so that derivatives
// and blur filter it (as OSL's testshade and testrender set up their TextureSystem).
OIIO::TextureSystem* texsys(RuntimeEnv* env) {
  std::call_once(env->texture_once, [env] {
    OIIO::TextureSystem* ts = OIIO::TextureSystem::create(false);
    ts->attribute("automip", 1);
    env->texture_system = ts;
  });
  return static_cast<OIIO::TextureSystem*>(env->texture_system);
}

OIIO::TextureOpt options(const TextureArgs* a) {
  OIIO::TextureOpt opt;
  opt.sblur = a->blur[0];
  opt.tblur = a->blur[1];
  opt.rblur = a->blur[2];
  opt.swidth = a->width[0];
  opt.twidth = a->width[1];
  opt.rwidth = a->width[2];
  opt.fill = a->fill;
  opt.firstchannel = a->firstchannel;
  if (a->wrap[0]) opt.swrap = OIIO::TextureOpt::decode_wrapmode(a->wrap[0]);
  if (a->wrap[1]) opt.twrap = OIIO::TextureOpt::decode_wrapmode(a->wrap[1]);
  if (a->wrap[2]) opt.rwrap = OIIO::TextureOpt::decode_wrapmode(a->wrap[2]);
  if (a->interp) { // OSL's names; any other (e.g. "bilinear") is the default, as in OSL
    std::string m = a->interp;
    opt.interpmode = m == "closest"  ? OIIO::TextureOpt::InterpClosest
                     : m == "linear" ? OIIO::TextureOpt::InterpBilinear
                     : m == "cubic"  ? OIIO::TextureOpt::InterpBicubic
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

// p, dpdx, dpdy, dpdz: three floats each.
void lobe_texture3d(ShaderGlobals* sg, RuntimeEnv* env, const char* file, const float* p,
                    const float* dpdx, const float* dpdy, const float* dpdz, int n, float* out,
                    const TextureArgs* a) {
  OIIO::TextureSystem* ts = texsys(env);
  OIIO::TextureOpt opt = options(a);
  Imath::V3f P(p[0], p[1], p[2]), dx(dpdx[0], dpdx[1], dpdx[2]), dy(dpdy[0], dpdy[1], dpdy[2]),
      dz(dpdz[0], dpdz[1], dpdz[2]);
  if (!ts->texture3d(OIIO::ustring(file), opt, P, dx, dy, dz, n, out))
    missing(sg, ts, a, file, n, out);
}

// As lobe_texture3d, for a direction r; the third derivative is unused (an environment is a
// function of direction only).
void lobe_environment(ShaderGlobals* sg, RuntimeEnv* env, const char* file, const float* r,
                      const float* drdx, const float* drdy, const float* /*unused*/, int n,
                      float* out, const TextureArgs* a) {
  OIIO::TextureSystem* ts = texsys(env);
  OIIO::TextureOpt opt = options(a);
  Imath::V3f R(r[0], r[1], r[2]), dx(drdx[0], drdx[1], drdx[2]), dy(drdy[0], drdy[1], drdy[2]);
  if (!ts->environment(OIIO::ustring(file), opt, R, dx, dy, n, out))
    missing(sg, ts, a, file, n, out);
}

} // extern "C"

extern "C" {

// gettextureinfo(file, [s, t,] query, dest): OIIO's get_texture_info ("exists", "resolution",
// "channels", "type", "textureformat", "datawindow", "averagecolor", any image metadata...)
// into `dest` of type `code` (typed_value.h). With `udim`, a UDIM file name (`tex.<UDIM>.tx`)
// resolves to its tile at (s, t) first, as OSL does; other names ignore s and t. 1 when
// answered; a failure reports OIIO's error, as OSL does.
int lobe_gettextureinfo(ShaderGlobals* sg, RuntimeEnv* env, const char* file, int udim, float s,
                        float t, const char* query, int code, void* dest) {
  using namespace lobe::shadeops;
  // Lobe's base types in order: int float color point vector normal matrix string.
  static const OIIO::TypeDesc kTypes[] = {
      OIIO::TypeDesc::INT, OIIO::TypeDesc::FLOAT, OIIO::TypeColor,  OIIO::TypePoint,
      OIIO::TypeVector,    OIIO::TypeNormal,      OIIO::TypeMatrix, OIIO::TypeDesc::STRING};
  int base = code_base(code);
  if (base < 0 || base >= int(std::size(kTypes))) return 0; // closures are no texture info
  OIIO::TypeDesc type = kTypes[base];
  if (code_arraylen(code) > 0) type.arraylen = code_arraylen(code);
  OIIO::TextureSystem* ts = texsys(env);
  OIIO::ustring name(file ? file : ""), what(query ? query : "");
  return fetch_value(env, code, 0, dest, [&](void* val) {
    if (udim) {
      OIIO::TextureSystem::TextureHandle* h = ts->get_texture_handle(name);
      if (h && ts->is_udim(h)) h = ts->resolve_udim(h, nullptr, s, t);
      if (h && ts->get_texture_info(h, nullptr, 0, what, type, val)) return true;
      if (!h) return false; // no tile at (s, t): not an error, as in OSL
    } else if (ts->get_texture_info(name, 0, what, type, val)) {
      return true;
    }
    std::string err = ts->geterror();
    if (!err.empty() && sg && sg->context) {
      sg->context->error("[RendererServices::get_texture_info] " + err);
    }
    return false;
  });
}

} // extern "C"

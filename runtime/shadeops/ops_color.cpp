// Colour shadeops: the C ABI over ColorSystem (color_system.h). Each call gets the material's
// colour system (CompileOptions::colorspace) as a constant pointer baked into the code; null
// means the default, Rec709. Unknown colour-space names are run-time errors worded as OSL's.
#include "color_system.h"
#include "lobe/context.h"
#include "lobe/shading.h"
#include "shadeop_decls.h"

#include <algorithm>
#include <string>

using lobe::ShaderGlobals;
using lobe::shadeops::Color3d;
using lobe::shadeops::Color3f;
using lobe::shadeops::ColorSystem;

namespace {

const ColorSystem& system_of(const void* cs) {
  return cs ? *static_cast<const ColorSystem*>(cs) : ColorSystem::rec709();
}

void unknown(ShaderGlobals* sg, const char* from, const char* to) {
  if (sg && sg->context)
    sg->context->error(std::string("Unknown color space transformation \"") + from + "\" -> \"" +
                       to + "\"");
}

void store(float* dst, const Color3f& c) {
  dst[0] = c.r;
  dst[1] = c.g;
  dst[2] = c.b;
}

} // namespace

extern "C" {

// dst = src converted from space `from` to space `to`.
void lobe_transformc(ShaderGlobals* sg, const void* cs, const char* from, const char* to,
                     float* dst, const float* src) {
  Color3f out;
  if (!system_of(cs).transform(from, to, {src[0], src[1], src[2]}, out)) unknown(sg, from, to);
  store(dst, out);
}

// The same with derivatives: src and dst hold 9 floats, value then d/dx then d/dy. Input
// derivatives that are all zero take the value-only form: OSL's dual sRGB curve rounds
// differently from its value-only one, and Lobe gives derivatives to some values OSL does not
// (temporaries shared with differentiated expressions); zero derivatives mark most of those.
void lobe_transformc_d(ShaderGlobals* sg, const void* cs, const char* from, const char* to,
                       float* dst, const float* src) {
  if (std::all_of(src + 3, src + 9, [](float d) { return d == 0; })) {
    lobe_transformc(sg, cs, from, to, dst, src);
    std::fill(dst + 3, dst + 9, 0.0f);
    return;
  }
  Color3d in{{src[0], src[3], src[6]}, {src[1], src[4], src[7]}, {src[2], src[5], src[8]}}, out;
  if (!system_of(cs).transform(from, to, in, out)) unknown(sg, from, to);
  const lobe::shadeops::DualF* c[3] = {&out.r, &out.g, &out.b};
  for (int k = 0; k < 3; ++k) {
    dst[k] = c[k]->v;
    dst[3 + k] = c[k]->dx;
    dst[6 + k] = c[k]->dy;
  }
}

// color("space", a, b, c): dst = src from `space` to RGB (no derivatives, as OSL).
void lobe_color_from(ShaderGlobals* sg, const void* cs, const char* space, float* dst,
                     const float* src) {
  Color3f out;
  if (!system_of(cs).to_rgb(space, {src[0], src[1], src[2]}, out)) unknown(sg, space, "RGB");
  store(dst, out);
}

void lobe_wavelength_color(const void* cs, float* dst, float lambda_nm) {
  store(dst, system_of(cs).wavelength_color(lambda_nm));
}

void lobe_blackbody(const void* cs, float* dst, float kelvin) {
  store(dst, system_of(cs).blackbody(kelvin));
}

} // extern "C"

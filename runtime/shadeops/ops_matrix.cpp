// Matrix and coordinate-space shadeops. Matrices are 16 floats, row-major, and points are row
// vectors (OSL): p' = p * M. Named spaces map to "common" through ShaderGlobals::object2common
// and shader2common (null: identity); "common" and "world" are the identity. The renderer
// (RendererServices::get_matrix, and get_inverse_matrix for a destination) answers any other
// name first; without an answer "camera", "screen", "raster" and "NDC" are the identity too,
// unless the renderer says it has no such defaults (testshade knows them only as destinations).
// An unknown space name is an error and gives the identity (documented in docs/runtime.md).
#include "matrix44.h"
#include "shadeop_decls.h"
#include "shadeops.h"

#include "lobe/context.h"
#include "lobe/shading.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

using lobe::RendererServices;
using lobe::ShaderGlobals;

namespace {

using lobe::math::mat_identity;
using lobe::math::mat_invert;
using lobe::math::mat_is_identity;
using lobe::math::mat_mul;

// Whether `s` is the literal `name`: compared inline, stopping at the first difference (so
// never past the end of `s`). The space names of every transform of every point come here; a
// call of strcmp each, and a strlen for a string_view, cost more than the comparisons.
template <size_t N> inline bool is(const char* s, const char (&name)[N]) {
  for (size_t k = 0; k < N; ++k)
    if (s[k] != name[k]) return false;
  return true;
}

// "common" and "world": the identity, never asked of the renderer.
inline bool is_common(const char* s) { return is(s, "common") || is(s, "world"); }

// space -> common; false for an unknown name. The renderer answers first (any name but
// "common" and "world"). *identity: whether m is the identity because no matrix applied.
bool space_to_common(const ShaderGlobals* sg, const char* space, float* m, bool* identity) {
  *identity = false;
  if (is_common(space)) {
    mat_identity(m);
    *identity = true;
    return true;
  }
  const RendererServices* renderer = sg && sg->context ? sg->context->renderer : nullptr;
  if (renderer && renderer->get_matrix(*sg, space, m)) return true;
  mat_identity(m);
  *identity = true;
  bool camera_defaults = !renderer || renderer->camera_spaces_default_to_identity();
  if (camera_defaults &&
      (is(space, "camera") || is(space, "screen") || is(space, "raster") || is(space, "NDC")))
    return true;
  if (is(space, "object")) {
    if (sg && sg->object2common) {
      std::memcpy(m, sg->object2common, 16 * sizeof(float));
      *identity = false;
    }
    return true;
  }
  if (is(space, "shader")) {
    if (sg && sg->shader2common) {
      std::memcpy(m, sg->shader2common, 16 * sizeof(float));
      *identity = false;
    }
    return true;
  }
  return false;
}

// Whether m times the identity (or the identity times m) is m bit for bit: each element is
// its own product with 1 plus products with 0, which add nothing to a finite non-zero value
// or to +0, but turn -0 into +0 and Inf into NaN.
bool product_with_identity_is_itself(const float* m) {
  uint32_t bits[16], bad = 0;
  std::memcpy(bits, m, sizeof bits);
  for (uint32_t u : bits) // branch-free, so that it vectorises: Inf or NaN, or -0
    bad |= uint32_t((u & 0x7f800000u) == 0x7f800000u) | uint32_t(u == 0x80000000u);
  return bad == 0;
}

// dst = a * b, skipping the product where a side is the identity and the product would give
// the other side's bits anyway.
void mat_mul_known(float* dst, const float* a, bool a_identity, const float* b, bool b_identity) {
  if (a_identity && b_identity) return mat_identity(dst);
  if (a_identity && product_with_identity_is_itself(b)) {
    std::memcpy(dst, b, 16 * sizeof(float));
    return;
  }
  if (b_identity && product_with_identity_is_itself(a)) {
    std::memcpy(dst, a, 16 * sizeof(float));
    return;
  }
  mat_mul(dst, a, b);
}

void unknown_space(ShaderGlobals* sg, const char* space) {
  if (sg && sg->context) {
    sg->context->error(std::string("Unknown transformation \"") + space + "\"");
  }
}

} // namespace

extern "C" {

void lobe_mat_mul(float* dst, const float* a, const float* b) { mat_mul(dst, a, b); }
void lobe_mat_inverse(float* dst, const float* src) { mat_invert(dst, src); }
void lobe_mat_div(float* dst, const float* a, const float* b) { lobe::math::mat_div(dst, a, b); }
void lobe_mat_transpose(float* dst, const float* m) { lobe::math::mat_transpose(dst, m); }
float lobe_mat_det(const float* m) { return lobe::math::mat_det(m); }

} // extern "C"

namespace {

// The matrix transforming points from space `from` to space `to`; false on an unknown name
// (reported), whose half of the product is then the identity. "rgb" is no space (a colour
// space): reported wherever a transformation is asked for, as OSL 1.13.12 does.
bool get_matrix(ShaderGlobals* sg, const char* from, const char* to, float* dst) {
  float a[16], b[16], binv[16];
  bool a_identity = false, binv_identity = false;
  bool ok = space_to_common(sg, from, a, &a_identity);
  if (!ok) unknown_space(sg, from);
  bool ok2 = true;
  const RendererServices* renderer = sg && sg->context ? sg->context->renderer : nullptr;
  if (is_common(to) || !renderer || !renderer->get_inverse_matrix(*sg, to, binv)) {
    bool b_identity = false;
    ok2 = space_to_common(sg, to, b, &b_identity);
    if (!ok2) unknown_space(sg, to);
    // To "common" or "world" (or any space that is the identity): the inversion is skipped and
    // the identity used (the float inverse would give it too, but with -0 in the translation
    // row); the product still runs (or is skipped where it would change no bit).
    if (b_identity || mat_is_identity(b)) {
      mat_identity(binv);
      binv_identity = true;
    } else {
      mat_invert(binv, b);
    }
  }
  mat_mul_known(dst, a, a_identity, binv, binv_identity);
  return ok && ok2;
}

} // namespace

extern "C" {

// OSL's getmatrix: the matrix from space `from` to space `to`; 0 on an unknown name (reported).
int lobe_get_matrix(ShaderGlobals* sg, const char* from, const char* to, float* dst) {
  return get_matrix(sg, from, to, dst);
}

// transform(from, to, x) and the spaced triple constructors: as lobe_get_matrix, but an unknown
// name leaves the value as it is (the identity), as OSL.
void lobe_get_transform(ShaderGlobals* sg, const char* from, const char* to, float* dst) {
  if (!get_matrix(sg, from, to, dst)) mat_identity(dst);
}

// matrix("space"): space -> common.
void lobe_space_matrix(ShaderGlobals* sg, const char* space, float* dst) {
  bool identity;
  if (!space_to_common(sg, space, dst, &identity)) unknown_space(sg, space);
}

// kind: 0 point (with translation and projective divide), 1 vector, 2 normal.
void lobe_transform(float* dst, const float* m, const float* p, int kind) {
  lobe::math::mat_transform(dst, m, p, kind);
}

// transformu's scale from unit `from` to unit `to` (shadeops.h, unit_scale), for names known
// only at run time; an unknown name is a run-time error and leaves the value (scale 1).
float lobe_transformu_scale(ShaderGlobals* sg, const char* from, const char* to, const char* file,
                            int line) {
  double a = lobe::shadeops::unit_scale(from ? from : "");
  double b = lobe::shadeops::unit_scale(to ? to : "");
  if (a > 0 && b > 0) return float(a / b);
  if (sg && sg->context) {
    sg->context->error(std::string("Unknown unit \"") + (a > 0 ? to : from) + "\": " + file + ":" +
                       std::to_string(line));
  }
  return 1.0f;
}

} // extern "C"

namespace lobe::shadeops {
double unit_scale(std::string_view u) {
  if (u == "m" || u == "meter" || u == "meters" || u == "common") return 1;
  if (u == "cm") return 0.01;
  if (u == "mm") return 0.001;
  if (u == "km") return 1000;
  if (u == "in" || u == "inch") return 0.0254;
  if (u == "ft" || u == "foot" || u == "feet") return 0.3048;
  if (u == "mi" || u == "mile") return 1609.344;
  return 0;
}
} // namespace lobe::shadeops

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
#include <cstring>
#include <string>
#include <string_view>

using lobe::ShaderGlobals;

namespace {

using lobe::math::mat_identity;
using lobe::math::mat_invert;
using lobe::math::mat_is_identity;
using lobe::math::mat_mul;

// Whether `s` is `name` (strcmp stops at the first difference; a string_view would first
// measure `s`, on every transform of every point).
bool is(const char* s, const char* name) { return std::strcmp(s, name) == 0; }

// space -> common; false for an unknown name. The renderer answers first (any name but
// "common" and "world").
bool space_to_common(const ShaderGlobals* sg, const char* space, float* m) {
  mat_identity(m);
  if (is(space, "common") || is(space, "world")) return true;
  std::string_view s = space;
  if (sg && sg->context && sg->context->renderer && sg->context->renderer->get_matrix(*sg, s, m))
    return true;
  mat_identity(m);
  bool camera_defaults = !(sg && sg->context && sg->context->renderer) ||
                         sg->context->renderer->camera_spaces_default_to_identity();
  if (s == "rgb") return true;
  if (camera_defaults && (s == "camera" || s == "screen" || s == "raster" || s == "NDC"))
    return true;
  if (s == "object") {
    if (sg && sg->object2common) std::memcpy(m, sg->object2common, 16 * sizeof(float));
    return true;
  }
  if (s == "shader") {
    if (sg && sg->shader2common) std::memcpy(m, sg->shader2common, 16 * sizeof(float));
    return true;
  }
  return false;
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

// The matrix transforming points from space `from` to space `to`; returns 0 on an unknown name
// (reported), whose half of the product is then the identity (OSL's getmatrix).
int lobe_get_matrix(ShaderGlobals* sg, const char* from, const char* to, float* dst) {
  float a[16], b[16], binv[16];
  bool ok = space_to_common(sg, from, a);
  if (!ok) unknown_space(sg, from);
  bool ok2 = true;
  if (is(to, "common") || is(to, "world") || !sg || !sg->context || !sg->context->renderer ||
      !sg->context->renderer->get_inverse_matrix(*sg, to, binv)) {
    ok2 = space_to_common(sg, to, b);
    if (!ok2) unknown_space(sg, to);
    // To "common" or "world" (or any space that is the identity): the inversion is skipped and
    // the identity used (the float inverse would give it too, but with -0 in the translation
    // row); the product still runs.
    if (mat_is_identity(b))
      mat_identity(binv);
    else
      mat_invert(binv, b);
  }
  mat_mul(dst, a, binv);
  return ok && ok2;
}

// transform(from, to, x) and the spaced triple constructors: as lobe_get_matrix, but an unknown
// name leaves the value as it is (the identity), as OSL.
void lobe_get_transform(ShaderGlobals* sg, const char* from, const char* to, float* dst) {
  if (!lobe_get_matrix(sg, from, to, dst)) mat_identity(dst);
}

// matrix("space"): space -> common.
void lobe_space_matrix(ShaderGlobals* sg, const char* space, float* dst) {
  if (!space_to_common(sg, space, dst)) unknown_space(sg, space);
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

// Matrix and coordinate-space shadeops. Matrices are 16 floats, row-major, and points are row
// vectors (OSL): p' = p * M. Named spaces map to "common" through ShaderGlobals::object2common
// and shader2common (null: identity); "common" and "world" are the identity. The renderer
// (RendererServices::get_matrix) answers any other name first; without an answer "camera",
// "screen", "raster" and "NDC" are identity too (documented in docs/runtime.md). An unknown
// space name is an error and gives the identity.
#include "shadeop_decls.h"
#include "shadeops.h"

#include "lobe/context.h"
#include "lobe/shading.h"

#include <cmath>
#include <cstring>
#include <string>

using lobe::ShaderGlobals;

namespace {

void identity(float* m) {
  for (int i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0f : 0.0f;
}

void matmul(float* dst, const float* a, const float* b) {
  float r[16];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += double(a[i * 4 + k]) * b[k * 4 + j];
      r[i * 4 + j] = float(s);
    }
  std::memcpy(dst, r, sizeof r);
}

// Gauss-Jordan with partial pivoting in double; a singular matrix inverts to all zeros.
bool invert(float* dst, const float* src) {
  double a[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 8; ++j) a[i][j] = j < 4 ? src[i * 4 + j] : (j - 4 == i ? 1.0 : 0.0);
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    if (a[p][c] == 0.0) {
      std::memset(dst, 0, 16 * sizeof(float));
      return false;
    }
    for (int j = 0; j < 8; ++j) std::swap(a[c][j], a[p][j]);
    double inv = 1.0 / a[c][c];
    for (int j = 0; j < 8; ++j) a[c][j] *= inv;
    for (int r = 0; r < 4; ++r)
      if (r != c) {
        double f = a[r][c];
        for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
      }
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) dst[i * 4 + j] = float(a[i][j + 4]);
  return true;
}

double det3(double a, double b, double c, double d, double e, double f, double g, double h,
            double i) {
  return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
}

// space -> common; false for an unknown name. The renderer answers first (any name but
// "common" and "world").
bool space_to_common(const ShaderGlobals* sg, const char* space, float* m) {
  std::string s = space;
  identity(m);
  if (s == "common" || s == "world") return true;
  if (sg && sg->context && sg->context->renderer && sg->context->renderer->get_matrix(*sg, s, m))
    return true;
  identity(m);
  if (s == "camera" || s == "screen" || s == "raster" || s == "NDC" || s == "rgb") return true;
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

void lobe_mat_mul(float* dst, const float* a, const float* b) { matmul(dst, a, b); }
void lobe_mat_inverse(float* dst, const float* src) { invert(dst, src); }
// a / b = a * inverse(b)
void lobe_mat_div(float* dst, const float* a, const float* b) {
  float inv[16];
  invert(inv, b);
  matmul(dst, a, inv);
}
void lobe_mat_transpose(float* dst, const float* m) {
  float r[16];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r[i * 4 + j] = m[j * 4 + i];
  std::memcpy(dst, r, sizeof r);
}
float lobe_mat_det(const float* m) {
  double d = 0;
  for (int c = 0; c < 4; ++c) {
    double minor[9];
    int k = 0;
    for (int i = 1; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (j != c) minor[k++] = m[i * 4 + j];
    double s = det3(minor[0], minor[1], minor[2], minor[3], minor[4], minor[5], minor[6], minor[7],
                    minor[8]);
    d += (c % 2 ? -1.0 : 1.0) * m[c] * s;
  }
  return float(d);
}

// The matrix transforming points from space `from` to space `to`; returns 0 on an unknown name.
int lobe_get_matrix(ShaderGlobals* sg, const char* from, const char* to, float* dst) {
  float a[16], b[16], binv[16];
  bool ok = space_to_common(sg, from, a);
  if (!ok) unknown_space(sg, from);
  bool ok2 = space_to_common(sg, to, b);
  if (!ok2) unknown_space(sg, to);
  invert(binv, b);
  matmul(dst, a, binv);
  return ok && ok2;
}

// matrix("space"): space -> common.
void lobe_space_matrix(ShaderGlobals* sg, const char* space, float* dst) {
  if (!space_to_common(sg, space, dst)) unknown_space(sg, space);
}

// kind: 0 point (with translation and projective divide), 1 vector, 2 normal.
void lobe_transform(float* dst, const float* m, const float* p, int kind) {
  float x = p[0], y = p[1], z = p[2];
  if (kind == 2) {
    float inv[16];
    invert(inv, m);
    // n * transpose(inverse(M)): row i of the inverse dotted with n.
    for (int i = 0; i < 3; ++i) dst[i] = x * inv[i * 4] + y * inv[i * 4 + 1] + z * inv[i * 4 + 2];
    return;
  }
  float r[3];
  for (int j = 0; j < 3; ++j) r[j] = x * m[j] + y * m[4 + j] + z * m[8 + j];
  if (kind == 0) {
    float w = x * m[3] + y * m[7] + z * m[11] + m[15];
    for (int j = 0; j < 3; ++j) r[j] += m[12 + j];
    if (w != 1.0f && w != 0.0f)
      for (float& c : r) c /= w;
  }
  std::memcpy(dst, r, sizeof r);
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

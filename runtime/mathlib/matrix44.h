// 4x4 matrix arithmetic of the matrix shadeops (ops_matrix.cpp), in one header so that the
// native library and the shadeop bitcode (bitcode_math.cpp, lobe_shadeops.bc) compile the same
// code and an inlined call computes the native call's bits. Matrices are 16 floats, row-major;
// points are row vectors (OSL): p' = p * M.
#pragma once

#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

namespace lobe::math {

inline void mat_identity(float* m) {
  for (int i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0f : 0.0f;
}

// Exactly the identity, bit for bit (so -0 entries do not count as 0).
inline bool mat_is_identity(const float* m) {
  static constexpr float kId[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  return std::memcmp(m, kId, sizeof kId) == 0;
}

// The arithmetic is OSL's, in float and in the same order, so that results match OSL 1.13 bit
// for bit (checked against its testshade; the figures are in matrix_test.cpp): the product
// element by element as a[i][0]*b[0][j] + ... + a[i][3]*b[3][j]; the inverse by cofactors when
// the matrix is affine (last column 0, 0, 0, 1), else Gauss-Jordan with partial pivoting; a
// singular matrix inverts to the identity; the determinant by 3x3 cofactors along the first row.

// dst = a * b (dst may be a or b).
inline void mat_mul(float* dst, const float* a, const float* b) {
  float r[16];
  for (int i = 0; i < 4; ++i) {
    const float a0 = a[i * 4], a1 = a[i * 4 + 1], a2 = a[i * 4 + 2], a3 = a[i * 4 + 3];
    for (int j = 0; j < 4; ++j)
      r[i * 4 + j] = a0 * b[j] + a1 * b[4 + j] + a2 * b[8 + j] + a3 * b[12 + j];
  }
  std::memcpy(dst, r, sizeof r);
}

// Gauss-Jordan with partial pivoting, in float: forward elimination below each pivot, then
// back substitution. False (and the identity) when a pivot is 0. A row is one 4-lane vector:
// every element gets the same single operations (a product, a difference, a quotient) as
// element by element, so the bits are the same; the quotients of a row are one division.
inline bool mat_invert_gauss_jordan(float* dst, const float* src) {
  typedef float Row __attribute__((vector_size(16)));
  Row t[4], s[4];
  for (int i = 0; i < 4; ++i) {
    std::memcpy(&t[i], src + 4 * i, sizeof(Row));
    s[i] =
        Row{i == 0 ? 1.0f : 0.0f, i == 1 ? 1.0f : 0.0f, i == 2 ? 1.0f : 0.0f, i == 3 ? 1.0f : 0.0f};
  }
  for (int i = 0; i < 3; ++i) {
    int pivot = i;
    float size = std::fabs(t[i][i]);
    for (int j = i + 1; j < 4; ++j)
      if (std::fabs(t[j][i]) > size) pivot = j, size = std::fabs(t[j][i]);
    if (size == 0) {
      mat_identity(dst);
      return false;
    }
    if (pivot != i) std::swap(t[i], t[pivot]), std::swap(s[i], s[pivot]);
    for (int j = i + 1; j < 4; ++j) {
      float f = t[j][i] / t[i][i];
      t[j] -= f * t[i];
      s[j] -= f * s[i];
    }
  }
  for (int i = 3; i >= 0; --i) {
    float f = t[i][i];
    if (f == 0) {
      mat_identity(dst);
      return false;
    }
    t[i] /= f;
    s[i] /= f;
    for (int j = 0; j < i; ++j) {
      f = t[j][i];
      t[j] -= f * t[i];
      s[j] -= f * s[i];
    }
  }
  std::memcpy(dst, s, sizeof s);
  return true;
}

// The inverse; the identity (and false) for a singular matrix. dst may be src.
inline bool mat_invert(float* dst, const float* src) {
  const float(*x)[4] = reinterpret_cast<const float(*)[4]>(src);
  if (x[0][3] != 0 || x[1][3] != 0 || x[2][3] != 0 || x[3][3] != 1)
    return mat_invert_gauss_jordan(dst, src);
  // Affine: the 3x3 part by its adjugate over the determinant, the translation row after.
  float s[4][4] = {{x[1][1] * x[2][2] - x[2][1] * x[1][2], x[2][1] * x[0][2] - x[0][1] * x[2][2],
                    x[0][1] * x[1][2] - x[1][1] * x[0][2], 0},
                   {x[2][0] * x[1][2] - x[1][0] * x[2][2], x[0][0] * x[2][2] - x[2][0] * x[0][2],
                    x[1][0] * x[0][2] - x[0][0] * x[1][2], 0},
                   {x[1][0] * x[2][1] - x[2][0] * x[1][1], x[2][0] * x[0][1] - x[0][0] * x[2][1],
                    x[0][0] * x[1][1] - x[1][0] * x[0][1], 0},
                   {0, 0, 0, 1}};
  float r = x[0][0] * s[0][0] + x[0][1] * s[1][0] + x[0][2] * s[2][0];
  // A determinant below 1 divides only entries that stay finite: |s| < |r| / FLT_MIN.
  float limit = std::fabs(r) / std::numeric_limits<float>::min();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (std::fabs(r) < 1 && !(limit > std::fabs(s[i][j]))) {
        mat_identity(dst);
        return false;
      }
      s[i][j] /= r;
    }
  for (int j = 0; j < 3; ++j) s[3][j] = -x[3][0] * s[0][j] - x[3][1] * s[1][j] - x[3][2] * s[2][j];
  std::memcpy(dst, s, sizeof s);
  return true;
}

// dst = a / b = a * inverse(b) (dst may be a or b).
inline void mat_div(float* dst, const float* a, const float* b) {
  float inv[16];
  mat_invert(inv, b);
  mat_mul(dst, a, inv);
}

inline void mat_transpose(float* dst, const float* m) {
  float r[16];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r[i * 4 + j] = m[j * 4 + i];
  std::memcpy(dst, r, sizeof r);
}

inline float det2(float a, float b, float c, float d) { return a * d - b * c; }

// | a1 b1 c1 |
// | a2 b2 c2 |  expanded along its first column.
// | a3 b3 c3 |
inline float det3(float a1, float a2, float a3, float b1, float b2, float b3, float c1, float c2,
                  float c3) {
  return a1 * det2(b2, b3, c2, c3) - b1 * det2(a2, a3, c2, c3) + c1 * det2(a2, a3, b2, b3);
}

// Cofactor expansion along the first row.
inline float mat_det(const float* m) {
  float a1 = m[0], b1 = m[1], c1 = m[2], d1 = m[3];
  float a2 = m[4], b2 = m[5], c2 = m[6], d2 = m[7];
  float a3 = m[8], b3 = m[9], c3 = m[10], d3 = m[11];
  float a4 = m[12], b4 = m[13], c4 = m[14], d4 = m[15];
  return a1 * det3(b2, b3, b4, c2, c3, c4, d2, d3, d4) -
         b1 * det3(a2, a3, a4, c2, c3, c4, d2, d3, d4) +
         c1 * det3(a2, a3, a4, b2, b3, b4, d2, d3, d4) -
         d1 * det3(a2, a3, a4, b2, b3, b4, c2, c3, c4);
}

// p * M for kind 0 (a point: with translation, divided by w; w = 0 gives 0, as OSL),
// 1 (a vector) and 2 (a normal: n * transpose(inverse(M))).
inline void mat_transform(float* dst, const float* m, const float* p, int kind) {
  float x = p[0], y = p[1], z = p[2];
  if (kind == 2) {
    float inv[16];
    mat_invert(inv, m);
    // Row i of the inverse dotted with n.
    for (int i = 0; i < 3; ++i) dst[i] = x * inv[i * 4] + y * inv[i * 4 + 1] + z * inv[i * 4 + 2];
    return;
  }
  float r[3];
  if (kind == 0) {
    for (int j = 0; j < 3; ++j) r[j] = x * m[j] + y * m[4 + j] + z * m[8 + j] + m[12 + j];
    float w = x * m[3] + y * m[7] + z * m[11] + m[15];
    for (float& c : r) c = w != 0 ? c / w : 0.0f;
  } else {
    for (int j = 0; j < 3; ++j) r[j] = x * m[j] + y * m[4 + j] + z * m[8 + j];
  }
  std::memcpy(dst, r, sizeof r);
}

} // namespace lobe::math

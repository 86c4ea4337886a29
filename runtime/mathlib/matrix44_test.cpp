// matrix44.h against OSL 1.13.12: every expected value below is what OSL's testshade printed
// (%.9g, which round-trips a float) for the shader
//   float a = 0.3 + u * 1.7, b = v * 2.3 - 0.6;
//   matrix m = matrix(a, 0.1 * b, -b, 0.2 * a * b, 0.3 + b, 1.1, 0.7 * a, 0.01, b * b, 0.5,
//                     a - b, 0.3 * a, 0.1, v + 0.37, 0.9, 1.3 + a);
//   matrix r = matrix(1.7, 0.2 * a, 0.33, 0, 0.21, 0.9 - b, -0.4, 0, 0.6, 0.25, 1.2 * a, 0,
//                     0.3 * b, 0.1, 0.7, 1);                       // affine
//   printf("%.9g ...", m * r, 1 / m, 1 / r, m / r, determinant(m), determinant(r),
//          transform(m, point(0.3, 0.7 * a, 1.9)), the same as a vector and as a normal, ...);
// at its first point (`testshade -g 8 8 mt3`; all 64 points agree bit for bit), and, for the edge
// cases, `testshade mt4` (singular matrices, w = 0, a tiny affine determinant).
#include "matrix44.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <utility>

namespace {

using namespace lobe::math;

const float kM[16] = {0.300000012f,  -0.0600000024f, 0.600000024f, -0.0360000022f,
                      -0.300000012f, 1.10000002f,    0.210000008f, 0.00999999978f,
                      0.360000014f,  0.5f,           0.900000036f, 0.0900000036f,
                      0.100000001f,  0.370000005f,   0.899999976f, 1.5999999f};
const float kR[16] = {
    1.70000005f,  0.0600000024f, 0.330000013f, 0, 0.209999993f,  1.5f,         -0.400000006f, 0,
    0.600000024f, 0.25f,         0.360000014f, 0, -0.180000007f, 0.100000001f, 0.699999988f,  1};
const float kP[3] = {0.3f, 0.7f * kM[0], 1.9f};

void expect_bits(const float* got, const float* want, int n) {
  for (int i = 0; i < n; ++i) EXPECT_EQ(got[i], want[i]) << "element " << i;
}

// p transformed by m as a point (kind 0), vector (1) or normal (2) is `want`.
void expect_transform(const float* m, const float* p, int kind, const float* want) {
  float got[3];
  mat_transform(got, m, p, kind);
  expect_bits(got, want, 3);
}

TEST(Matrix44, ProductIsOsls) {
  const float want[16] = {0.863880038f,  0.0744000003f, 0.313800037f,  -0.0360000022f,
                          -0.154800028f, 1.68550014f,   -0.456400037f, 0.00999999978f,
                          1.24080014f,   1.00559998f,   0.305800021f,  0.0900000036f,
                          0.499700069f,  0.94599998f,   1.32899988f,   1.5999999f};
  float got[16];
  mat_mul(got, kM, kR);
  expect_bits(got, want, 16);
}

TEST(Matrix44, InverseOfAGeneralMatrixIsOsls) {
  const float want[16] = {-8.75022507f, -3.57708049f,  7.25049829f,  -0.582363904f,
                          -3.43720078f, -0.387193888f, 2.60315728f,  -0.221344665f,
                          5.58990288f,  1.71086538f,   -3.31631541f, 0.301622689f,
                          -1.80257881f, -0.649255633f, 0.810291231f, 0.542920947f};
  float got[16];
  EXPECT_TRUE(mat_invert(got, kM));
  expect_bits(got, want, 16);
}

TEST(Matrix44, InverseOfAnAffineMatrixIsOsls) {
  const float want[16] = {
      0.810753703f, 0.077148281f,  -0.657470524f, 0, -0.399802893f, 0.524456263f, 0.949215114f, 0,
      -1.07361519f, -0.492786169f, 3.21438503f,   0, 0.937446594f,  0.306391388f, -2.46333551f, 1};
  float got[16];
  EXPECT_TRUE(mat_invert(got, kR));
  expect_bits(got, want, 16);
  // m / r is m * inverse(r).
  const float div[16] = {-0.410702944f, -0.315024674f, 1.76311707f,   -0.0360000022f,
                         -0.899094105f, 0.453336239f,  1.89176536f,   0.00999999978f,
                         -0.789913595f, -0.125930846f, 2.90916467f,   0.0900000036f,
                         0.466809034f,  0.248482272f,  -0.762927532f, 1.5999999f};
  float prod[16];
  mat_mul(prod, kM, got);
  expect_bits(prod, div, 16);
}

TEST(Matrix44, DeterminantIsOsls) {
  EXPECT_EQ(mat_det(kM), -0.152574688f);
  EXPECT_EQ(mat_det(kR), 0.789389014f);
}

TEST(Matrix44, TransformsAreOsls) {
  const float point[3] = {0.460194111f, 0.869885981f, 1.60818255f};
  const float vector[3] = {0.711000025f, 1.16299999f, 1.93410003f};
  const float normal[3] = {10.3996925f, 3.83352757f, -4.26474667f};
  const float normal_affine[3] = {-0.989766717f, 1.79370356f, 5.68176174f};
  expect_transform(kM, kP, 0, point);
  expect_transform(kM, kP, 1, vector);
  expect_transform(kM, kP, 2, normal);
  expect_transform(kR, kP, 2, normal_affine);
}

// OSL: 1 / matrix(0), the inverse of a singular affine matrix, of a singular general matrix,
// and of an affine matrix whose determinant (1e-60) underflows are all the identity; a point
// transformed with w = 0 is (0, 0, 0); w = 2 divides; a normal through a singular matrix is
// unchanged (its inverse is the identity); both determinants are 0.
TEST(Matrix44, EdgeCasesAreOsls) {
  const float zero[16] = {};
  const float singular_affine[16] = {1, 2, 3, 0, 2, 4, 6, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const float singular[16] = {1, 2, 3, 4, 2, 4, 6, 8, 0, 0, 1, 0, 0, 0, 0, 1};
  const float tiny[16] = {1e-20f, 0, 0, 0, 0, 1e-20f, 0, 0, 0, 0, 1e-20f, 0, 0, 0, 0, 1};
  float id[16], got[16];
  mat_identity(id);
  for (const float* m : {zero, singular_affine, singular, tiny}) {
    EXPECT_FALSE(mat_invert(got, m));
    expect_bits(got, id, 16);
  }
  const float w0[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0};
  const float w2[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 2};
  const float p[3] = {1, 2, 3}, origin[3] = {0, 0, 0}, halved[3] = {3, 4, 5};
  expect_transform(w0, p, 0, origin);
  expect_transform(w2, p, 0, halved);
  expect_transform(singular_affine, p, 2, p);
  EXPECT_EQ(mat_det(singular_affine), 0.0f);
  EXPECT_EQ(mat_det(zero), 0.0f);
}

// Gauss-Jordan element by element, with a branch for the pivot and a swap of whole rows: the
// textbook form of the algorithm mat_invert_gauss_jordan computes with row vectors and masks.
bool gauss_jordan_reference(float* dst, const float* src) {
  float t[4][4], s[4][4];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) t[i][j] = src[4 * i + j], s[i][j] = i == j ? 1.0f : 0.0f;
  for (int i = 0; i < 3; ++i) {
    int pivot = i;
    float size = std::fabs(t[i][i]);
    for (int j = i + 1; j < 4; ++j)
      if (std::fabs(t[j][i]) > size) pivot = j, size = std::fabs(t[j][i]);
    if (size == 0) return false;
    if (pivot != i)
      for (int k = 0; k < 4; ++k) std::swap(t[i][k], t[pivot][k]), std::swap(s[i][k], s[pivot][k]);
    for (int j = i + 1; j < 4; ++j) {
      float f = t[j][i] / t[i][i];
      for (int k = 0; k < 4; ++k) t[j][k] -= f * t[i][k], s[j][k] -= f * s[i][k];
    }
  }
  for (int i = 3; i >= 0; --i) {
    float f = t[i][i];
    if (f == 0) return false;
    for (int k = 0; k < 4; ++k) t[i][k] /= f, s[i][k] /= f;
    for (int j = 0; j < i; ++j) {
      f = t[j][i];
      for (int k = 0; k < 4; ++k) t[j][k] -= f * t[i][k], s[j][k] -= f * s[i][k];
    }
  }
  std::memcpy(dst, s, sizeof s);
  return true;
}

// Every pivot order (random entries), ties between candidate pivots (the first row wins),
// zero and NaN entries: the same result and the same bits as the reference.
TEST(Matrix44, GaussJordanIsTheTextbookAlgorithmToTheBit) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  std::uniform_int_distribution<int> kind(0, 9);
  int mismatches = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    float m[16];
    for (float& x : m) {
      int k = kind(rng);
      x = k == 0 ? 0.0f : k == 1 ? 1.5f : k == 2 ? -1.5f : u(rng); // ties at +-1.5
    }
    if (trial % 1000 == 0) m[5] = std::numeric_limits<float>::quiet_NaN();
    float got[16], want[16];
    mat_identity(want);
    bool ok = mat_invert_gauss_jordan(got, m), want_ok = gauss_jordan_reference(want, m);
    EXPECT_EQ(ok, want_ok);
    if (std::memcmp(got, want, sizeof got) != 0 && ++mismatches <= 3) ADD_FAILURE() << trial;
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(Matrix44, IdentityIsExact) {
  float id[16];
  mat_identity(id);
  EXPECT_TRUE(mat_is_identity(id));
  id[12] = -0.0f; // -0 is not the identity's +0
  EXPECT_FALSE(mat_is_identity(id));
}

} // namespace

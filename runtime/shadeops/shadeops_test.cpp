// Unit tests of the shadeops called directly (no JIT): formatting, strings, matrices, colour,
// noise. Expected values are worked by hand or from closed forms.
#include "env.h"
#include "format.h"
#include "lobe/context.h"
#include "shadeop_decls.h"
#include "shadeops.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace lobe;
using namespace lobe::shadeops;

extern "C" {
const char* lobe_format(RuntimeEnv*, const char*, const char*, const void* const*);
const char* lobe_substr(RuntimeEnv*, const char*, int, int);
const char* lobe_concat(RuntimeEnv*, const char*, const char*);
int lobe_regex(const char*, const char*, int);
int lobe_regex_results(const char*, const char*, int, int*, int);
void lobe_mat_inverse(float*, const float*);
int lobe_get_matrix(ShaderGlobals*, const char*, const char*, float*);
float lobe_mat_det(const float*);
void lobe_transform(float*, const float*, const float*, int);
void lobe_noise(int, const float*, int, const float*, float*, int, float*);
void lobe_range_error(ShaderGlobals*, int, int, const char*, const char*, int, const char*);
void lobe_noise_named(ShaderGlobals*, const char*, const float*, int, const float*, float*, int,
                      float*, const char*, int);
void lobe_noise_d(int, const float*, const float*, const float*, int, const float*, float*, float*,
                  float*, int);
void lobe_gabor(const float*, const float*, const float*, int, const float*, const GaborOptions*,
                float*, float*, float*, int);
int lobe_split(RuntimeEnv*, const char*, const char*, int, const char**, int);
int lobe_dict_find(ShaderGlobals*, const char*, const char*);
int lobe_dict_find_node(ShaderGlobals*, int, const char*);
int lobe_dict_next(ShaderGlobals*, int);
int lobe_dict_value(ShaderGlobals*, RuntimeEnv*, int, const char*, int, int, void*);
int lobe_pointcloud(ShaderGlobals*, RuntimeEnv*, const char*);
}

TEST(Format, TriplesIntsAndStrings) {
  RuntimeEnv env;
  float t[3] = {1, 0.5f, 0.25f};
  int i = 42;
  float f = 3.0f;
  const char* s = env.strings.intern("hey");
  const void* args[] = {t, &i, &f, &s};
  EXPECT_EQ(format_values(env, "P = %g, i = %d, f = %.2f, s = %s%%\n", "tifs", args),
            "P = 1 0.5 0.25, i = 42, f = 3.00, s = hey%\n");
}

TEST(Format, ArraysAndConversions) {
  RuntimeEnv env;
  float a[3] = {1, 2, 3.5f};
  int n = 7;
  const void* args[] = {a, &n};
  // %d of a float truncates, %g of an int promotes.
  EXPECT_EQ(format_values(env, "[%g] %g %d", "f{3}i", args), "[1 2 3.5] 7 %d");
}

// Infinities and NaNs, and %o of a negative int, in each of OSL's three rules. Expected text
// from OSL 1.13.12 (testshade test, the values varying so that format() runs while shading, or
// constant so that -O2 folds it):
//   printf("[%5g] [%6f] [%10.3e] [%+6g] [%05g]", inf, -inf, nan, inf, inf)
//     -> [inf  ] [-inf  ] [nan       ] [+inf  ] [  inf]
//   format("%g %f %e [%5g]", inf, -inf, nan, inf) -> Inf -Inf NaN [  Inf]
//   format("%o %#o", -8, -8) -> 37777777770 037777777770; printf("%o", -8) -> -10
TEST(Format, NonFiniteFloatsAndNegativeOctalAsOsl) {
  RuntimeEnv env;
  float inf = INFINITY, ninf = -INFINITY, nan = std::nanf("");
  const void* p[] = {&inf, &ninf, &nan, &inf, &inf};
  EXPECT_EQ(format_values(env, "[%5g] [%6f] [%10.3e] [%+6g] [%05g]", "fffff", p),
            "[inf  ] [-inf  ] [nan       ] [+inf  ] [  inf]");
  const void* q[] = {&inf, &ninf, &nan, &inf};
  EXPECT_EQ(format_values(env, "%g %f %e [%5g]", "ffff", q, FormatRule::Format),
            "Inf -Inf NaN [  Inf]");
  EXPECT_EQ(format_values(env, "%g %f %g [%5g]", "ffff", q, FormatRule::FormatFolded),
            "inf -inf nan [  inf]");
  int m8 = -8;
  const void* o[] = {&m8, &m8};
  EXPECT_EQ(format_values(env, "%o %#o", "ii", o, FormatRule::Format), "37777777770 037777777770");
  EXPECT_EQ(format_values(env, "%o %#o", "ii", o, FormatRule::FormatFolded),
            "37777777770 037777777770");
  EXPECT_EQ(format_values(env, "%o", "i", o), "-10");
}

// format() of ints is remembered per thread: asked again, or after more formats than the memo
// holds, it gives the same interned string, read from the format's text (not its address) and
// interned in the asking table (not one since destroyed).
TEST(Format, InternedIntFormatsRemembered) {
  RuntimeEnv env;
  for (int round = 0; round < 2; ++round)
    for (int a = 0; a < 40; ++a)
      for (int b = -3; b < 17; b += 4) {
        const void* args[] = {&a, &b};
        std::string want = "tile_" + std::to_string(a) + "_" + std::to_string(b);
        const char* got = lobe_format(&env, "tile_%d_%d", "ii", args);
        EXPECT_STREQ(got, want.c_str());
        EXPECT_EQ(got, env.strings.intern(want));
      }
  int five = 5;
  const void* one[] = {&five};
  char fmt[8] = "a%d";
  EXPECT_STREQ(lobe_format(&env, fmt, "i", one), "a5");
  fmt[0] = 'b'; // the same address, another text
  EXPECT_STREQ(lobe_format(&env, fmt, "i", one), "b5");
  EXPECT_STREQ(lobe_format(&env, "none", "", nullptr), "none");
  const void* two[] = {&five, &five};
  EXPECT_STREQ(lobe_format(&env, "%x|%5d", "ii", two), "5|    5");
  int a = 7, b = 8;
  const void* ab[] = {&a, &b};
  for (int round = 0; round < 3; ++round) { // a table destroyed, another made, maybe in its place
    auto other = std::make_unique<RuntimeEnv>();
    const char* got = lobe_format(other.get(), "tile_%d_%d", "ii", ab);
    EXPECT_STREQ(got, "tile_7_8");
    EXPECT_EQ(got, other->strings.intern("tile_7_8"));
    EXPECT_NE(got, env.strings.intern("tile_7_8"));
  }
}

// What the memo does not take is formatted as before: strings, arrays, more than four ints.
TEST(Format, InternedOtherFormats) {
  RuntimeEnv env;
  const char* s = env.strings.intern("ab");
  int i[5] = {1, 2, 3, 4, 5};
  const void* mixed[] = {&s, &i[0]};
  EXPECT_STREQ(lobe_format(&env, "%s_%d", "si", mixed), "ab_1");
  const void* array[] = {i};
  EXPECT_STREQ(lobe_format(&env, "[%d]", "i{3}", array), "[1 2 3]");
  const void* five[] = {&i[0], &i[1], &i[2], &i[3], &i[4]};
  EXPECT_STREQ(lobe_format(&env, "%d%d%d%d%d", "iiiii", five), "12345");
  EXPECT_STREQ(lobe_format(&env, "%d%d%d%d", "iiii", five), "1234");
}

TEST(Strings, InternedAndSubstr) {
  RuntimeEnv env;
  EXPECT_EQ(env.strings.intern("abc"), env.strings.intern(std::string("ab") + "c"));
  EXPECT_STREQ(lobe_substr(&env, "hello", 1, 3), "ell");
  EXPECT_STREQ(lobe_substr(&env, "hello", -3, 2), "ll");
  EXPECT_STREQ(lobe_substr(&env, "hello", 3, 100), "lo");
  EXPECT_STREQ(lobe_concat(&env, "ab", "cd"), "abcd");
  EXPECT_EQ(lobe_regex("foo123", "[0-9]+", 0), 1);
  EXPECT_EQ(lobe_regex("foo123", "[0-9]+", 1), 0);
  EXPECT_EQ(lobe_regex("foo", "(", 0), 0); // invalid pattern: no match, no crash
}

TEST(Strings, RegexResults) {
  int m[5] = {-1, -1, -1, -1, -1};
  EXPECT_EQ(lobe_regex_results("ab12", "b([0-9])", 0, m, 5), 1);
  EXPECT_EQ(m[0], 1); // "b1": [1, 3), group 1 "1": [2, 3), then the pattern's length (8)
  EXPECT_EQ(m[1], 3);
  EXPECT_EQ(m[2], 2);
  EXPECT_EQ(m[3], 3);
  EXPECT_EQ(m[4], 8);
  EXPECT_EQ(lobe_regex_results("ab12", "b([0-9])", 1, m, 2), 0); // not a full match
  EXPECT_EQ(m[0], 8);
  EXPECT_EQ(lobe_regex_results("x", "(", 0, m, 1), 0); // invalid pattern
  EXPECT_EQ(m[0], 1);
}

// Compiled patterns are kept per thread: the same pattern keeps its meaning after many others
// (more than the cache holds) and an invalid one stays invalid when asked again.
TEST(Strings, RegexCacheKeepsMeaning) {
  for (int round = 0; round < 3; ++round) {
    for (int i = 0; i < 100; ++i) {
      // Appended piecewise: `"x" + std::to_string(i)` trips GCC 12's -Wrestrict (bug 105329).
      std::string name = "x", other = "x";
      name += std::to_string(i);
      other += std::to_string(i + 1);
      std::string p = "^" + name;
      p += "$";
      EXPECT_EQ(lobe_regex(name.c_str(), p.c_str(), 1), 1) << p;
      EXPECT_EQ(lobe_regex(other.c_str(), p.c_str(), 1), 0) << p;
    }
    EXPECT_EQ(lobe_regex("foo", "(", 0), 0);
    EXPECT_EQ(lobe_regex("a(b", "a\\(b", 1), 1);
  }
}

// The pieces of split() in "[a][b]" form, with the count; expectations are OSL 1.13.12's
// (testshade -O0, which leaves the unwritten entries alone).
std::string split_of(RuntimeEnv& env, const char* s, const char* sep, int maxsplit, int n = 5) {
  std::vector<const char*> r(size_t(n), "x");
  int count = lobe_split(&env, s, sep, maxsplit, r.data(), n);
  std::string out = std::to_string(count);
  for (const char* p : r) out += std::string("[") + p + "]";
  return out;
}

TEST(Strings, SplitAsOSL) {
  RuntimeEnv env;
  EXPECT_EQ(split_of(env, "a,b,,c,d,e", ",", 3), "3[a][b][,c,d,e][x][x]");
  EXPECT_EQ(split_of(env, "a,", ",", 5), "2[a][][x][x][x]");
  EXPECT_EQ(split_of(env, ",,", ",", 2), "2[][,][x][x][x]");
  EXPECT_EQ(split_of(env, "aaa", "aa", 5), "2[][a][x][x][x]");
  EXPECT_EQ(split_of(env, " a ", " ", 5), "3[][a][][x][x]");
  EXPECT_EQ(split_of(env, "a b  ", "", 2), "2[a][b  ][x][x][x]");
  EXPECT_EQ(split_of(env, "  a b  c  d e", "", 2), "2[a][b  c  d e][x][x][x]");
  EXPECT_EQ(split_of(env, "a\tb\nc", "", 5), "3[a][b][c][x][x]");
  EXPECT_EQ(split_of(env, "a,b,c,d,e,f,g", ",", 5), "5[a][b][c][d][e,f,g]");
  EXPECT_EQ(split_of(env, "a,b,c", ",", 10, 2), "2[a][b,c]"); // maxsplit clamped to the array
  EXPECT_EQ(split_of(env, "   ", "", 5), "0[x][x][x][x][x]");
  EXPECT_EQ(split_of(env, "", ",", 5), "0[x][x][x][x][x]");
  EXPECT_EQ(split_of(env, "a,b", ",", 0), "0[x][x][x][x][x]");
  EXPECT_EQ(split_of(env, "a,b", ",", -1), "0[x][x][x][x][x]");
}

// Dictionaries: node ids in query order (a query asked again gives its first id), queries
// relative to a node, values parsed by type, and errors reported once with OSL's wording.
TEST(Dictionaries, FindNextValueAndErrors) {
  RuntimeEnv env;
  ShadingContext ctx;
  ShaderGlobals sg{};
  sg.context = &ctx;
  const char* xml = "<w><s name=\"a\" v=\"3\" c=\"1, 2 3\"/><s name=\"b\"><t/></s></w>";
  int first = lobe_dict_find(&sg, xml, "//s");
  EXPECT_EQ(first, 1);
  EXPECT_EQ(lobe_dict_next(&sg, 1), 2);
  EXPECT_EQ(lobe_dict_next(&sg, 2), 0);
  EXPECT_EQ(lobe_dict_find_node(&sg, 2, "t"), 3);
  EXPECT_EQ(lobe_dict_find(&sg, xml, "//s"), 1);
  EXPECT_EQ(lobe_dict_find(&sg, xml, "//none"), 0);
  EXPECT_EQ(lobe_dict_find_node(&sg, 99, "t"), 0);
  const char* name = nullptr;
  EXPECT_EQ(lobe_dict_value(&sg, &env, 2, "name", int(DataType::Base::String), 0, &name), 1);
  EXPECT_STREQ(name, "b");
  float c[3] = {0, 0, 0}, m[16];
  EXPECT_EQ(lobe_dict_value(&sg, &env, 1, "c", int(DataType::Base::Color), 0, c), 1);
  EXPECT_EQ(c[0], 1.0f);
  EXPECT_EQ(c[2], 3.0f);
  EXPECT_EQ(lobe_dict_value(&sg, &env, 1, "v", int(DataType::Base::Matrix), 0, m), 1);
  EXPECT_EQ(m[15], 3.0f); // no number left: the last one repeats
  int i = -1;
  EXPECT_EQ(lobe_dict_value(&sg, &env, 1, "missing", int(DataType::Base::Int), 0, &i), 0);
  EXPECT_EQ(i, -1);
  EXPECT_EQ(ctx.errors, 0);
  EXPECT_EQ(lobe_dict_find(&sg, "<open", "//x"), -1);
  EXPECT_EQ(lobe_dict_find(&sg, "<open", "//x"), -1);
  EXPECT_EQ(lobe_dict_find(&sg, xml, "///[["), 0);
  EXPECT_EQ(lobe_dict_find(&sg, "no_such_file.xml", "//x"), -1);
  EXPECT_EQ(ctx.errors, 3);
  EXPECT_NE(ctx.output.find("ERROR: XML parsed with errors: Error parsing start element tag, at "
                            "offset 4\n"),
            std::string::npos)
      << ctx.output;
  EXPECT_NE(ctx.output.find("ERROR: Invalid dict_find query '///[[': Unrecognized node test\n"),
            std::string::npos)
      << ctx.output;
  EXPECT_NE(ctx.output.find("XML parsed with errors: File was not found, at offset 0"),
            std::string::npos)
      << ctx.output;
}

TEST(PointClouds, NothingFoundWarnedOnce) {
  RuntimeEnv env;
  ShadingContext ctx;
  ShaderGlobals sg{};
  sg.context = &ctx;
  EXPECT_EQ(lobe_pointcloud(&sg, &env, "pointcloud_search"), 0);
  EXPECT_EQ(lobe_pointcloud(&sg, &env, "pointcloud_write"), 0);
  EXPECT_EQ(ctx.warnings, 1);
}

TEST(Matrix, InverseDeterminantTransform) {
  // Scale by 2 along x, translate by (1,2,3) (row-vector convention: translation in row 3).
  float m[16] = {2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1};
  EXPECT_FLOAT_EQ(lobe_mat_det(m), 2.0f);
  float inv[16];
  lobe_mat_inverse(inv, m);
  EXPECT_FLOAT_EQ(inv[0], 0.5f);
  EXPECT_FLOAT_EQ(inv[12], -0.5f);
  EXPECT_FLOAT_EQ(inv[13], -2.0f);
  float p[3] = {1, 1, 1}, r[3];
  lobe_transform(r, m, p, 0);
  EXPECT_FLOAT_EQ(r[0], 3.0f);
  EXPECT_FLOAT_EQ(r[1], 3.0f);
  EXPECT_FLOAT_EQ(r[2], 4.0f);
  lobe_transform(r, m, p, 1); // vectors ignore translation
  EXPECT_FLOAT_EQ(r[0], 2.0f);
  EXPECT_FLOAT_EQ(r[2], 1.0f);
  float n[3] = {1, 0, 0};
  lobe_transform(r, m, n, 2); // normals by the inverse transpose: x scaled by 1/2
  EXPECT_FLOAT_EQ(r[0], 0.5f);
}

// A renderer that knows one space, "mine", whose matrix the test sets.
struct OneSpaceRenderer : RendererServices {
  float m[16] = {};
  bool get_matrix(const ShaderGlobals&, std::string_view space, float* out) const override {
    if (space != "mine") return false;
    std::copy(m, m + 16, out);
    return true;
  }
};

// The product a * b of OSL's getmatrix, written out: sum over k of a[i][k] * b[k][j], in k
// order, in float.
std::array<float, 16> product(const float* a, const float* b) {
  std::array<float, 16> r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      float s = a[i * 4] * b[j];
      for (int k = 1; k < 4; ++k) s = s + a[i * 4 + k] * b[k * 4 + j];
      r[size_t(i * 4 + j)] = s;
    }
  return r;
}

// getmatrix(from, to) is from -> common times common -> to, and the product runs even with
// the identity on one side, as in OSL: it turns a -0 into +0 and an Inf into NaN. Lobe skips
// the product only where it changes no bit; these cases tell the two apart.
TEST(Matrix, NamedSpacesThroughTheRendererKeepTheProductsBits) {
  OneSpaceRenderer renderer;
  ShadingContext ctx;
  ctx.renderer = &renderer;
  ShaderGlobals sg{};
  sg.context = &ctx;
  const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const float inf = std::numeric_limits<float>::infinity();
  const float cases[][16] = {
      {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 1, 2, 3, 1},     // clean: the product is itself
      {2, -0.0f, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 1, 2, 3, 1}, // -0 at [0][1]: +0 after
      {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, inf, 0, 1, 2, 3, 1},   // Inf: NaN along its row
  };
  for (const auto& c : cases) {
    std::copy(c, c + 16, renderer.m);
    float got[16];
    for (const char* other : {"world", "common"}) {
      ASSERT_EQ(lobe_get_matrix(&sg, "mine", other, got), 1);
      std::array<float, 16> want = product(c, id);
      for (int k = 0; k < 16; ++k) {
        EXPECT_EQ(std::isnan(got[k]), std::isnan(want[size_t(k)])) << k;
        if (!std::isnan(want[size_t(k)])) {
          EXPECT_EQ(got[k], want[size_t(k)]) << k;
          EXPECT_EQ(std::signbit(got[k]), std::signbit(want[size_t(k)])) << k;
        }
      }
    }
  }
  // The -0 case by hand: 2 * 0 + -0 * 1 + ... = +0 at [0][1].
  std::copy(cases[1], cases[1] + 16, renderer.m);
  float got[16];
  lobe_get_matrix(&sg, "mine", "world", got);
  EXPECT_EQ(got[1], 0.0f);
  EXPECT_FALSE(std::signbit(got[1]));
  // The identity both ways, and an unknown name (reported; its half is the identity).
  lobe_get_matrix(&sg, "common", "world", got);
  for (int k = 0; k < 16; ++k) EXPECT_EQ(got[k], id[k]);
  EXPECT_EQ(lobe_get_matrix(&sg, "nowhere", "world", got), 0);
  EXPECT_EQ(ctx.errors, 1);
}

TEST(Noise, LatticeRangeDerivativeCellPeriod) {
  float x[3] = {3, -2, 7}, v, g[3];
  lobe_noise(kPerlin, x, 3, nullptr, &v, 1, g);
  EXPECT_EQ(v, 0.0f); // signed gradient noise vanishes on the lattice
  lobe_noise(kUPerlin, x, 3, nullptr, &v, 1, nullptr);
  EXPECT_EQ(v, 0.5f);
  for (int n = 1; n <= 4; ++n) { // every dimension, scalar and vector, on the lattice
    float l[4] = {-5, 2, 11, -1}, o[3];
    lobe_noise(kPerlin, l, n, nullptr, o, 3, nullptr);
    for (float c : o) EXPECT_EQ(c, 0.0f) << n;
  }
  for (int n = 1; n <= 4; ++n) {
    float lo = 1, hi = -1;
    for (int i = 0; i < 4000; ++i) {
      float p[4] = {i * 0.137f - 50, i * 0.0713f, i * -0.0291f, i * 0.0517f + 3};
      lobe_noise(kUPerlin, p, n, nullptr, &v, 1, nullptr);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    EXPECT_GE(lo, 0.0f) << n;
    EXPECT_LE(hi, 1.0f) << n;
    EXPECT_LT(lo, 0.3f) << n; // it actually varies
    EXPECT_GT(hi, 0.7f) << n;
  }
  float c1[2] = {2.1f, 5.9f}, c2[2] = {2.8f, 5.2f}, v1, v2;
  lobe_noise(kCell, c1, 2, nullptr, &v1, 1, nullptr);
  lobe_noise(kCell, c2, 2, nullptr, &v2, 1, nullptr);
  EXPECT_EQ(v1, v2);
  float per[1] = {4}, q1[1] = {0.3f}, q2[1] = {4.3f};
  lobe_noise(kPerlin, q1, 1, per, &v1, 1, nullptr);
  lobe_noise(kPerlin, q2, 1, per, &v2, 1, nullptr);
  EXPECT_NEAR(v1, v2, 1e-5);
}

// Analytic derivatives (carried through OSL's formulas) against central differences, for 1-4
// input dimensions, scalar and vector results, plain and periodic.
TEST(Noise, DerivativesMatchFiniteDifferences) {
  const float p[4] = {0.3f, 1.7f, -0.4f, 2.6f}, period[4] = {3, 2, 5, 4};
  for (int kind : {kPerlin, kUPerlin})
    for (int n = 1; n <= 4; ++n)
      for (int nout : {1, 3})
        for (const float* per : {(const float*)nullptr, period}) {
          float out[3], grad[12];
          lobe_noise(kind, p, n, per, out, nout, grad);
          for (int k = 0; k < n; ++k) {
            float a[4] = {p[0], p[1], p[2], p[3]}, b[4] = {p[0], p[1], p[2], p[3]}, va[3], vb[3];
            a[k] += 1e-3f;
            b[k] -= 1e-3f;
            lobe_noise(kind, a, n, per, va, nout, nullptr);
            lobe_noise(kind, b, n, per, vb, nout, nullptr);
            for (int j = 0; j < nout; ++j)
              EXPECT_NEAR(grad[j * n + k], (va[j] - vb[j]) / 2e-3f, 1e-2)
                  << kind << " n=" << n << " nout=" << nout << " k=" << k << " j=" << j;
          }
        }
  float x[1] = {0.5f}, out[3], grad[3] = {1, 1, 1};
  lobe_noise(kCell, x, 1, nullptr, out, 3, grad); // cell/hash: piecewise constant
  for (float g : grad) EXPECT_EQ(g, 0.0f);
}

// Exact values, as OSL computes them (oslnoise.h: lookup3 inthash, bits_to_01, perlin with
// OSL's grad/fade/lerp and scale constants). Derived by hand and with the independent Python
// transcription runtime/shadeops/noise_reference.py (binary32 rounding after every operation;
// `python3 runtime/shadeops/noise_reference.py` prints these), not by this C++.
TEST(Noise, OslValues) {
  // lookup3 with one key: a = b = c = 0xdeadbeef + (1 << 2) + 13, a += 0, bjfinal -> c =
  // 0x9519dc65 = inthash(0); inthash(1) = 0x4ad7c6a0. cellnoise(0.5) = inthash(0) * 2^-32
  // (float(UINT_MAX) rounds to 2^32), rounded to float.
  float x[4] = {0.5f}, v, o3[3], per[4] = {4, 4, 4, 4};
  lobe_noise(kCell, x, 1, nullptr, &v, 1, nullptr);
  EXPECT_EQ(v, float(double(0x9519dc65u) * 0x1p-32));
  EXPECT_EQ(v, 0.582425833f);
  // noise(0.5): h0 = inthash(0) & 15 = 5 -> grad 6 * 0.5 = 3; h1 = inthash(1) & 15 = 0 ->
  // grad 1 * -0.5; fade(0.5) = 0.5 -> lerp 1.25; * scale1 0.25 = 0.3125; 0.5 * (1 + 0.3125).
  lobe_noise(kUPerlin, x, 1, nullptr, &v, 1, nullptr);
  EXPECT_EQ(v, 0.65625f);
  lobe_noise(kPerlin, x, 1, nullptr, &v, 1, nullptr);
  EXPECT_EQ(v, 0.3125f);
  // cellnoise(vector) appends the channel as a last key: inthash(0, j) for j = 0, 1, 2.
  lobe_noise(kCell, x, 1, nullptr, o3, 3, nullptr);
  EXPECT_EQ(o3[0], 0.86031276f);
  EXPECT_EQ(o3[1], 0.842521071f);
  EXPECT_EQ(o3[2], 0.97482121f);
  float c[3] = {2.1f, 5.9f, 0.5f};
  lobe_noise(kCell, c, 2, nullptr, &v, 1, nullptr);
  EXPECT_EQ(v, 0.611083984f);
  lobe_noise(kCell, c, 3, nullptr, &v, 1, nullptr);
  EXPECT_EQ(v, 0.976975441f);
  float h[1] = {1.5f}; // hashnoise: inthash of the float bits 0x3fc00000
  lobe_noise(kHash, h, 1, nullptr, &v, 1, nullptr);
  EXPECT_EQ(v, 0.914302945f);
  const float p[4] = {0.3f, 1.7f, -0.4f, 2.6f};
  // OSL 1.13.12's values (testshade): 3-D and 4-D interpolate along z (and w) first, as OSL's
  // SIMD code does.
  const float snoise[4] = {0.348075002f, -0.646099925f, 0.0186578184f, 0.380862951f};
  for (int n = 1; n <= 4; ++n) {
    lobe_noise(kPerlin, p, n, nullptr, &v, 1, nullptr);
    EXPECT_EQ(v, snoise[n - 1]) << n;
  }
  lobe_noise(kUPerlin, p, 3, nullptr, &v, 1, nullptr);
  EXPECT_EQ(v, 0.509328902f);
  // Vector perlin: one inthash per corner, channels from h, h >> 8, h >> 16 (OSL's HashVector).
  lobe_noise(kPerlin, p, 3, nullptr, o3, 3, nullptr);
  EXPECT_EQ(o3[0], 0.0186578184f);
  EXPECT_EQ(o3[1], 0.0256961975f);
  EXPECT_EQ(o3[2], -0.489490867f);
  // Periodic: corners wrapped by imod(., floor(period)).
  float q[1] = {1.3f}, qm[1] = {-2.7f};
  lobe_noise(kPerlin, q, 1, per, &v, 1, nullptr);
  EXPECT_EQ(v, 0.291080922f);
  lobe_noise(kPerlin, qm, 1, per, &v, 1, nullptr);
  EXPECT_EQ(v, 0.291080922f);
}

// Value-only 3-D and 4-D gradient noise, float and vector, at ordinary, negative, large and
// lattice points (the vector-lane code paths of noise.cpp). Expected: OSL 1.13.12, `oslc n4.osl;
// testshade -g 1 1 n4` printing `noise("perlin", p, w)`, `snoise(p, w)` and
// `vector(snoise(p))` with %.9g at these p and w.
TEST(Noise, GradientNoise3dAnd4dAsOsl) {
  const float p[4][3] = {
      {0.3f, 1.7f, -0.4f}, {-12.25f, 3.5f, 7.75f}, {101.1f, -0.02f, 44.4f}, {5, 6, 7}};
  const float w[4] = {2.6f, -3.3f, 0.5f, 8};
  const float n4[4][3] = {{0.380862951f, 0.113822117f, -0.632481456f},
                          {0.49426201f, 0.371457756f, -0.0644355342f},
                          {-0.378766119f, -0.043003656f, 0.436642349f},
                          {0, 0, 0}};
  const float n3[4][3] = {{0.0186578184f, 0.0256961975f, -0.489490867f},
                          {0.0710552186f, 0.256891221f, 0.0240977593f},
                          {0.091456905f, -0.29080084f, 0.235086024f},
                          {0, 0, 0}};
  for (int i = 0; i < 4; ++i) {
    float x[4] = {p[i][0], p[i][1], p[i][2], w[i]}, v3[3], v;
    lobe_noise(kPerlin, x, 4, nullptr, v3, 3, nullptr);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(v3[c], n4[i][c]) << i << " " << c;
    lobe_noise(kPerlin, x, 4, nullptr, &v, 1, nullptr);
    EXPECT_EQ(v, n4[i][0]) << i;
    lobe_noise(kPerlin, x, 3, nullptr, v3, 3, nullptr);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(v3[c], n3[i][c]) << i << " " << c;
  }
}

// Simplex noise values as OSL's simplexnoise.cpp computes them, from the independent Python
// transcription runtime/shadeops/noise_reference.py (binary32 rounding after every operation),
// not from this C++: channel j of a vector result is the noise with seed j.
TEST(Noise, SimplexValues) {
  const float p[4] = {0.3f, 1.7f, -0.4f, 2.6f}, q[4] = {-3.71f, 12.25f, 0.83f, -5.4f};
  const float vp[4][3] = {{-0.245098889f, -0.153989658f, 0.0399643481f},
                          {-0.0409611762f, -0.118609093f, 0.532899082f},
                          {-0.000524203584f, -0.195786819f, 0.003108826f},
                          {-0.274919122f, 0.160436407f, -0.298546612f}};
  const float vq[4][3] = {{-0.150754213f, 0.0192775037f, 0.564461768f},
                          {-0.285048127f, -0.152325839f, 0.515406013f},
                          {0.305916905f, 0.0888545439f, -0.429894656f},
                          {0.0298274849f, 0.0269907266f, 0.062671721f}};
  const float up[4] = {0.377450556f, 0.479519427f, 0.499737889f, 0.362540424f};
  const float uq[4] = {0.424622893f, 0.357475936f, 0.652958453f, 0.514913738f};
  for (int n = 1; n <= 4; ++n) {
    float v, o[3];
    lobe_noise(kSimplex, p, n, nullptr, &v, 1, nullptr);
    EXPECT_EQ(v, vp[n - 1][0]) << n;
    lobe_noise(kSimplex, p, n, nullptr, o, 3, nullptr);
    for (int j = 0; j < 3; ++j) EXPECT_EQ(o[j], vp[n - 1][j]) << n << " " << j;
    lobe_noise(kSimplex, q, n, nullptr, o, 3, nullptr);
    for (int j = 0; j < 3; ++j) EXPECT_EQ(o[j], vq[n - 1][j]) << n << " " << j;
    lobe_noise(kUSimplex, p, n, nullptr, &v, 1, nullptr);
    EXPECT_EQ(v, up[n - 1]) << n;
    lobe_noise(kUSimplex, q, n, nullptr, &v, 1, nullptr);
    EXPECT_EQ(v, uq[n - 1]) << n;
  }
}

namespace {

// Uniform points in [-r, r]^4 from a fixed seed (the same points on every run).
struct Points {
  explicit Points(float r = 100) : u(-r, r) {}
  std::mt19937 rng{12345};
  std::uniform_real_distribution<float> u;
  std::array<float, 4> next() { return {u(rng), u(rng), u(rng), u(rng)}; }
};

float simplex_at(const float* x, int n) {
  float v;
  lobe_noise(kSimplex, x, n, nullptr, &v, 1, nullptr);
  return v;
}

} // namespace

// Continuity: a step of 1e-4 along any axis changes the noise by at most 1.5e-3 (measured
// worst 2.9e-4 / 5.9e-4 / 6.0e-4 / 4.6e-4 in 1-4-D). Gustavson's 0.6 radius in 3-D and 4-D (a
// corner's support cut at the simplex boundary) makes jumps these steps find (worst 5.9e-3 and
// 2.6e-3), stepping to the corners along the smallest offsets first jumps by ~0.6.
TEST(Noise, SimplexIsContinuous) {
  Points pts;
  for (int n = 1; n <= 4; ++n) {
    float worst = 0;
    for (int i = 0; i < 100000; ++i) {
      std::array<float, 4> p = pts.next();
      float v = simplex_at(p.data(), n);
      for (int k = 0; k < n; ++k) {
        std::array<float, 4> s = p;
        s[k] += 1e-4f;
        worst = std::max(worst, std::abs(simplex_at(s.data(), n) - v));
      }
    }
    EXPECT_LT(worst, 1.5e-3f) << n;
    std::printf("simplex %d-D worst change over a 1e-4 step %.2e\n", n, worst);
  }
}

// At a vertex of the simplex lattice only that vertex is within the support radius (every
// other corner is at distance^2 >= 0.67 > 0.5), and its offset is 0: the noise is 0 and its
// gradient is scale * t^4 * g with t = 0.5 (1 in 1-D), so |gradient| = 0.36 |g| (|g| in 1..8)
// in 1-D, 64/16 (1 or sqrt(2)) in 2-D, 68/16 sqrt(2) in 3-D and 54/16 sqrt(3) in 4-D. Integer
// points whose coordinates sum to 0 are vertices exactly (the unskew moves a lattice point by G *
// sum).
TEST(Noise, SimplexZeroAtLatticeVertices) {
  const float norm[4] = {0, 5.65685425f, 6.01040764f, 5.84567148f}; // and 4 in 2-D
  const int vertices[][4] = {{0, 0, 0, 0}, {3, -3, 5, -5}, {-7, 2, 4, 1}, {12, -20, 8, 0}};
  for (int n = 1; n <= 4; ++n)
    for (const int* iv : vertices) {
      float x[4], v[3], g[12];
      int sum = 0;
      for (int k = 0; k < n - 1; ++k) sum += iv[k];
      for (int k = 0; k < n; ++k) x[k] = float(k == n - 1 && n > 1 ? -sum : iv[k]);
      lobe_noise(kSimplex, x, n, nullptr, v, 3, g);
      for (int j = 0; j < 3; ++j) {
        EXPECT_EQ(v[j], 0.0f) << n << " " << x[0];
        float len = 0;
        for (int k = 0; k < n; ++k) len += g[j * n + k] * g[j * n + k];
        len = std::sqrt(len);
        if (n == 1) {
          float m = len / 0.36f; // t = 1 at the vertex in 1-D
          EXPECT_NEAR(m, std::round(m), 1e-5) << x[0];
          EXPECT_GE(std::round(m), 1.0f);
          EXPECT_LE(std::round(m), 8.0f);
        } else {
          float want = n == 2 && len < 5 ? 4.0f : norm[n - 1];
          EXPECT_NEAR(len, want, 1e-5) << n << " " << x[0];
        }
      }
    }
}

// |n| <= 1 over 1e5 random points per dimension, and the range is actually used. Measured
// extremes (these points): 1-D [-0.9112, 0.9113] (the bound is 0.36 * 2 * 8 * 0.5 * 0.75^4 =
// 0.911), 2-D [-0.9120, 0.9123], 3-D [-0.8844, 0.8833], 4-D [-0.8410, 0.8579].
TEST(Noise, SimplexRange) {
  Points pts;
  for (int n = 1; n <= 4; ++n) {
    float lo = 0, hi = 0;
    for (int i = 0; i < 100000; ++i) {
      std::array<float, 4> p = pts.next();
      float v = simplex_at(p.data(), n);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    EXPECT_GE(lo, -1.0f) << n;
    EXPECT_LE(hi, 1.0f) << n;
    EXPECT_LT(lo, -0.5f) << n; // both signs reach past 0.5
    EXPECT_GT(hi, 0.5f) << n;
    std::printf("simplex %d-D range [%.4f, %.4f]\n", n, lo, hi);
  }
}

// Analytic gradient against central differences (h = 1e-3) at 2000 random points in
// [-10, 10]^n per dimension and channel, simplex and usimplex. The difference's error is h^2/6
// times the third derivative plus the float rounding of the noise over 2h, which grows with |x|
// (at |x| ~ 100 one ulp, 7.6e-6, of the offset from the lattice alone gives ~1e-2), hence the
// smaller domain. Measured worst 1.8e-4 / 8.9e-4 / 1.3e-3 / 1.6e-3 in 1-4-D against the bound
// 1e-2; a gradient 5% off, or without its -8 t^3 (g . d) d term, fails.
TEST(Noise, SimplexDerivativesMatchFiniteDifferences) {
  Points pts(10);
  for (int kind : {kSimplex, kUSimplex})
    for (int n = 1; n <= 4; ++n) {
      float worst = 0;
      for (int i = 0; i < 2000; ++i) {
        std::array<float, 4> p = pts.next();
        float out[3], grad[12];
        lobe_noise(kind, p.data(), n, nullptr, out, 3, grad);
        for (int k = 0; k < n; ++k) {
          std::array<float, 4> a = p, b = p;
          a[k] += 1e-3f;
          b[k] -= 1e-3f;
          float va[3], vb[3];
          lobe_noise(kind, a.data(), n, nullptr, va, 3, nullptr);
          lobe_noise(kind, b.data(), n, nullptr, vb, 3, nullptr);
          for (int j = 0; j < 3; ++j) {
            float fd = (va[j] - vb[j]) / (a[k] - b[k]), g = grad[j * n + k];
            worst = std::max(worst, std::abs(g - fd));
            EXPECT_NEAR(g, fd, 1e-2f)
                << kind << " n=" << n << " k=" << k << " j=" << j << " at " << p[0];
          }
        }
      }
      std::printf("simplex kind %d %d-D worst |grad - fd| %.2e\n", kind, n, worst);
    }
}

// The vector form's channels are independent noises (seeds 0, 1, 2; channel 0 is the float
// noise), and usimplex = 0.5 * (simplex + 1) with the gradient halved, exactly in float.
TEST(Noise, SimplexChannelsAndUnsigned) {
  Points pts;
  for (int n = 1; n <= 4; ++n) {
    int differ01 = 0, differ12 = 0, differ02 = 0;
    for (int i = 0; i < 1000; ++i) {
      std::array<float, 4> p = pts.next();
      float v[3], s, us, g[4], ug[4];
      lobe_noise(kSimplex, p.data(), n, nullptr, v, 3, nullptr);
      lobe_noise(kSimplex, p.data(), n, nullptr, &s, 1, g);
      lobe_noise(kUSimplex, p.data(), n, nullptr, &us, 1, ug);
      EXPECT_EQ(v[0], s);
      EXPECT_EQ(us, 0.5f * (s + 1.0f));
      for (int k = 0; k < n; ++k) EXPECT_EQ(ug[k], 0.5f * g[k]);
      differ01 += std::abs(v[0] - v[1]) > 1e-3f;
      differ12 += std::abs(v[1] - v[2]) > 1e-3f;
      differ02 += std::abs(v[0] - v[2]) > 1e-3f;
    }
    EXPECT_GT(differ01, 950) << n;
    EXPECT_GT(differ12, 950) << n;
    EXPECT_GT(differ02, 950) << n;
  }
}

// The W-point simplex functions (what the JIT's noise batching calls, runtime/jit/noise_batch.h)
// against lobe_noise_d's value path, lane by lane to the bit: random points, lattice points,
// coordinates tied with each other (the simplex choice), negative zero, values far out where
// x + skew leaves the int range (the lattice coordinate is then INT_MIN, as x86 converts); every
// lane with a seed of its own (channel `seed` of a vector noise). lobe_noise_d's values are held
// against OSL by the tests above. (The JIT passes a W-point function only coordinates below
// 2^31 in magnitude and no NaN: lobe_noise_d's guard comes first.)
TEST(Noise, SimplexLanesMatchOnePointToTheBit) {
  using Wide = void (*)(const float*, const uint32_t*, float*);
  const Wide wide[4][2] = {{lobe_simplex_v1_x4, lobe_simplex_v1_x8},
                           {lobe_simplex_v2_x4, lobe_simplex_v2_x8},
                           {lobe_simplex_v3_x4, lobe_simplex_v3_x8},
                           {lobe_simplex_v4_x4, lobe_simplex_v4_x8}};
  const float special[] = {0.0f,   -0.0f,   1.0f, -1.0f, 0.5f,   -2.5f,  7.0f,
                           1e-30f, 16.999f, 1e9f, -1e9f, 2.1e9f, -2.1e9f};
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  std::uniform_int_distribution<int> pick(0, int(std::size(special)) - 1), coin(0, 3);
  auto same = [](float a, float b) { return std::memcmp(&a, &b, 4) == 0; };
  int compared = 0, mismatched = 0;
  for (int n = 1; n <= 4; ++n)
    for (int wi = 0; wi < 2; ++wi) {
      const int w = wi ? 8 : 4;
      for (int trial = 0; trial < 2000; ++trial) {
        float x[4 * 8], out[8];
        uint32_t seed[8];
        for (int l = 0; l < w; ++l) {
          seed[l] = uint32_t(coin(rng) % 3);
          for (int a = 0; a < n; ++a) {
            int c = coin(rng);
            x[a * w + l] = c == 0            ? special[pick(rng)]
                           : c == 1 && a > 0 ? x[(a - 1) * w + l] // a tie
                           : c == 2          ? std::round(u(rng)) // a lattice coordinate
                                             : u(rng);
          }
        }
        wide[n - 1][wi](x, seed, out);
        for (int l = 0; l < w; ++l) {
          float p[4], channels[3];
          for (int a = 0; a < n; ++a) p[a] = x[a * w + l];
          lobe_noise_d(kSimplex, p, nullptr, nullptr, n, nullptr, channels, nullptr, nullptr, 3);
          float expect = channels[seed[l]];
          ++compared;
          if (!same(out[l], expect) && ++mismatched <= 5)
            ADD_FAILURE() << "n " << n << " W " << w << " lane " << l << ": " << out[l] << " vs "
                          << expect;
        }
      }
    }
  EXPECT_EQ(mismatched, 0) << "of " << compared;
}

// The same for gradient noise of 2 to 4 coordinates, one channel or three (lobe_perlin_v2,
// v2c, v3, v3c, v4, v4c: lobe_noise_d's value path for them, whose values the tests above hold
// against OSL): lattice points and their neighbours, negative zero, values near the int range.
TEST(Noise, PerlinLanesMatchOnePointToTheBit) {
  const float special[] = {0.0f,   -0.0f,   1.0f,       -1.0f,       0.5f,
                           -2.5f,  7.0f,    1e-30f,     16.999f,     std::nextafter(3.0f, 0.0f),
                           2.1e9f, -2.1e9f, 8388607.5f, -16777216.0f};
  using Wide = void (*)(const float*, const uint32_t*, float*);
  struct Form {
    int n, channels;
    Wide x4, x8;
  };
  const Form forms[] = {
      {2, 1, lobe_perlin_v2_x4, lobe_perlin_v2_x8}, {2, 3, lobe_perlin_v2c_x4, lobe_perlin_v2c_x8},
      {3, 1, lobe_perlin_v3_x4, lobe_perlin_v3_x8}, {3, 3, lobe_perlin_v3c_x4, lobe_perlin_v3c_x8},
      {4, 1, lobe_perlin_v4_x4, lobe_perlin_v4_x8}, {4, 3, lobe_perlin_v4c_x4, lobe_perlin_v4c_x8}};
  std::mt19937 rng(22);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  std::uniform_int_distribution<int> pick(0, int(std::size(special)) - 1), coin(0, 2);
  auto same = [](float a, float b) { return std::memcmp(&a, &b, 4) == 0; };
  int compared = 0, mismatched = 0;
  for (const Form& f : forms)
    for (int w : {4, 8})
      for (int trial = 0; trial < 2000; ++trial) {
        float x[4 * 8], out[3 * 8];
        for (int l = 0; l < w; ++l)
          for (int a = 0; a < f.n; ++a) {
            int c = coin(rng);
            x[a * w + l] = c == 0 ? special[pick(rng)] : c == 1 ? std::round(u(rng)) : u(rng);
          }
        (w == 4 ? f.x4 : f.x8)(x, nullptr, out);
        for (int l = 0; l < w; ++l) {
          float p[4] = {x[l], x[w + l], f.n > 2 ? x[2 * w + l] : 0.0f,
                        f.n == 4 ? x[3 * w + l] : 0.0f};
          float one[3], noise[3];
          if (f.channels == 1) {
            one[0] = f.n == 2   ? lobe_perlin_v2(p[0], p[1])
                     : f.n == 3 ? lobe_perlin_v3(p[0], p[1], p[2])
                                : lobe_perlin_v4(p[0], p[1], p[2], p[3]);
          } else {
            lobe_float4 v = f.n == 2   ? lobe_perlin_v2c(p[0], p[1])
                            : f.n == 3 ? lobe_perlin_v3c(p[0], p[1], p[2])
                                       : lobe_perlin_v4c(p[0], p[1], p[2], p[3]);
            for (int j = 0; j < 3; ++j) one[j] = v[j];
            EXPECT_EQ(v[3], 0.0f);
          }
          lobe_noise_d(kPerlin, p, nullptr, nullptr, f.n, nullptr, noise, nullptr, nullptr,
                       f.channels);
          for (int j = 0; j < f.channels; ++j) {
            ++compared;
            if ((!same(out[j * w + l], one[j]) || !same(noise[j], one[j])) && ++mismatched <= 5)
              ADD_FAILURE() << f.n << "-D, " << f.channels << " channels, W " << w << " lane " << l
                            << " channel " << j << " at (" << p[0] << ", " << p[1] << ", " << p[2]
                            << ", " << p[3] << "): " << out[j * w + l] << ", one point " << one[j]
                            << ", noise " << noise[j];
          }
        }
      }
  EXPECT_EQ(mismatched, 0) << "of " << compared;
}

// noise(name, ...) with a run-time name dispatches to the same kind as the constant case; an
// unknown name gives 0 (and a zero gradient) and reports a run-time error with the location.
// Simplex noise has no periodic form (as in OSL), so pnoise("simplex") is an unknown name.
// Beyond 2^24 the lattice is not wrapped (values from testshade 1.13.12). Beyond the int range,
// and for inf and NaN, OSL's gradient noise is inf or garbage; Lobe's reads such a coordinate
// as 0 (a deliberate difference: noise stays finite and in range). Cell noise keys on the
// lattice coordinate as OSL's float-to-int conversion gives it on x86: INT_MIN beyond the int
// range (testshade's value, the same for every such input).
TEST(Noise, HugeInputs) {
  float v, zero;
  float p1[3] = {0.3f, 1.7f, -3e7f}, p2[3] = {0.3f, 1.7f, 2e7f};
  lobe_noise(kPerlin, p1, 3, nullptr, &v, 1, nullptr);
  EXPECT_EQ(v, 0.0986982733f);
  lobe_noise(kPerlin, p2, 3, nullptr, &v, 1, nullptr);
  EXPECT_EQ(v, -0.0182813499f);
  float z = 0;
  lobe_noise(kPerlin, &z, 1, nullptr, &zero, 1, nullptr);
  for (float x : {3e9f, -1e20f, INFINITY, -INFINITY, NAN}) {
    lobe_noise(kPerlin, &x, 1, nullptr, &v, 1, nullptr);
    EXPECT_EQ(v, zero) << x;
    lobe_noise(kSimplex, &x, 1, nullptr, &v, 1, nullptr);
    EXPECT_TRUE(std::isfinite(v) && std::fabs(v) <= 1) << x;
  }
  for (float c : {3e9f, 3.0000003e9f, -1e20f, -2147483648.0f}) {
    lobe_noise(kCell, &c, 1, nullptr, &v, 1, nullptr);
    EXPECT_EQ(v, 0.902607918f) << c; // all INT_MIN
  }
}

// The Dual2 path (derivatives requested) against the value-only one: the same value except in
// 4-D, where OSL interpolates in another order; the derivatives follow the input's.
TEST(Noise, DualPathAsOSL) {
  const float p[4] = {0.3f, 1.7f, -0.4f, 2.6f}, dx[4] = {1, 0, 0, 0}, dy[4] = {0, 0, 0, 0};
  for (int n = 1; n <= 4; ++n) {
    float v, vd, ox, oy, g[4];
    lobe_noise(kPerlin, p, n, nullptr, &v, 1, g);
    lobe_noise_d(kPerlin, p, dx, dy, n, nullptr, &vd, &ox, &oy, 1);
    if (n < 4) {
      EXPECT_EQ(v, vd) << n;
    }
    EXPECT_NEAR(v, vd, 1e-6f) << n;
    EXPECT_EQ(ox, g[0]) << n;
    EXPECT_EQ(oy, 0.0f) << n;
  }
}

// Gabor noise: OSL 1.13.12's values (testshade) at a point without derivatives (no filter).
TEST(Noise, GaborAsOSL) {
  const float p[3] = {0.3f, 1.7f, -0.4f};
  float v, c[3];
  lobe_gabor(p, nullptr, nullptr, 3, nullptr, nullptr, &v, nullptr, nullptr, 1);
  EXPECT_EQ(v, -0.0326871015f);
  GaborOptions o;
  o.anisotropic = 1;
  o.do_filter = 0;
  o.direction[1] = 0.5f, o.direction[2] = 0.25f;
  o.bandwidth = 2.5f, o.impulses = 8;
  lobe_gabor(p, nullptr, nullptr, 3, nullptr, &o, &v, nullptr, nullptr, 1);
  EXPECT_EQ(v, 0.10948883f);
  GaborOptions h;
  h.anisotropic = 2, h.do_filter = 0, h.impulses = 4;
  h.direction[0] = 0.3f, h.direction[1] = 1, h.direction[2] = 0;
  const float per[3] = {3, 4, 5};
  lobe_gabor(p, nullptr, nullptr, 3, per, &h, c, nullptr, nullptr, 3);
  EXPECT_EQ(c[0], -0.0477480181f);
  EXPECT_EQ(c[1], 0.0842730924f);
  EXPECT_EQ(c[2], -0.214254081f);
}

TEST(Noise, NamedDispatchAndUnknownName) {
  const std::pair<const char*, int> names[] = {
      {"perlin", kPerlin}, {"snoise", kPerlin},     {"simplex", kSimplex}, {"uperlin", kUPerlin},
      {"noise", kUPerlin}, {"usimplex", kUSimplex}, {"cell", kCell},       {"cellnoise", kCell},
      {"hash", kHash},     {"hashnoise", kHash}};
  float p[3] = {0.3f, 1.7f, -0.4f}, per[3] = {2, 3, 4};
  for (auto& [name, kind] : names)
    for (const float* period :
         {static_cast<const float*>(nullptr), static_cast<const float*>(per)}) {
      if (period && (kind == kSimplex || kind == kUSimplex)) continue; // an error: below
      float a[3], b[3], ga[9], gb[9];
      lobe_noise(kind, p, 3, period, a, 3, ga);
      lobe_noise_named(nullptr, name, p, 3, period, b, 3, gb, "t.osl", 1);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(a[k], b[k]) << name;
      for (int k = 0; k < 9; ++k) EXPECT_EQ(ga[k], gb[k]) << name;
    }
  ShadingContext ctx;
  ShaderGlobals sg{};
  sg.context = &ctx;
  float out[3] = {7, 7, 7}, grad[9];
  std::fill(grad, grad + 9, 7.0f);
  lobe_noise_named(&sg, "perln", p, 3, nullptr, out, 3, grad, "t.osl", 12);
  for (float v : out) EXPECT_EQ(v, 0.0f);
  for (float g : grad) EXPECT_EQ(g, 0.0f);
  EXPECT_EQ(ctx.errors, 1);
  EXPECT_EQ(ctx.output, "ERROR: noise type \"perln\" is unknown, called from (t.osl:12)\n");
  for (const char* name : {"simplex", "usimplex"}) {
    EXPECT_EQ(noise_kind_from_name(name, true), -1) << name;
    std::fill(out, out + 3, 7.0f);
    std::fill(grad, grad + 9, 7.0f);
    lobe_noise_named(&sg, name, p, 3, per, out, 3, grad, "t.osl", 13);
    for (float v : out) EXPECT_EQ(v, 0.0f) << name;
    for (float g : grad) EXPECT_EQ(g, 0.0f) << name;
  }
  EXPECT_EQ(ctx.errors, 3);
  // OSL 1.13.12 (oslc nz4.osl; testshade nz4, with pnoise("bogus2", P, point(4))) prints
  // `ERROR: periodic noise type "bogus2" is unknown, called from (nz4.osl:4)`.
  EXPECT_EQ(ctx.output,
            "ERROR: noise type \"perln\" is unknown, called from (t.osl:12)\n"
            "ERROR: periodic noise type \"simplex\" is unknown, called from (t.osl:13)\n"
            "ERROR: periodic noise type \"usimplex\" is unknown, called from (t.osl:13)\n");
  // A name known only while shading (no place given): OSL's other wording (OSL 1.13.12:
  // `noise(k, P)` with k = u > 0.5 ? "bogus" : "perlin" prints `ERROR: Unknown noise type
  // "bogus"`).
  ctx.output.clear();
  lobe_noise_named(&sg, "bogus", p, 3, nullptr, out, 3, grad, nullptr, 0);
  EXPECT_EQ(ctx.output, "ERROR: Unknown noise type \"bogus\"\n");
  EXPECT_EQ(noise_kind_from_name("perlin", true), kPerlin); // the other kinds have periods
  EXPECT_EQ(noise_kind_from_name("cell", true), kCell);
}

TEST(Errors, RangeErrorReportsLocation) {
  ShadingContext ctx;
  ShaderGlobals sg{};
  sg.context = &ctx;
  lobe_range_error(&sg, 5, 3, "a", "t.osl", 7, "(group g, layer 0 t_0, shader t)");
  EXPECT_EQ(ctx.errors, 1);
  // OSL 1.13.12 words it so (testshade on `float a[3]; int i = 5; a[i] = 1;` at line 7).
  EXPECT_EQ(ctx.output,
            "ERROR: Index [5] out of range a[0..2]: t.osl:7 (group g, layer 0 t_0, shader t)\n");
}

TEST(Table, NamesResolve) {
  ASSERT_NE(find_shadeop("lobe_noise"), nullptr);
  EXPECT_STREQ(find_shadeop("sinf")->sig, "ff");
  EXPECT_EQ(find_shadeop("nope"), nullptr);
}

// spline() with a NaN position reads it as 0 (the first segment's start, knots[1] for the
// linear basis) and gives no derivatives; the segment index is never computed from the NaN
// (it would index far outside the knots).
TEST(Spline, NanPositionReadsAsZero) {
  const float knots[4] = {0.0f, 0.25f, 0.75f, 1.0f};
  float out = -1, dx = -1, dy = -1;
  lobe_spline("linear", std::numeric_limits<float>::quiet_NaN(), 1.0f, 1.0f, 1, knots, nullptr,
              nullptr, 4, 1, &out, &dx, &dy);
  EXPECT_EQ(out, 0.25f);
  EXPECT_EQ(dx, 0.0f);
  EXPECT_EQ(dy, 0.0f);
  lobe_spline("catmull-rom", -std::numeric_limits<float>::infinity(), 0, 0, 0, knots, nullptr,
              nullptr, 4, 1, &out, nullptr, nullptr);
  EXPECT_EQ(out, 0.25f);
}

// Knot derivatives carry through the cubic. Linear basis over knots (0, a, b, 1) at x in the
// segment: s = a + (b - a) x, so ds = da (1 - x) + db x + (b - a) dx, computed here in closed
// form; a clamped x (1.5 reads as 1) keeps only the knots' part, db.
TEST(Spline, KnotDerivativesCarryThroughTheCubic) {
  const float knots[4] = {0.0f, 0.25f, 0.75f, 1.0f};
  const float kdx[4] = {0.0f, 2.0f, -1.0f, 0.0f};
  const float kdy[4] = {0.0f, 0.5f, 0.5f, 0.0f};
  float out = -1, dx = -1, dy = -1;
  lobe_spline("linear", 0.25f, 4.0f, 0.0f, 1, knots, kdx, kdy, 4, 1, &out, &dx, &dy);
  EXPECT_FLOAT_EQ(out, 0.25f + 0.5f * 0.25f);
  EXPECT_FLOAT_EQ(dx, 2.0f * 0.75f + -1.0f * 0.25f + 0.5f * 4.0f);
  EXPECT_FLOAT_EQ(dy, 0.5f);
  lobe_spline("linear", 1.5f, 4.0f, 0.0f, 1, knots, kdx, kdy, 4, 1, &out, &dx, &dy);
  EXPECT_FLOAT_EQ(out, 0.75f);
  EXPECT_FLOAT_EQ(dx, -1.0f);
  EXPECT_FLOAT_EQ(dy, 0.5f);
  // "constant" has no derivatives, whatever the knots carry.
  lobe_spline("constant", 0.25f, 4.0f, 1.0f, 1, knots, kdx, kdy, 4, 1, &out, &dx, &dy);
  EXPECT_EQ(out, 0.25f);
  EXPECT_EQ(dx, 0.0f);
  EXPECT_EQ(dy, 0.0f);
}

// splineinverse's derivative is y's through the curve: x = (y - a) / (b - a) on the linear
// basis, dx/dy' = 1 / (b - a) (the knots' derivatives are not taken: OSL's search reads their
// values only).
TEST(Spline, InverseDerivativeIsThroughTheCurve) {
  const float knots[4] = {0.0f, 0.25f, 0.75f, 1.0f};
  float out[3] = {-1, -1, -1};
  lobe_splineinverse_d("linear", 0.5f, 1.0f, -2.0f, knots, 4, out);
  EXPECT_NEAR(out[0], 0.5f, 1e-6f);
  EXPECT_NEAR(out[1], 2.0f, 1e-5f);
  EXPECT_NEAR(out[2], -4.0f, 1e-5f);
  // Beyond the curve's ends: 0 or 1, no derivatives.
  lobe_splineinverse_d("linear", 0.1f, 1.0f, 1.0f, knots, 4, out);
  EXPECT_EQ(out[0], 0.0f);
  EXPECT_EQ(out[1], 0.0f);
}

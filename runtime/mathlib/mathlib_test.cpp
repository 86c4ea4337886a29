// runtime/mathlib against OSL 1.13.12's digits. Every expected string below is what OSL printed
// (printf "%.9g", which round-trips a float) for constant arguments, i.e. what OSL's constant
// folder computes, recorded with
//   oslc math_osl.osl && testshade math_osl
// (OSL 1.13.12 from /work/shared/osl-reference; math_osl.osl is tests/shade/math_osl.osl, one
// printf per function over these inputs). Lobe computes these values at every -O level.
#include "hashword.h"
#include "mathops.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

namespace {

using lobe::math::Fn;
using lobe::math::MathMode;

uint32_t bits(float x) {
  uint32_t u;
  std::memcpy(&u, &x, 4);
  return u;
}

// The float a "%.9g" string denotes (exactly: 9 digits round-trip).
float parse(const char* s) { return std::strtof(s, nullptr); }

struct Case1 {
  Fn fn;
  float x;
  const char* osl;
};
struct Case2 {
  Fn fn;
  float a, b;
  const char* osl;
};

const Case1 kUnary[] = {
    {Fn::Sin, 0.5f, "0.47942555"},
    {Fn::Sin, 2.0f, "0.909297407"},
    {Fn::Sin, -3.7f, "0.529836237"},
    {Fn::Sin, 10.0f, "-0.54402107"},
    {Fn::Sin, 100.5f, "-0.0309600234"},
    {Fn::Sin, 1e-3f, "0.00100004661"},
    {Fn::Cos, 0.5f, "0.87758255"},
    {Fn::Cos, 2.0f, "-0.416146815"},
    {Fn::Cos, -3.7f, "-0.848099947"},
    {Fn::Cos, 10.0f, "-0.839071512"},
    {Fn::Cos, 1.5707964f, "-0"},
    {Fn::Cos, 100.5f, "0.9995206"},
    {Fn::Tan, 0.5f, "0.546302497"},
    {Fn::Tan, 1.2f, "2.57215166"},
    {Fn::Tan, -3.7f, "-0.62473309"},
    {Fn::Tan, 10.0f, "0.648360789"},
    {Fn::Tan, 0.785398f, "0.999999642"},
    {Fn::Asin, 0.1f, "0.100124359"},
    {Fn::Asin, 0.5f, "0.523616552"},
    {Fn::Asin, -0.7f, "-0.775353551"},
    {Fn::Asin, 0.99f, "1.42929053"},
    {Fn::Asin, 2.0f, "1.57079637"},
    {Fn::Acos, 0.1f, "1.47067201"},
    {Fn::Acos, 0.5f, "1.04717982"},
    {Fn::Acos, -0.7f, "2.34614992"},
    {Fn::Acos, 0.99f, "0.141505808"},
    {Fn::Acos, -2.0f, "3.14159274"},
    {Fn::Atan, 0.1f, "0.0996691361"},
    {Fn::Atan, 0.5f, "0.46364972"},
    {Fn::Atan, -0.7f, "-0.610719442"},
    {Fn::Atan, 3.0f, "1.24903917"},
    {Fn::Atan, -50.0f, "-1.55079901"},
    {Fn::Sinh, 0.1f, "0.100166775"},
    {Fn::Sinh, 0.5f, "0.521095335"},
    {Fn::Sinh, -0.9f, "-1.02651668"},
    {Fn::Sinh, 2.5f, "6.05021381"},
    {Fn::Sinh, -7.0f, "-548.315918"},
    {Fn::Cosh, 0.1f, "1.00500405"},
    {Fn::Cosh, 0.5f, "1.12762845"},
    {Fn::Cosh, -0.9f, "1.43308365"},
    {Fn::Cosh, 2.5f, "6.13229847"},
    {Fn::Cosh, -7.0f, "548.316772"},
    {Fn::Tanh, 0.1f, "0.0996667743"},
    {Fn::Tanh, 0.5f, "0.462116301"},
    {Fn::Tanh, -0.9f, "-0.716298103"},
    {Fn::Tanh, 2.5f, "0.986614287"},
    {Fn::Tanh, -7.0f, "-0.999998331"},
    {Fn::Exp, 0.1f, "1.10516977"},
    {Fn::Exp, 0.5f, "1.64872909"},
    {Fn::Exp, -0.9f, "0.406568468"},
    {Fn::Exp, 2.5f, "12.1825123"},
    {Fn::Exp, -7.0f, "0.000911881623"},
    {Fn::Exp, 20.3f, "654901824"},
    {Fn::Exp2, 0.1f, "1.07177281"},
    {Fn::Exp2, 0.5f, "1.41421187"},
    {Fn::Exp2, -0.9f, "0.535891294"},
    {Fn::Exp2, 2.5f, "5.65684748"},
    {Fn::Exp2, -7.3f, "0.0063457014"},
    {Fn::Exp2, 20.3f, "1290944.5"},
    {Fn::Expm1, 0.01f, "0.0100499904"},
    {Fn::Expm1, 0.02f, "0.0201999806"},
    {Fn::Expm1, -0.02f, "-0.0197999813"},
    {Fn::Expm1, 0.5f, "0.648729086"},
    {Fn::Expm1, -0.9f, "-0.593431532"},
    {Fn::Expm1, 2.5f, "11.1825123"},
    {Fn::Log, 0.1f, "-2.30258512"},
    {Fn::Log, 0.5f, "-0.693147182"},
    {Fn::Log, 2.0f, "0.693147182"},
    {Fn::Log, 3.0f, "1.09861231"},
    {Fn::Log, 7.5f, "2.01490307"},
    {Fn::Log, 1000.0f, "6.90775537"},
    {Fn::Log, 0.0f, "-87.3365479"},
    {Fn::Log2, 0.1f, "-3.32192802"},
    {Fn::Log2, 0.5f, "-1"},
    {Fn::Log2, 3.0f, "1.58496249"},
    {Fn::Log2, 7.5f, "2.90689063"},
    {Fn::Log2, 1000.0f, "9.96578407"},
    {Fn::Log2, 0.0f, "-126"},
    {Fn::Log10, 0.1f, "-1"},
    {Fn::Log10, 0.5f, "-0.30103001"},
    {Fn::Log10, 3.0f, "0.477121264"},
    {Fn::Log10, 7.5f, "0.875061333"},
    {Fn::Log10, 1000.0f, "3"},
    {Fn::Log10, 0.0f, "-37.9297829"},
    {Fn::Logb, 0.1f, "-4"},
    {Fn::Logb, 0.5f, "-1"},
    {Fn::Logb, 3.0f, "1"},
    {Fn::Logb, 1000.0f, "9"},
    {Fn::Logb, 0.0f, "-126"},
    {Fn::Erf, 0.1f, "0.112463236"},
    {Fn::Erf, 0.5f, "0.520499825"},
    {Fn::Erf, -0.9f, "-0.796908498"},
    {Fn::Erf, 1.7f, "0.983790517"},
    {Fn::Erf, 3.1f, "0.999988198"},
    {Fn::Erfc, 0.1f, "0.887536764"},
    {Fn::Erfc, 0.5f, "0.479500175"},
    {Fn::Erfc, -0.9f, "1.7969085"},
    {Fn::Erfc, 1.7f, "0.0162094831"},
    {Fn::Erfc, 3.1f, "1.18017197e-05"},
    {Fn::Cbrt, 0.1f, "0.464158893"},
    {Fn::Cbrt, 2.0f, "1.25992239"},
    {Fn::Cbrt, -27.5f, "-3.01840591"},
    {Fn::Cbrt, 1000.0f, "10.0000067"},
};

const Case2 kBinary[] = {
    {Fn::Pow, 2.0f, 0.5f, "1.41421187"},
    {Fn::Pow, 3.0f, 1.7f, "6.47303438"},
    {Fn::Pow, -2.0f, 3.0f, "-8"},
    {Fn::Pow, 0.7f, -2.3f, "2.2712965"},
    {Fn::Pow, 10.0f, 4.5f, "31622.7617"},
    {Fn::Pow, 1.5f, 2.0f, "2.25"},
    {Fn::Atan2, 1.0f, 2.0f, "0.46364972"},
    {Fn::Atan2, -0.3f, 0.7f, "-0.404897422"},
    {Fn::Atan2, 3.0f, -1.0f, "1.89255357"},
    {Fn::Atan2, -2.0f, -5.0f, "-2.76108003"},
    {Fn::Atan2, 0.0f, -1.0f, "3.14159274"},
    {Fn::Fmod, 7.5f, 2.0f, "1.5"},
    {Fn::Fmod, -7.5f, 2.0f, "-1.5"},
    {Fn::Fmod, 100.3f, 0.7f, "0.200004756"},
    {Fn::Fmod, 5.0f, 0.0f, "0"},
};

TEST(Mathlib, UnaryFunctionsPrintOslDigits) {
  for (const Case1& c : kUnary) {
    float got = lobe::math::value1(c.fn, MathMode::Fast, c.x);
    EXPECT_EQ(bits(got), bits(parse(c.osl)))
        << lobe::math::kFns[size_t(c.fn)].name << "(" << c.x << ") = " << got << ", OSL " << c.osl;
  }
}

TEST(Mathlib, BinaryFunctionsPrintOslDigits) {
  for (const Case2& c : kBinary) {
    float got = lobe::math::value2(c.fn, MathMode::Fast, c.a, c.b);
    EXPECT_EQ(bits(got), bits(parse(c.osl))) << lobe::math::kFns[size_t(c.fn)].name << "(" << c.a
                                             << ", " << c.b << ") = " << got << ", OSL " << c.osl;
  }
}

// cos(float(pi/2)) is a tiny negative number in OSL's fast_cos before its clamp, -0 after:
// OSL prints "-0" (same run as above).
TEST(Mathlib, CosOfHalfPiIsNegativeZero) {
  EXPECT_EQ(bits(lobe::math::value1(Fn::Cos, MathMode::Fast, 1.5707964f)), 0x80000000u);
}

// hash(): same run as above, "%d" of hash(0.25), hash(0.0), hash(1.5, 2.5), hash(point(1, 2, 3)),
// hash(point(1, 2, 3), 0.5), hash(42), hash(-7).
TEST(Mathlib, HashIsOslsLookup3) {
  auto h = [](std::initializer_list<uint32_t> w) {
    return lobe::math::osl_hash(w.begin(), int(w.size()));
  };
  auto f = [](float x) { return lobe::math::word_of(x); };
  EXPECT_EQ(h({f(0.25f)}), -1518044388);
  EXPECT_EQ(h({f(0.0f)}), -1793467291);
  EXPECT_EQ(h({f(1.5f), f(2.5f)}), 166400005);
  EXPECT_EQ(h({f(1), f(2), f(3)}), 1265289404);
  EXPECT_EQ(h({f(1), f(2), f(3), f(0.5f)}), 1455492444);
  EXPECT_EQ(h({42u}), 778167589);
  EXPECT_EQ(h({uint32_t(-7)}), 1471852768);
  // The bits are hashed: -0 is not 0.
  EXPECT_NE(h({f(-0.0f)}), h({f(0.0f)}));
}

// Domain rules shared by both modes (docs: mathops.h): log of 0 and of NaN is log(FLT_MIN),
// logb(0) = -126, pow(x, 0) = 1, 0^y = 0, a negative base needs an integer exponent.
TEST(Mathlib, DomainRulesInBothModes) {
  for (MathMode m : {MathMode::Fast, MathMode::Exact}) {
    EXPECT_EQ(lobe::math::value1(Fn::Log2, m, 0.0f), -126.0f);
    EXPECT_EQ(lobe::math::value1(Fn::Log2, m, std::nanf("")), -126.0f);
    EXPECT_EQ(lobe::math::value1(Fn::Logb, m, 0.0f), -126.0f);
    EXPECT_EQ(lobe::math::value2(Fn::Pow, m, 5.0f, 0.0f), 1.0f);
    EXPECT_EQ(lobe::math::value2(Fn::Pow, m, 0.0f, 3.0f), 0.0f);
    EXPECT_EQ(lobe::math::value2(Fn::Pow, m, -2.0f, 1.5f), 0.0f);
    EXPECT_EQ(lobe::math::value2(Fn::Pow, m, -2.0f, 3.0f), -8.0f);
    EXPECT_EQ(lobe::math::value2(Fn::Fmod, m, 5.0f, 0.0f), 0.0f);
  }
  // Exact mode is libm: exp(1) to the float nearest e.
  EXPECT_EQ(lobe::math::value1(Fn::Exp, MathMode::Exact, 1.0f), 2.71828183f);
}

// The derivative factors are OSL's JIT's (fused) forms; the value is never fused. exp: the
// factor is the value itself, sin: cos.
TEST(Mathlib, SlopesFollowTheValues) {
  EXPECT_EQ(lobe::math::slope1(Fn::Exp, MathMode::Fast, 0.0f), 1.0f);
  EXPECT_EQ(lobe::math::slope1(Fn::Sin, MathMode::Fast, 0.0f), 1.0f);
  EXPECT_EQ(lobe::math::slope1(Fn::Log, MathMode::Fast, 0.0f), 0.0f); // clamped: no slope
  EXPECT_EQ(lobe::math::slope1(Fn::Log, MathMode::Fast, 4.0f), 0.25f);
}

} // namespace

// Derivative analysis on hand-written IR: exactly the symbols whose derivatives are read.
#include "passes/derivs.h"
#include "passes/pass_test_util.h"

using lobe::passes::analyze_derivatives;
using lobe::passes::testing::run_pass;

namespace {

TEST(Derivs, BackwardClosureFromDerivativeReads) {
  // f = u * 2; g = sin(f); h = Dx(g)  ->  g, f, u need derivs; k (not feeding Dx) does not;
  // h (the result of Dx) does not; the int i feeding f through assign cannot carry them.
  const char* in = R"(lobe-ir 1
surface s
symbols
  global float u
  global float v
  global point P
  local float f
  local float g
  local float h
  local float k
  local int i
  const float $c0 = 2
main
  mul f u $c0
  add f f i
  sin g f
  Dx h g
  mul k v $c0
  assign k h
end
)";
  bool changed = false;
  std::string out = run_pass(in, analyze_derivatives, &changed);
  EXPECT_TRUE(changed);
  EXPECT_NE(out.find("global float u derivs\n  global float v\n"), std::string::npos) << out;
  EXPECT_NE(out.find("local float f derivs\n  local float g derivs\n  local float h\n"
                     "  local float k\n  local int i\n"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("const float $c0 = 2\n"), std::string::npos) << out;
}

TEST(Derivs, ThroughComponentsTexturesAndArrays) {
  const char* in = R"(lobe-ir 1
surface s
symbols
  global point P
  global float u
  global float v
  local float s
  local float t
  local color c
  local float[2] a
  local float x
  local normal n
  const int $c0 = 0
  const string $c1 = "tex.exr"
main
  compref s P $c0
  aassign a $c0 u
  aref t a $c0
  texture c $c1 s t
  calculatenormal n P
  filterwidth x v
end
)";
  std::string out = run_pass(in, analyze_derivatives);
  for (const char* want : {"global point P derivs", "global float u derivs", "global float v derivs",
                           "local float s derivs", "local float t derivs", "local float[2] a derivs"})
    EXPECT_NE(out.find(want), std::string::npos) << want << "\n" << out;
  for (const char* no : {"local color c derivs", "local float x derivs", "local normal n derivs"})
    EXPECT_EQ(out.find(no), std::string::npos) << no << "\n" << out;
}

TEST(Derivs, ClearsStaleFlagsAndIsIdempotent) {
  const char* in = R"(lobe-ir 1
surface s
symbols
  global float u derivs
  local float f derivs
main
  assign f u
end
)";
  bool changed = false;
  std::string out = run_pass(in, analyze_derivatives, &changed);
  EXPECT_TRUE(changed);
  EXPECT_EQ(out.find("derivs"), std::string::npos) << out;
  run_pass(out, analyze_derivatives, &changed);
  EXPECT_FALSE(changed);
}

} // namespace

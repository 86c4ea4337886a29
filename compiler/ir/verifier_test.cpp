// The verifier on hand-written IR: valid programs pass; each broken invariant is reported.
#include "ir/parser.h"
#include "ir/verifier.h"

#include <gtest/gtest.h>

using namespace lobe::ir;

namespace {

const char* kSymbols = R"(lobe-ir 1
surface s
symbols
  param float Kd = 0.5
  param color Cs = 1 1 1
  global normal N
  global closure Ci
  local int i
  local float x
  local color c
  local matrix m
  local float[4] a
  local string str
  local closure cl
  temp int $t0
  const int $c0 = 0
  const float $c1 = 2
  const string $c2 = "diffuse"
  const string $c3 = "%g\n"
)";

std::vector<std::string> check(const std::string& body) {
  ParseResult r = parse(std::string(kSymbols) + body);
  if (!r.shader) return {"parse error: " + r.error.to_string()};
  return verify(*r.shader);
}

TEST(Verifier, AcceptsWellTypedProgram) {
  auto errs = check(R"(main
  assign x Kd
  assign c x
  assign x i
  assign i x
  assign cl $c0
  add c Cs x
  mul x x $c1
  div m m x
  lt $t0 x $c1
  eq $t0 c Cs
  compref x c i
  compassign c $c0 x
  mxcompref x m i i
  aref x a i
  aassign a i x
  arraylength i a
  construct c x x x
  closure cl $c2 N
  mul cl cl Cs
  mul cl x cl
  add Ci Ci cl
  neg cl cl
  cbr $t0 -> L1 L2
L1:
  br -> L2
L2:
  useparam Kd Cs
  printf $c3 x
  Dx x x
  sin c c
  exit
end
)");
  EXPECT_TRUE(errs.empty()) << errs[0];
}

struct Bad {
  const char* body;
  const char* expect;
};

TEST(Verifier, ReportsEachBrokenRule) {
  const Bad cases[] = {
      {"main\n  assign $c1 x\nend\n", "op 0 (assign): writes the constant '$c1'"},
      {"main\n  assign c str\nend\n", "cannot assign 'str' (string) to 'c' (color)"},
      {"main\n  add x c x\nend\n", "operand 'c' (color) does not convert to 'x' (float)"},
      {"main\n  add x x\nend\n", "has 2 operands, needs 3"},
      {"main\n  lt x x x\nend\n", "result 'x' (float) must be int"},
      {"main\n  lt $t0 c c\nend\n", "ordered comparison of 'c' (color)"},
      {"main\n  bitand i i x\nend\n", "operand 'x' (float) must be int"},
      {"main\n  compref x x i\nend\n", "needs float = triple[int]"},
      {"main\n  aref x a x\nend\n", "index 'x' (float) must be int"},
      {"main\n  aref c a i\nend\n", "element 'c' (color) does not match 'a' (float[4])"},
      {"main\n  closure cl x N\nend\n", "registry key"},
      {"main\n  mul cl cl cl\nend\n", "closure mul needs one closure and one weight"},
      {"main\n  sub cl cl cl\nend\n", "closures support only add, mul, neg"},
      {"main\n  cbr c -> L0 L0\nL0:\nend\n", "condition 'c' (color) must be int or float"},
      {"main\n  useparam x\nend\n", "'x' (float) is not a parameter"},
      {"main\n  printf x\nend\n", "format 'x' (float) must be a string"},
      {"main\n  assign x x @f.osl:3:4\nL9:\n  br\nend\n", "op 1 (br): has 0 jump targets, needs 1"},
  };
  for (const Bad& b : cases) {
    auto errs = check(b.body);
    ASSERT_FALSE(errs.empty()) << b.body;
    EXPECT_NE(errs[0].find(b.expect), std::string::npos) << errs[0];
  }
}

TEST(Verifier, LocationsAppearInMessages) {
  auto errs = check("main\n  assign $c1 x @f.osl:3:4\nend\n");
  ASSERT_EQ(errs.size(), 1u);
  EXPECT_EQ(errs[0], "op 0 (assign @f.osl:3:4): writes the constant '$c1'");
}

TEST(Verifier, JumpsStayInTheirRegion) {
  // An init op jumping into the main body, and a main op jumping into the init region.
  ParseResult r =
      parse(std::string(kSymbols) + "init\n  br -> Lm\nmain\n  assign x x\nLm:\n  br -> Lm\nend\n");
  ASSERT_TRUE(r.shader) << r.error.to_string();
  r.shader->ops[2].jumps = {0};
  auto errs = verify(*r.shader);
  ASSERT_EQ(errs.size(), 2u);
  EXPECT_NE(errs[0].find("jump target 2 outside its region 0..1"), std::string::npos) << errs[0];
  EXPECT_NE(errs[1].find("jump target 0 outside its region 1..3"), std::string::npos) << errs[1];
}

TEST(Verifier, SymbolInvariants) {
  ParseResult r = parse(std::string(kSymbols) + "main\nend\n");
  ASSERT_TRUE(r.shader);
  Shader sh = *r.shader;
  sh.symbols.push_back(sh.symbols[0]);
  sh.symbols[sh.find_symbol("$c1")].init.clear();
  sh.symbols[sh.find_symbol("x")].init_begin = 0;
  sh.symbols[sh.find_symbol("x")].init_end = 0;
  sh.symbols[sh.find_symbol("Kd")].init_begin = 0;
  sh.symbols[sh.find_symbol("Kd")].init_end = 3;
  auto errs = verify(sh);
  ASSERT_EQ(errs.size(), 4u);
  EXPECT_EQ(errs[0], "symbol 'Kd': init range 0:3 outside the init region 0:0");
  EXPECT_EQ(errs[1], "symbol 'x': init ops on a symbol that is not a parameter");
  EXPECT_EQ(errs[2], "symbol '$c1': constant has 0 values, type float needs 1");
  EXPECT_EQ(errs[3], "symbol 'Kd': duplicate name");
}

} // namespace

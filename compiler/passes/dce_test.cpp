// Dead-code elimination on hand-written IR, text in and text out.
#include "passes/constfold.h"
#include "passes/dce.h"
#include "passes/pass_test_util.h"

using lobe::passes::eliminate_dead_code;
// eliminate_dead_code as the compiler's pass runs it (no element-store rule).
static bool dce(lobe::ir::Shader& sh) { return eliminate_dead_code(sh); }
// fold_constants with the default options (the pass helper takes a one-argument pass).
static bool fold_constants(lobe::ir::Shader& sh) { return lobe::passes::fold_constants(sh); }
using lobe::passes::testing::run_pass;

namespace {

TEST(Dce, RemovesUnreadTempsUnreachableOpsAndUnusedSymbols) {
  const char* in = R"(lobe-ir 1
surface s
symbols
  oparam float f = 0
  global float u
  temp float $t0
  temp float $t1
  local int t
  const int $c0 = 0
  const float $c1 = 2
main
  mul $t0 u $c1
  mul $t1 $t0 $c1
  assign f $t0
  br -> Lend
  assign f u
  nop
Lend:
  assign f f
  printf $c2 $t1
end
)";
  std::string text = in;
  text.replace(text.find("main\n"), 5, "  const string $c2 = \"%g\"\nmain\n");
  bool changed = false;
  std::string out = run_pass(text, dce, &changed);
  EXPECT_TRUE(changed);
  EXPECT_EQ(out, R"(lobe-ir 1
surface s
symbols
  oparam float f = 0
  global float u
  temp float $t0
  temp float $t1
  const float $c1 = 2
  const string $c2 = "%g"
main
  mul $t0 u $c1
  mul $t1 $t0 $c1
  assign f $t0
  printf $c2 $t1
end
)");
}

TEST(Dce, KeepsLoopsAndRemapsJumps) {
  const char* in = R"(lobe-ir 1
surface s
symbols
  oparam float f = 0
  local int i
  local int t
  local float dead
  const int $c0 = 0
  const int $c1 = 4
  const int $c2 = 1
main
  assign i $c0
  assign dead $c2
Lc:
  lt t i $c1
  cbr t -> Lb Ld
Lb:
  add f f i
  add i i $c2
  br -> Lc
Ld:
end
)";
  std::string out = run_pass(in, dce);
  EXPECT_NE(out.find(R"(main
  assign i $c0
L1:
  lt t i $c1
  cbr t -> L3 L6
L3:
  add f f i
  add i i $c2
  br -> L1
L6:
end
)"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("dead"), std::string::npos);
}

TEST(Dce, InitRangesShrinkWithRemovedOps) {
  const char* in = R"(lobe-ir 1
surface s
symbols
  param float a init=0:3
  param float b init=3:4
  global float u
  temp float $t0
init
  assign $t0 u
  nop
  assign a u
  assign b a
main
  nop
  assign u b
end
)";
  std::string out = run_pass(in, dce);
  EXPECT_EQ(out, R"(lobe-ir 1
surface s
symbols
  param float a init=0:1
  param float b init=1:2
  global float u
init
  assign a u
  assign b a
main
  assign u b
end
)");
}

TEST(Dce, FoldThenDceRemovesDeadBranch) {
  const char* in = R"(lobe-ir 1
surface s
symbols
  const int On = 0
  global closure Ci
  global normal N
  local closure c
  const string $c0 = "diffuse"
  const string $c1 = "emission"
main
  cbr On -> Lyes Lno
Lyes:
  closure c $c1
  br -> Ldone
Lno:
  closure c $c0 N
Ldone:
  assign Ci c
end
)";
  std::string folded = run_pass(in, fold_constants);
  std::string out = run_pass(folded, dce);
  EXPECT_NE(out.find("main\n  closure c $c0 N\n  assign Ci c\nend\n"), std::string::npos) << out;
  EXPECT_EQ(out.find("emission"), std::string::npos) << out;
  bool changed = true;
  run_pass(out, dce, &changed);
  EXPECT_FALSE(changed);
}

// A temporary overwritten in the same block before any read loses the earlier write; across
// a block boundary, after a partial write (compassign) or a shorter arraycopy it stays.
TEST(Dce, RemovesStoresOverwrittenInTheSameBlock) {
  const char* in = R"(lobe-ir 1
surface s
symbols
  oparam float f = 0
  oparam color c = 0 0 0
  global float u
  temp float $t0
  temp color $t1
  local float[2] a
  local float[3] b
  const float $c0 = 1
  const int $c1 = 0
  const float $c2 = 2
  const float[3] $c3 = 1 2 3
main
  assign $t0 $c0
  assign $t0 u
  add f $t0 $c0
  assign $t1 $c0
  compassign $t1 $c1 u
  assign c $t1
  assign $t0 $c2
  cbr u -> L9 L9
L9:
  mul f $t0 f
  arraycopy b $c3
  arraycopy b a
  aref f b $c1
  assign $t0 $c2
  mul $t0 $t0 u
  assign $t0 u
  add f f $t0
end
)";
  bool changed = false;
  std::string out = run_pass(in, dce, &changed);
  EXPECT_TRUE(changed);
  std::string main = out.substr(out.find("main\n"));
  EXPECT_EQ(main, R"(main
  assign $t0 u
  add f $t0 $c0
  assign $t1 $c0
  compassign $t1 $c1 u
  assign c $t1
  assign $t0 $c2
  mul f $t0 f
  arraycopy b $c3
  arraycopy b a
  aref f b $c1
  assign $t0 u
  add f f $t0
end
)");
}

// OSL's run-time -O2 (part_stores): an element or component store into a local that no path
// reads afterwards goes, with its index's range check; one read afterwards stays, and without
// part_stores such stores stay (OSL's -O0 and -O1 print the range error of each).
TEST(Dce, PartStoresNoOneReadsAfterwardsGoAtOslsO2) {
  const char* in = R"(lobe-ir 1
surface s
symbols
  oparam float f = 0
  global float u
  local float[3] a
  local float[3] b
  local color c
  const int $c0 = 5
  const float $c1 = 3
main
  aref f a $c0
  aassign a $c0 $c1
  aassign b $c0 u
  aref f b $c0
  aassign b $c0 $c1
  compassign c $c0 u
end
)";
  auto o2 = [](lobe::ir::Shader& sh) { return eliminate_dead_code(sh, true); };
  std::string out = run_pass(in, o2);
  EXPECT_EQ(out.substr(out.find("main\n")),
            "main\n  aref f a $c0\n  aassign b $c0 u\n  aref f b $c0\nend\n");
  std::string kept = run_pass(in, dce);
  EXPECT_NE(kept.find("  aassign a $c0 $c1\n"), std::string::npos) << kept;
  EXPECT_NE(kept.find("  aref f b $c0\n  aassign b $c0 $c1\n"), std::string::npos) << kept;
}

// Liveness over the control-flow graph: a store overwritten on every path before any read is
// dead even across blocks; one read on some path (or around a loop) stays.
TEST(Dce, RemovesStoresDeadOnEveryPathAcrossBlocks) {
  const char* in = R"(lobe-ir 1
surface s
symbols
  oparam float f = 0
  oparam float g = 0
  global float u
  temp float $t0
  temp float $t1
  local int i
  local int t
  const float $c0 = 1
  const float $c1 = 2
  const int $c2 = 0
  const int $c3 = 3
  const int $c4 = 1
main
  assign $t0 $c0
  assign $t1 $c0
  cbr u -> La Lb
La:
  assign $t0 u
  add f f $t1
  br -> Lc
Lb:
  assign $t0 $c1
Lc:
  add f f $t0
  assign i $c2
  assign $t1 $c1
Ld:
  lt t i $c3
  cbr t -> Le Lf
Le:
  add g g $t1
  assign $t1 u
  add i i $c4
  br -> Ld
Lf:
end
)";
  std::string out = run_pass(in, dce);
  std::string main = out.substr(out.find("main\n"));
  // `assign $t0 $c0` is overwritten on both branches: dead. `assign $t1 $c0` is read on the
  // La path: kept. `assign $t1 $c1` before the loop is read in its first iteration: kept.
  EXPECT_EQ(main.find("assign $t0 $c0"), std::string::npos) << main;
  EXPECT_NE(main.find("assign $t1 $c0"), std::string::npos) << main;
  EXPECT_NE(main.find("assign $t1 $c1"), std::string::npos) << main;
  EXPECT_NE(main.find("assign $t1 u"), std::string::npos) << main;
  EXPECT_NE(main.find("assign $t0 u"), std::string::npos) << main;
  EXPECT_NE(main.find("assign $t0 $c1"), std::string::npos) << main;
}

} // namespace

namespace {

// A value only the op updating it reads (`add x x t` in a loop) is dead, and so is an output
// the group marked unread (its `useparam` is no read); an output not so marked is kept.
TEST(Dce, SelfUpdatesAndUnreadOutputs) {
  const char* in = R"(lobe-ir 1
shader s
symbols
  oparam float kept = 0
  oparam float dropped = 0
  global float u
  local float acc
  local int i
  temp int $t1
  temp float $t2
  const int $c0 = 0
  const int $c1 = 4
  const int $c3 = 1
main
  assign i $c0
L1:
  lt $t1 i $c1
  cbr $t1 -> L3 L9
L3:
  sin $t2 u
  add acc acc $t2
  useparam dropped
  add dropped dropped $t2
  add kept kept $t2
  add i i $c3
  br -> L1
L9:
end
)";
  std::string out = run_pass(in, [](lobe::ir::Shader& sh) {
    for (auto& s : sh.symbols)
      if (s.name == "dropped") s.unread = true;
    return eliminate_dead_code(sh);
  });
  EXPECT_EQ(out.find("add acc"), std::string::npos) << out;
  EXPECT_EQ(out.find("add dropped"), std::string::npos) << out;
  EXPECT_NE(out.find("add kept kept $t2"), std::string::npos) << out;
  EXPECT_NE(out.find("sin $t2 u"), std::string::npos) << out;
}

} // namespace

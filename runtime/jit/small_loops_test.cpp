// Small counted loops at -O2 (small_loops.h): which loops Jit::optimize unrolls in full, and
// that the unrolled code computes what the rolled code computes (the -O0 module's results).
#include "jit.h"
#include "small_loops.h"

#include <gtest/gtest.h>
#include <llvm/Analysis/LoopInfo.h>
#include <llvm/AsmParser/Parser.h>
#include <llvm/IR/Dominators.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>
#include <llvm/Support/SourceMgr.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace lobe;

// `steps` rounds of a multiply-rotate mix of a 32-bit accumulator (3 instructions each, nothing
// LLVM can fold), the loop counter mixed in first.
std::string body(const std::string& p, const std::string& acc, const std::string& i, int steps) {
  std::string s = "  %" + p + "x0 = xor i32 " + acc + ", " + i + "\n";
  for (int k = 1; k <= steps; ++k) {
    std::string a = "%" + p + "x" + std::to_string(k - 1);
    std::string m = "%" + p + "m" + std::to_string(k), x = "%" + p + "x" + std::to_string(k);
    s += "  " + m + " = mul i32 " + a + ", " + std::to_string(int32_t(0x9E3779B1u + 2u * k)) + "\n";
    s += "  %" + p + "r" + std::to_string(k) + " = call i32 @llvm.fshl.i32(i32 " + m + ", i32 " +
         m + ", i32 " + std::to_string(5 + k % 23) + ")\n";
    s += "  " + x + " = xor i32 %" + p + "r" + std::to_string(k) + ", " + a + "\n";
  }
  return s;
}

// void @f(i32 %seed, ptr %count, ptr %out): `trips` iterations of body(steps) over an
// accumulator, its last value stored to *out and the count of iterations that left it below
// 2^28 to *count; with `outer` > 0 that loop nested in another of `outer` iterations.
std::string loop_ir(int trips, int steps, int outer = 0) {
  std::string last = "%bx" + std::to_string(steps);
  std::string inner = "inner:\n"
                      "  %i = phi i32 [ 0, %inner.pre ], [ %i.next, %inner ]\n"
                      "  %acc = phi i32 [ %acc.in, %inner.pre ], [ " +
                      last +
                      ", %inner ]\n"
                      "  %n = phi i32 [ %n.in, %inner.pre ], [ %n.next, %inner ]\n" +
                      body("b", "%acc", "%i", steps) + "  %small = icmp ult i32 " + last +
                      ", 268435456\n"
                      "  %inc = zext i1 %small to i32\n"
                      "  %n.next = add i32 %n, %inc\n"
                      "  %i.next = add nuw nsw i32 %i, 1\n"
                      "  %again = icmp ult i32 %i.next, " +
                      std::to_string(trips) + "\n  br i1 %again, label %inner, label %inner.done\n";
  std::string s = "declare i32 @llvm.fshl.i32(i32, i32, i32)\n"
                  "define void @f(i32 %seed, ptr %count, ptr %out) {\n"
                  "entry:\n";
  if (outer == 0) {
    s += "  br label %inner.pre\ninner.pre:\n  %acc.in = add i32 %seed, 0\n"
         "  %n.in = add i32 0, 0\n  br label %inner\n" +
         inner + "inner.done:\n  store i32 %n.next, ptr %count\n  store i32 " + last +
         ", ptr %out\n  ret void\n}\n";
    return s;
  }
  s += "  br label %outer\n"
       "outer:\n"
       "  %j = phi i32 [ 0, %entry ], [ %j.next, %inner.done ]\n"
       "  %acc.o = phi i32 [ %seed, %entry ], [ " +
       last +
       ", %inner.done ]\n"
       "  %n.o = phi i32 [ 0, %entry ], [ %n.next, %inner.done ]\n"
       "  br label %inner.pre\n"
       "inner.pre:\n"
       "  %acc.in = add i32 %acc.o, %j\n"
       "  %n.in = add i32 %n.o, 0\n"
       "  br label %inner\n" +
       inner +
       "inner.done:\n"
       "  %j.next = add nuw nsw i32 %j, 1\n"
       "  %again.o = icmp ult i32 %j.next, " +
       std::to_string(outer) +
       "\n  br i1 %again.o, label %outer, label %exit\n"
       "exit:\n  store i32 %n.next, ptr %count\n  store i32 " +
       last + ", ptr %out\n  ret void\n}\n";
  return s;
}

std::unique_ptr<llvm::Module> parse(const std::string& ir, llvm::LLVMContext& ctx) {
  llvm::SMDiagnostic diag;
  auto m = llvm::parseAssemblyString(ir, diag, ctx);
  if (!m) ADD_FAILURE() << diag.getMessage().str() << " at line " << diag.getLineNo();
  return m;
}

// Loops left in @f (every depth).
int loops_in(llvm::Module& m) {
  llvm::Function* f = m.getFunction("f");
  llvm::DominatorTree dt(*f);
  llvm::LoopInfo li(dt);
  return int(li.getLoopsInPreorder().size());
}

struct Case {
  const char* what;
  int trips, steps, outer;
  int loops_left; // after -O2
};

TEST(SmallLoops, CountedLoopsWithinTheBudgetUnrollInFullWithTheSameResults) {
  if (jit::small_loop_budget() != jit::kSmallLoopMaxUnrolledSize)
    GTEST_SKIP() << "LOBE_UNROLL_BUDGET is set";
  std::string err;
  auto jit = jit::Jit::create(err);
  ASSERT_TRUE(jit) << err;
  // Sizes: body() is 3 instructions a step, and the loop adds 10 of its own (its phis, counter,
  // count and branch); the step counts keep a few instructions' margin from each limit.
  constexpr int kMax = int(jit::kSmallLoopMaxUnrolledSize);
  const int fits3 = (kMax / 3 - 8) / 3 - 2;      // 3 copies just within the budget
  const int over3 = (kMax / 3 - 8) / 3 + 2;      // 3 copies just over it
  const int fits8 = (kMax / 8 - 8) / 3 - 2;      // 8 copies within it
  const int nest_inner = (kMax / 3 - 8) / 3 - 2; // inner copies fit, the outer's do not
  const int nest_both = (kMax / 9 - 16) / 3 - 2; // both levels' copies fit
  static_assert(jit::kSmallLoopMaxTrips == 8, "the trip counts below straddle the limit");
  const Case cases[] = {
      {"3 trips, within the budget", 3, fits3, 0, 0},
      {"3 trips, over the budget", 3, over3, 0, 1},
      {"8 trips, within the budget", 8, fits8, 0, 0},
      {"9 trips: more than the most", 9, 30, 0, 1}, // (too big for LLVM's own threshold)
      {"a 3x3 nest whose inner copies fit", 3, nest_inner, 3, 1},
      {"a 3x3 nest whose copies all fit", 3, nest_both, 3, 0},
  };
  for (const Case& c : cases) {
    std::string ir = loop_ir(c.trips, c.steps, c.outer);
    // The loops as written (-O0 keeps them), and what -O2 leaves.
    std::vector<void*> fns;
    std::vector<jit::CompiledGroup> codes;
    for (int opt : {0, 2}) {
      auto ctx = std::make_unique<llvm::LLVMContext>();
      auto mod = parse(ir, *ctx);
      ASSERT_TRUE(mod) << c.what;
      jit->configure(*mod);
      EXPECT_EQ(loops_in(*mod), c.outer ? 2 : 1) << c.what;
      jit->optimize(*mod, opt);
      if (opt == 2) {
        EXPECT_EQ(loops_in(*mod), c.loops_left) << c.what << " (" << c.steps << " steps)";
      }
      jit::CompiledGroup code;
      jit::JitTimes times;
      std::vector<void*> addr;
      ASSERT_TRUE(jit->add(std::move(ctx), std::move(mod), 0, {"f"}, addr, code, times, err))
          << err;
      fns.push_back(addr[0]);
      codes.push_back(code);
    }
    using Fn = void (*)(uint32_t, uint32_t*, uint32_t*);
    int small_total = 0;
    for (uint32_t seed = 0; seed < 2000; ++seed) {
      uint32_t n0 = 0, a0 = 0, n2 = 0, a2 = 0;
      reinterpret_cast<Fn>(fns[0])(seed * 2654435761u, &n0, &a0);
      reinterpret_cast<Fn>(fns[1])(seed * 2654435761u, &n2, &a2);
      ASSERT_EQ(n0, n2) << c.what << " seed " << seed;
      ASSERT_EQ(a0, a2) << c.what << " seed " << seed;
      small_total += int(n0);
    }
    // The count's comparison goes both ways (about one iteration in 16 has a small
    // accumulator), so the count checks it too.
    int iterations = 2000 * c.trips * (c.outer ? c.outer : 1);
    EXPECT_GT(small_total, iterations / 40) << c.what;
    EXPECT_LT(small_total, iterations / 8) << c.what;
    for (auto& code : codes) jit->remove(code);
  }
}

} // namespace

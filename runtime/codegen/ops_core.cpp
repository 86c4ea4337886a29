// Core ops: assignment and conversion, arithmetic (floats as dual numbers, ints with OSL's
// division rules, matrices, closures), comparisons and integer bit ops.
#include "duals.h"
#include "ir/edit.h"
#include "mathops.h"
#include "op_tables.h"

#include <llvm/IR/Constants.h>
#include <llvm/IR/Intrinsics.h>

#include <limits>

namespace lobe::codegen {
namespace {

using ir::BaseType;

bool is_closure(const ir::Symbol& s) { return s.type.base == BaseType::Closure; }

void op_assign(LayerEmitter& e, const ir::Op& op) {
  e.store(op.args[0], e.load_as(op, 1, e.arg(op, 0).type.base, e.wants_derivs(op.args[0])));
}

// Integer a / b and a % b without UB: 0 where b == 0, and b == -1 handled without overflow.
llvm::Value* int_divmod(LayerEmitter& e, llvm::Value* a, llvm::Value* b, bool mod) {
  auto& B = e.b();
  llvm::Value* zero = B.CreateICmpEQ(b, e.iconst(0));
  llvm::Value* m1 = B.CreateICmpEQ(b, e.iconst(-1));
  llvm::Value* safe = B.CreateSelect(B.CreateOr(zero, m1), e.iconst(1), b);
  llvm::Value* r = mod ? B.CreateSRem(a, safe) : B.CreateSDiv(a, safe);
  llvm::Value* at_m1 = mod ? e.iconst(0) : B.CreateSub(e.iconst(0), a);
  return B.CreateSelect(zero, e.iconst(0), B.CreateSelect(m1, at_m1, r));
}

// Float division as OSL's JIT computes it (llvm_gen_div). By a divisor that is a constant and
// not all zero: a plain a / b (so a zero component of such a divisor gives inf or NaN);
// otherwise OSL's safe division, a / b where that is finite and 0 where not (x / 0, an overflow,
// a NaN). With derivatives, (a' - q b') * binv with binv = 1 / b by the same rule: the reciprocal
// is rounded, then multiplied (OSL 1.13.12, testshade -g 4 4, a = P[0]*3.3+0.7, b = P[1]*1.7+0.3:
// Dx(a / b) = 3.66666675 at the first point, where (a' - q b') / b gives 3.66666651).
Dual osl_div(LayerEmitter& e, const Dual& a, const Dual& b, bool plain) {
  auto& B = e.b();
  auto quotient = [&](llvm::Value* x, llvm::Value* y) -> llvm::Value* {
    llvm::Value* q = B.CreateFDiv(x, y);
    if (plain) return q;
    llvm::Value* finite = B.CreateFCmpOLT(B.CreateUnaryIntrinsic(llvm::Intrinsic::fabs, q),
                                          e.fconst(std::numeric_limits<float>::infinity()));
    return B.CreateSelect(finite, q, e.fconst(0));
  };
  Dual r{quotient(a.v, b.v)};
  if (!a.dx && !a.dy && !b.dx && !b.dy) return r;
  llvm::Value* binv = quotient(e.fconst(1), b.v);
  auto slope = [&](llvm::Value* ad, llvm::Value* bd) {
    return B.CreateFMul(
        B.CreateFSub(ad ? ad : e.fconst(0), B.CreateFMul(r.v, bd ? bd : e.fconst(0))), binv);
  };
  r.dx = slope(a.dx, b.dx);
  r.dy = slope(a.dy, b.dy);
  return r;
}

// OSL's dual arithmetic gives an operand without derivatives zero ones and computes with them
// (0 - b', a * b' + 0 * b): that differs from leaving the term out in the sign of a zero
// derivative and where a value is infinite or NaN. So when the result has derivatives and an
// operand has some, the missing ones are explicit zeros.
void zero_missing_derivs(LayerEmitter& e, Val& a, Val& b) {
  bool any = false;
  for (const Val* v : {&a, &b})
    for (const Dual& x : *v) any |= x.dx || x.dy;
  if (!any) return;
  for (Val* v : {&a, &b})
    for (Dual& x : *v) {
      if (!x.dx) x.dx = e.fconst(0);
      if (!x.dy) x.dy = e.fconst(0);
    }
}

// Whether closure operand `ci` of `op` is a temporary that a `closure` op makes earlier in the
// same straight run of ops and that nothing else reads: each component it holds is then
// weighted by `op` alone, so the weight can go into the component (lobe_closure_weight) rather
// than into a ClosureMul node over it.
bool fresh_component(LayerEmitter& e, const ir::Op& op, int ci) {
  const auto& ops = e.shader().ops;
  if (ops.empty() || &op < ops.data() || &op >= ops.data() + ops.size()) return false;
  const int at = int(&op - ops.data()), s = op.args[size_t(ci)];
  if (e.sym(s).kind != ir::SymKind::Temp) return false;
  int producer = -1, reads = 0;
  for (int i = 0; i < int(ops.size()); ++i) {
    const ir::Op& o = ops[size_t(i)];
    for (size_t a = 0; a < o.args.size(); ++a) {
      if (o.args[a] != s) continue;
      reads += ir::op_reads(o, int(a));
      if (o.writes(int(a))) {
        if (producer >= 0 || o.opcode != ir::Opcode::Closure) return false;
        producer = i;
      }
    }
  }
  if (reads != 1 || producer < 0 || producer >= at) return false;
  // Both in the main body, or both in one parameter's default (regions run separately).
  const int body = e.shader().main_begin;
  if ((producer >= body) != (at >= body)) return false;
  if (at < body) {
    bool same = false;
    for (const ir::Symbol& p : e.shader().symbols)
      same |= p.init_begin <= producer && at < p.init_end;
    if (!same) return false;
  }
  for (int i = producer; i < at; ++i) // no jump out of the run, none into it
    if (ir::is_jump(ops[size_t(i)].opcode) || ops[size_t(i)].opcode == ir::Opcode::Exit)
      return false;
  for (const ir::Op& o : ops)
    for (int t : o.jumps)
      if (t > producer && t <= at) return false;
  return true;
}

// Closure arithmetic: sums and weights built at run time by shadeops.
void closure_arith(LayerEmitter& e, const ir::Op& op) {
  auto& B = e.b();
  auto weight_ptr = [&](int argi) {
    Val w = e.load_as(op, argi, BaseType::Color, false);
    return e.spill({w[0].v, w[1].v, w[2].v});
  };
  llvm::Value* r = nullptr;
  if (op.opcode == ir::Opcode::Add) {
    r = e.call("lobe_closure_add", {e.sg(), e.load(op.args[1])[0].v, e.load(op.args[2])[0].v});
  } else if (op.opcode == ir::Opcode::Mul || op.opcode == ir::Opcode::Div) {
    int ci = is_closure(e.arg(op, 1)) ? 1 : 2, wi = 3 - ci;
    llvm::Value* w = weight_ptr(wi);
    if (op.opcode == ir::Opcode::Div) { // closure / w: scale by 1/w (0 where w == 0)
      Val wv = e.load_as(op, wi, BaseType::Color, false);
      DualOps d(e);
      std::vector<llvm::Value*> inv;
      for (const Dual& c : wv) inv.push_back(d.div(d.constant(1), c).v);
      w = e.spill(inv);
    }
    r = e.call(fresh_component(e, op, ci) ? "lobe_closure_weight" : "lobe_closure_mul",
               {e.sg(), e.load(op.args[size_t(ci)])[0].v, w});
  } else if (op.opcode == ir::Opcode::Neg) {
    llvm::Value* w = e.spill({e.fconst(-1), e.fconst(-1), e.fconst(-1)});
    r = e.call(fresh_component(e, op, 1) ? "lobe_closure_weight" : "lobe_closure_mul",
               {e.sg(), e.load(op.args[1])[0].v, w});
  } else {
    e.fail(op, "not defined on closures");
    return;
  }
  (void)B;
  e.store(op.args[0], Val{Dual{r}});
}

// A div op's divisor when it is a constant: all zero (an empty value is zero) or not.
enum class ConstDivisor { None, Zero, Nonzero };
ConstDivisor const_divisor(LayerEmitter& e, const ir::Op& op) {
  if (op.opcode != ir::Opcode::Div || op.args.size() < 3) return ConstDivisor::None;
  const ir::Symbol& d = e.arg(op, 2);
  if (d.kind != ir::SymKind::Const) return ConstDivisor::None;
  return d.init.empty() || ir::const_all(d, 0) ? ConstDivisor::Zero : ConstDivisor::Nonzero;
}

// Matrix arithmetic: products and inverses through shadeops, the rest per element.
void matrix_arith(LayerEmitter& e, const ir::Op& op) {
  bool am = e.arg(op, 1).type.base == BaseType::Matrix;
  bool bm = op.args.size() > 2 && e.arg(op, 2).type.base == BaseType::Matrix;
  if ((op.opcode == ir::Opcode::Mul || op.opcode == ir::Opcode::Div) && am && bm) {
    auto to_ptr = [&](int i) {
      Val v = e.load_as(op, i, BaseType::Matrix, false);
      std::vector<llvm::Value*> c;
      for (auto& d : v) c.push_back(d.v);
      return e.spill(c);
    };
    llvm::Value* out = e.spill(std::vector<llvm::Value*>(16, e.fconst(0)));
    e.call(op.opcode == ir::Opcode::Mul ? "lobe_mat_mul" : "lobe_mat_div",
           {out, to_ptr(1), to_ptr(2)});
    Val r;
    for (llvm::Value* v : e.reload(out, 16)) r.push_back(Dual{v});
    e.store(op.args[0], r);
    return;
  }
  if (op.opcode == ir::Opcode::Div && !am && bm) { // float / matrix = float * inverse(matrix)
    llvm::Value* a = e.load_as(op, 1, BaseType::Float, false)[0].v;
    Val b = e.load_as(op, 2, BaseType::Matrix, false);
    std::vector<llvm::Value*> bc;
    for (const Dual& d : b) bc.push_back(d.v);
    llvm::Value* out = e.spill(std::vector<llvm::Value*>(16, e.fconst(0)));
    e.call("lobe_mat_inverse", {out, e.spill(bc)});
    Val r;
    for (llvm::Value* v : e.reload(out, 16)) r.push_back(Dual{e.b().CreateFMul(a, v)});
    e.store(op.args[0], r);
    return;
  }
  // Per element: matrix +-* float or matrix, matrix / float, -matrix. A float operand of
  // add/sub acts as a diagonal matrix (conversion rule), of mul/div as a scalar.
  DualOps d(e);
  bool scalar_b =
      op.args.size() > 2 && !bm && (op.opcode == ir::Opcode::Mul || op.opcode == ir::Opcode::Div);
  bool scalar_a = !am && op.opcode == ir::Opcode::Mul;
  Val a = scalar_a ? e.load_as(op, 1, BaseType::Float, false)
                   : e.load_as(op, 1, BaseType::Matrix, false);
  Val b;
  if (op.args.size() > 2)
    b = scalar_b ? e.load_as(op, 2, BaseType::Float, false)
                 : e.load_as(op, 2, BaseType::Matrix, false);
  // matrix / float divides plainly (a zero divisor gives inf, nan for 0 / 0), as OSL's Imath
  // operator does at run time; only OSL's -O2 folds a constant zero divisor to a zero matrix.
  bool folded_zero = e.group().opt_level >= 2 && const_divisor(e, op) == ConstDivisor::Zero;
  Val r(16);
  for (size_t i = 0; i < 16; ++i) {
    Dual x = scalar_a ? a[0] : a[i];
    if (op.opcode == ir::Opcode::Neg) {
      r[i] = d.neg(x);
      continue;
    }
    Dual y = scalar_b ? b[0] : b[i];
    if (op.opcode == ir::Opcode::Add)
      r[i] = d.add(x, y);
    else if (op.opcode == ir::Opcode::Sub)
      r[i] = d.sub(x, y);
    else if (op.opcode == ir::Opcode::Mul)
      r[i] = d.mul(x, y);
    else
      r[i] = folded_zero ? Dual{e.fconst(0)} : Dual{e.b().CreateFDiv(x.v, y.v)};
  }
  e.store(op.args[0], r);
}

void arith(LayerEmitter& e, const ir::Op& op) {
  const ir::Symbol& dst = e.arg(op, 0);
  BaseType t = dst.type.base;
  if (t == BaseType::Closure) return closure_arith(e, op);
  if (t == BaseType::Matrix) return matrix_arith(e, op);
  auto& B = e.b();
  bool unary = op.opcode == ir::Opcode::Neg;
  if (t == BaseType::Int) {
    llvm::Value* a = e.load_as(op, 1, t)[0].v;
    llvm::Value* r = nullptr;
    if (unary)
      r = B.CreateSub(e.iconst(0), a);
    else {
      llvm::Value* b = e.load_as(op, 2, t)[0].v;
      if (op.opcode == ir::Opcode::Add)
        r = B.CreateAdd(a, b);
      else if (op.opcode == ir::Opcode::Sub)
        r = B.CreateSub(a, b);
      else if (op.opcode == ir::Opcode::Mul)
        r = B.CreateMul(a, b);
      else
        r = int_divmod(e, a, b, op.opcode == ir::Opcode::Mod);
    }
    e.store(op.args[0], Val{Dual{r}});
    return;
  }
  bool derivs = e.wants_derivs(op.args[0]);
  Val a = e.load_as(op, 1, t, derivs);
  Val b = unary ? Val{} : e.load_as(op, 2, t, derivs);
  if (derivs && !unary && op.opcode != ir::Opcode::Mod) zero_missing_derivs(e, a, b);
  // A constant divisor all zero divides safely, as OSL's does; another plainly.
  bool plain_div = const_divisor(e, op) == ConstDivisor::Nonzero;
  DualOps d(e);
  Val r(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    if (unary)
      r[i] = d.neg(a[i]);
    else if (op.opcode == ir::Opcode::Add)
      r[i] = d.add(a[i], b[i]);
    else if (op.opcode == ir::Opcode::Sub)
      r[i] = d.sub(a[i], b[i]);
    else if (op.opcode == ir::Opcode::Mul)
      r[i] = d.mul(a[i], b[i]);
    else if (op.opcode == ir::Opcode::Div)
      r[i] = osl_div(e, a[i], b[i], plain_div);
    else { // fmod (math::fmod), 0 where b == 0; d(fmod(a,b)) = da - trunc(a/b) db
      Dual q = d.div(a[i], b[i]);
      llvm::Value* tq = B.CreateUnaryIntrinsic(llvm::Intrinsic::trunc, q.v);
      Dual res{call_math(e, math::Fn::Fmod, shadeops::MathForm::Value, {a[i].v, b[i].v})};
      res.dx = d.dsub(a[i].dx, d.scale(b[i].dx, tq));
      res.dy = d.dsub(a[i].dy, d.scale(b[i].dy, tq));
      r[i] = res;
    }
  }
  e.store(op.args[0], r);
}

// The type two operands are compared in: the wider of the two (int < float < triple).
BaseType compare_type(const ir::Symbol& a, const ir::Symbol& b) {
  auto rank = [](BaseType t) {
    if (t == BaseType::Int) return 0;
    if (t == BaseType::Float) return 1;
    if (t == BaseType::Matrix) return 3;
    if (t == BaseType::String || t == BaseType::Closure) return 4;
    return 2;
  };
  return rank(a.type.base) >= rank(b.type.base) ? a.type.base : b.type.base;
}

// Comparisons as OSL's JIT computes them: float predicates are unordered, so a NaN operand
// makes every comparison true (== and != too); triples: == in all components, != in any.
void compare(LayerEmitter& e, const ir::Op& op) {
  auto& B = e.b();
  BaseType t = compare_type(e.arg(op, 1), e.arg(op, 2));
  Val a = e.load_as(op, 1, t, false), b = e.load_as(op, 2, t, false);
  const ir::Opcode o = op.opcode;
  llvm::Value* r = nullptr;
  if (o == ir::Opcode::Eq || o == ir::Opcode::Neq) {
    for (size_t i = 0; i < a.size(); ++i) {
      llvm::Value* c;
      if (t == BaseType::Int || t == BaseType::String || t == BaseType::Closure)
        c = B.CreateICmpEQ(a[i].v, b[i].v);
      else
        c = B.CreateFCmpUEQ(a[i].v, b[i].v);
      r = r ? B.CreateAnd(r, c) : c;
    }
    if (o == ir::Opcode::Neq && t != BaseType::Int && t != BaseType::String &&
        t != BaseType::Closure) {
      r = nullptr; // any component != (unordered: a NaN makes == and != both true)
      for (size_t i = 0; i < a.size(); ++i) {
        llvm::Value* c = B.CreateFCmpUNE(a[i].v, b[i].v);
        r = r ? B.CreateOr(r, c) : c;
      }
    } else if (o == ir::Opcode::Neq) {
      r = B.CreateNot(r);
    }
  } else if (t == BaseType::Int) {
    auto p = o == ir::Opcode::Lt   ? llvm::CmpInst::ICMP_SLT
             : o == ir::Opcode::Le ? llvm::CmpInst::ICMP_SLE
             : o == ir::Opcode::Gt ? llvm::CmpInst::ICMP_SGT
                                   : llvm::CmpInst::ICMP_SGE;
    r = B.CreateICmp(p, a[0].v, b[0].v);
  } else {
    auto p = o == ir::Opcode::Lt   ? llvm::CmpInst::FCMP_ULT
             : o == ir::Opcode::Le ? llvm::CmpInst::FCMP_ULE
             : o == ir::Opcode::Gt ? llvm::CmpInst::FCMP_UGT
                                   : llvm::CmpInst::FCMP_UGE;
    r = B.CreateFCmp(p, a[0].v, b[0].v);
  }
  e.store(op.args[0],
          e.convert(Val{Dual{B.CreateZExt(r, e.i32())}}, BaseType::Int, e.arg(op, 0).type.base));
}

// `!x`: x == 0, unordered for floats as OSL's generated code computes it (`!nan` is 1, while
// `nan` is also true as a condition: truthy).
void logic_not(LayerEmitter& e, const ir::Op& op) {
  BaseType t = e.arg(op, 1).type.base;
  Val v = e.load(op.args[1], nullptr, false);
  llvm::Value* zero = nullptr;
  if (t == BaseType::Int || t == BaseType::String || t == BaseType::Closure) {
    zero = e.b().CreateNot(e.truthy(v, t));
  } else {
    for (const Dual& d : v) {
      llvm::Value* z = e.b().CreateFCmpUEQ(d.v, e.fconst(0));
      zero = zero ? e.b().CreateAnd(zero, z) : z;
    }
  }
  Val r{Dual{e.b().CreateZExt(zero, e.i32())}};
  e.store(op.args[0], e.convert(r, BaseType::Int, e.arg(op, 0).type.base));
}

void bits(LayerEmitter& e, const ir::Op& op) {
  auto& B = e.b();
  llvm::Value* a = e.load_as(op, 1, BaseType::Int)[0].v;
  llvm::Value* r;
  if (op.opcode == ir::Opcode::Compl)
    r = B.CreateNot(a);
  else {
    llvm::Value* b = e.load_as(op, 2, BaseType::Int)[0].v;
    const ir::Opcode o = op.opcode;
    if (o == ir::Opcode::BitAnd)
      r = B.CreateAnd(a, b);
    else if (o == ir::Opcode::BitOr)
      r = B.CreateOr(a, b);
    else if (o == ir::Opcode::Xor)
      r = B.CreateXor(a, b);
    else { // shift counts are taken modulo 32 (C leaves larger ones undefined)
      llvm::Value* n = B.CreateAnd(b, e.iconst(31));
      r = o == ir::Opcode::Shl ? B.CreateShl(a, n) : B.CreateAShr(a, n);
    }
  }
  e.store(op.args[0], Val{Dual{r}});
}

const OpEntry kCoreOps[] = {
    {ir::Opcode::Assign, op_assign}, {ir::Opcode::Add, arith},     {ir::Opcode::Sub, arith},
    {ir::Opcode::Mul, arith},        {ir::Opcode::Div, arith},     {ir::Opcode::Mod, arith},
    {ir::Opcode::Neg, arith},        {ir::Opcode::Eq, compare},    {ir::Opcode::Neq, compare},
    {ir::Opcode::Lt, compare},       {ir::Opcode::Le, compare},    {ir::Opcode::Gt, compare},
    {ir::Opcode::Ge, compare},       {ir::Opcode::Not, logic_not}, {ir::Opcode::Compl, bits},
    {ir::Opcode::BitAnd, bits},      {ir::Opcode::BitOr, bits},    {ir::Opcode::Xor, bits},
    {ir::Opcode::Shl, bits},         {ir::Opcode::Shr, bits},
};

} // namespace

std::span<const OpEntry> core_ops() { return kCoreOps; }

} // namespace lobe::codegen

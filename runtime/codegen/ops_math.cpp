// The math library: per-component functions of floats and triples, each with its derivative.
// The values and derivative factors of the functions computed by formula (math::Fn: sin ...
// erfc, atan2, pow, fmod) come from out-of-line shadeops over runtime/mathlib/mathops.h, the
// code the constant folder runs too, so a folded value equals the computed one; the mode is
// CompileOptions::fast_math (OSL's fast-math values, or libm). Exact IEEE operations (sqrt,
// floor, fabs, ...) are inline, with the same rules as mathops.h (sqrt(x < 0) = 0, sign(NaN) =
// 1, ...). Derivatives are OSL's dual forms: where an argument is clamped the factor is 0.
#include "duals.h"
#include "mathops.h"
#include "op_tables.h"
#include "passes/math_opcode.h"
#include "shadeops.h"

#include <llvm/IR/Constants.h>
#include <llvm/IR/Intrinsics.h>

#include <cmath>

namespace lobe::codegen {
namespace {

using ir::BaseType;
using shadeops::MathForm;

llvm::Value* intr(LayerEmitter& e, llvm::Intrinsic::ID id, llvm::Value* x) {
  return e.b().CreateUnaryIntrinsic(id, x);
}
llvm::Value* fmul(LayerEmitter& e, llvm::Value* a, llvm::Value* b) {
  return e.b().CreateFMul(a, b);
}
llvm::Value* fdiv(LayerEmitter& e, llvm::Value* a, llvm::Value* b) {
  return e.b().CreateFDiv(a, b);
}

llvm::Value* math_mode(LayerEmitter& e) {
  return e.iconst(int(e.group().fast_math ? math::MathMode::FastJit : math::MathMode::Exact));
}

} // namespace

// A call of a math shadeop; value and slope functions read nothing but their arguments, so
// LLVM may share, hoist or drop them.
llvm::Value* call_math(LayerEmitter& e, math::Fn f, MathForm form, std::vector<llvm::Value*> args) {
  // Constant arguments (a literal at -O0, where nothing was specialised): the value OSL gets,
  // whose LLVM folds such a call with its multiply-adds unfused (llvm.fmuladd folds as a
  // product and a sum), as its optimiser and Lobe's folder compute (math::MathMode::Fast).
  auto* a = llvm::dyn_cast<llvm::ConstantFP>(args[0]);
  auto* b = args.size() > 1 ? llvm::dyn_cast<llvm::ConstantFP>(args[1]) : nullptr;
  if (form == MathForm::Value && a && (args.size() == 1 || b)) {
    math::MathMode m = e.group().fast_math ? math::MathMode::Fast : math::MathMode::Exact;
    float x = a->getValueAPF().convertToFloat();
    return e.fconst(b ? math::value2(f, m, x, b->getValueAPF().convertToFloat())
                      : math::value1(f, m, x));
  }
  const char* name = shadeops::math_shadeop(f, form);
  llvm::FunctionCallee callee = e.shadeop(name);
  if (auto* fn = llvm::dyn_cast<llvm::Function>(callee.getCallee()); fn && form != MathForm::Dual) {
    fn->setDoesNotAccessMemory();
    fn->setDoesNotThrow();
    fn->setWillReturn();
  }
  args.push_back(math_mode(e));
  return e.b().CreateCall(callee, args);
}

namespace {

// A binary math::Fn with derivatives: the dual shadeop over (value, d/dx, d/dy) triples.
Dual binary_dual(LayerEmitter& e, math::Fn f, const Dual& a, const Dual& b) {
  auto spill = [&](const Dual& x) {
    return e.spill({x.v, x.dx ? x.dx : e.fconst(0), x.dy ? x.dy : e.fconst(0)});
  };
  llvm::Value* out = e.spill({e.fconst(0), e.fconst(0), e.fconst(0)});
  call_math(e, f, MathForm::Dual, {out, spill(a), spill(b)});
  std::vector<llvm::Value*> r = e.reload(out, 3);
  return Dual{r[0], r[1], r[2]};
}

// The unary functions: value and derivative.
Dual unary(LayerEmitter& e, DualOps& d, ir::Opcode name, const Dual& x) {
  auto& B = e.b();
  llvm::Value* v = x.v;
  llvm::Value* one = e.fconst(1);
  llvm::Value* zero = e.fconst(0);
  if (const math::FnInfo* f = passes::math_fn(name, 1)) {
    llvm::Value* r = call_math(e, f->fn, MathForm::Value, {v});
    if (f->fn == math::Fn::Logb) return Dual{r}; // piecewise constant
    return d.chain(x, r, [&] { return call_math(e, f->fn, MathForm::Slope, {v}); });
  }
  if (name == ir::Opcode::Sqrt ||
      name == ir::Opcode::InverseSqrt) { // 0 outside the domain (NaN included)
    bool sq = name == ir::Opcode::Sqrt;
    llvm::Value* pos = sq ? B.CreateFCmpOGE(v, zero) : B.CreateFCmpOGT(v, zero);
    llvm::Value* s = intr(e, llvm::Intrinsic::sqrt, B.CreateSelect(pos, v, one));
    llvm::Value* r = B.CreateSelect(pos, sq ? s : fdiv(e, one, s), zero);
    return d.chain(x, r, [&] {
      // OSL's factors: 0.5 / sqrt(x) and (-0.5 * x^-0.5) / x, for x > 0 only
      llvm::Value* k = sq ? fdiv(e, e.fconst(0.5f), s) : fdiv(e, fmul(e, e.fconst(-0.5f), r), v);
      return B.CreateSelect(B.CreateFCmpOGT(v, zero), k, zero);
    });
  }
  if (name == ir::Opcode::Abs ||
      name == ir::Opcode::Fabs) { // |x|; the partials flip where !(x >= 0), as OSL's
    Dual r = d.select(B.CreateFCmpOGE(v, zero), x, d.neg(x));
    r.v = intr(e, llvm::Intrinsic::fabs, v);
    return r;
  }
  if (name == ir::Opcode::Sign) { // -1, 0 (either zero) or 1 (NaN too)
    llvm::Value* s = B.CreateSelect(B.CreateFCmpOLT(v, zero), e.fconst(-1),
                                    B.CreateSelect(B.CreateFCmpOEQ(v, zero), zero, one));
    return Dual{s};
  }
  if (name == ir::Opcode::Floor) return Dual{intr(e, llvm::Intrinsic::floor, v)};
  if (name == ir::Opcode::Ceil) return Dual{intr(e, llvm::Intrinsic::ceil, v)};
  if (name == ir::Opcode::Round) return Dual{intr(e, llvm::Intrinsic::round, v)};
  if (name == ir::Opcode::Trunc) return Dual{intr(e, llvm::Intrinsic::trunc, v)};
  return x;
}

void op_unary(LayerEmitter& e, const ir::Op& op) {
  BaseType t = e.arg(op, 0).type.base;
  auto& B = e.b();
  if (t == BaseType::Int) { // abs/sign of ints; float functions truncated into int results
    BaseType src = e.arg(op, 1).type.base;
    bool abs = op.opcode == ir::Opcode::Abs || op.opcode == ir::Opcode::Fabs;
    if (src == BaseType::Int && (abs || op.opcode == ir::Opcode::Sign)) {
      llvm::Value* x = e.load(op.args[1])[0].v;
      llvm::Value* r =
          abs ? B.CreateSelect(B.CreateICmpSLT(x, e.iconst(0)), B.CreateSub(e.iconst(0), x), x)
              : B.CreateSelect(
                    B.CreateICmpSGT(x, e.iconst(0)), e.iconst(1),
                    B.CreateSelect(B.CreateICmpSLT(x, e.iconst(0)), e.iconst(-1), e.iconst(0)));
      e.store(op.args[0], Val{Dual{r}});
      return;
    }
    DualOps d(e);
    Dual r = unary(e, d, op.opcode, e.load_as(op, 1, BaseType::Float, false)[0]);
    e.store(op.args[0], e.convert(Val{r}, BaseType::Float, BaseType::Int));
    return;
  }
  bool derivs = e.wants_derivs(op.args[0]);
  Val x = e.load_as(op, 1, t, derivs);
  DualOps d(e);
  Val r;
  for (const Dual& c : x) r.push_back(unary(e, d, op.opcode, c));
  e.store(op.args[0], r);
}

void op_isclass(LayerEmitter& e, const ir::Op& op) {
  auto& B = e.b();
  llvm::Value* x = e.load_as(op, 1, BaseType::Float, false)[0].v;
  llvm::Value* a = intr(e, llvm::Intrinsic::fabs, x);
  llvm::Value* inf = e.fconst(INFINITY);
  llvm::Value* r = op.opcode == ir::Opcode::IsNan   ? B.CreateFCmpUNO(x, x)
                   : op.opcode == ir::Opcode::IsInf ? B.CreateFCmpOEQ(a, inf)
                                                    : B.CreateFCmpOLT(a, inf);
  e.store(op.args[0], Val{Dual{B.CreateZExt(r, e.i32())}});
}

// fmod(a, b) for a divisor not known while compiling, as OSL computes it then: a - int(a/b) * b
// (one rounding: an fma) with the quotient truncated as x86's cvttss2si does (INT_MIN outside int32
// and for NaN), 0 where b is 0. It is not C's fmod: a quotient that rounds up to a whole number
// leaves a tiny remainder, not about b, and a huge one is garbage. OSL 1.13.12 prints
// "3.7252903e-08 1.64424509e+10 0" for printf("%.9g %.9g %.9g", fmod(-2.5 + z, 0.1 + z), fmod(1e10
// + z, 3 + z), fmod(-7.5 + z, 2.5 + z)) with z = floor(u) (testshade -g 1 1); with a constant
// divisor, C's fmod ("-0.0999999642" for fmod(-2.5 + z, 0.1)).
llvm::Value* fmod_varying(LayerEmitter& e, llvm::Value* a, llvm::Value* b) {
  auto& B = e.b();
  llvm::Value* b0 = B.CreateFCmpOEQ(b, e.fconst(0));
  llvm::Value* q = B.CreateFDiv(a, B.CreateSelect(b0, e.fconst(1), b));
  llvm::Value* n = e.convert(Val{Dual{q}}, BaseType::Float, BaseType::Int)[0].v; // x86's truncation
  // a - n b rounded once (OSL's shadeop is C++ compiled with contraction: an fma)
  llvm::Value* r = B.CreateIntrinsic(llvm::Intrinsic::fma, {e.f32()},
                                     {B.CreateFNeg(B.CreateSIToFP(n, e.f32())), b, a});
  return B.CreateSelect(b0, e.fconst(0), r);
}

// Binary and ternary per-component functions.
void op_nary(LayerEmitter& e, const ir::Op& op) {
  auto& B = e.b();
  BaseType t = e.arg(op, 0).type.base;
  const ir::Opcode o = op.opcode;
  if (t == BaseType::Int &&
      (o == ir::Opcode::Min || o == ir::Opcode::Max || o == ir::Opcode::Clamp)) {
    llvm::Value* a = e.load_as(op, 1, t)[0].v;
    llvm::Value* b = e.load_as(op, 2, t)[0].v;
    llvm::Value* r = o == ir::Opcode::Max ? B.CreateSelect(B.CreateICmpSGT(a, b), a, b)
                                          : B.CreateSelect(B.CreateICmpSLT(a, b), a, b);
    if (o == ir::Opcode::Clamp) {
      llvm::Value* mx = B.CreateSelect(B.CreateICmpSGT(a, b), a, b);
      llvm::Value* c = e.load_as(op, 3, t)[0].v;
      r = B.CreateSelect(B.CreateICmpSLT(mx, c), mx, c);
    }
    e.store(op.args[0], Val{Dual{r}});
    return;
  }
  bool derivs = e.wants_derivs(op.args[0]);
  BaseType ft = t == BaseType::Int ? BaseType::Float : t;
  std::vector<Val> a;
  for (size_t i = 1; i < op.args.size(); ++i) {
    const ir::Symbol& s = e.arg(op, int(i));
    // pow's exponent, mix's and smoothstep's float parameters broadcast like any other operand
    a.push_back(
        e.load_as(op, int(i), s.type.is_triple() || ft == BaseType::Float ? ft : ft, derivs));
  }
  DualOps d(e);
  Val r;
  // fmod by a constant divisor that is not all zeros is C's fmod of each component, as OSL
  // generates it (LLVM's frem): a zero component gives NaN (fmod(v, vector(0, 1, 0)) is
  // "-nan 0 -nan" at run time in OSL 1.13.12), NaN keeps the sign C gives it (fmod(-inf, 2) is
  // -nan); an all-zero constant divisor gives 0 (math::fmod).
  bool c_fmod = false;
  const math::FnInfo* fn2 = passes::math_fn(o, 2);
  if (fn2 && fn2->fn == math::Fn::Fmod && a.size() > 1 && e.arg(op, 2).kind == ir::SymKind::Const)
    for (const Dual& y : a[1])
      if (auto* k = llvm::dyn_cast<llvm::ConstantFP>(y.v); !k || !k->isZero()) c_fmod = true;
  for (size_t c = 0; c < a[0].size(); ++c) {
    const Dual& x = a[0][c];
    const Dual& y = a.size() > 1 ? a[1][c] : x;
    Dual z = a.size() > 2 ? a[2][c] : x;
    Dual out;
    if (const math::FnInfo* f = passes::math_fn(o, 2)) { // atan2, pow, fmod
      bool has = x.dx || x.dy || y.dx || y.dy;
      if (f->fn == math::Fn::Fmod && e.arg(op, 2).kind != ir::SymKind::Const)
        out = Dual{fmod_varying(e, x.v, y.v), x.dx, x.dy};
      else if (f->fn == math::Fn::Fmod && c_fmod)
        out = Dual{B.CreateFRem(x.v, y.v), x.dx, x.dy};
      else if (f->fn == math::Fn::Fmod || !has) // fmod passes a's derivatives on
        out = Dual{call_math(e, f->fn, MathForm::Value, {x.v, y.v}), x.dx, x.dy};
      else
        out = binary_dual(e, f->fn, x, y);
    } else if (o == ir::Opcode::Min) // OSL's: x <= y (unordered) ? x : y; a tie gives x
      out = d.select(B.CreateFCmpOLT(y.v, x.v), y, x);
    else if (o == ir::Opcode::Max) // OSL's: x > y (unordered) ? x : y; a tie gives y
      out = d.select(B.CreateFCmpUGT(x.v, y.v), x, y);
    else if (o == ir::Opcode::Clamp) { // min(max(x, lo), hi), a tie's derivatives as there
      Dual lo = d.select(B.CreateFCmpUGT(x.v, y.v), x, y);
      out = d.select(B.CreateFCmpOLT(z.v, lo.v), z, lo);
    } else if (o == ir::Opcode::Mix)
      out = d.add(d.mul(x, d.sub(d.constant(1), z)), d.mul(y, z));
    else if (o == ir::Opcode::Select)
      out = d.select(B.CreateFCmpUNE(z.v, e.fconst(0)), y, x);
    else if (o == ir::Opcode::Step)
      out = Dual{B.CreateSelect(B.CreateFCmpOLT(y.v, x.v), e.fconst(0), e.fconst(1))};
    else if (o == ir::Opcode::SmoothStep) { // t = (z-x)/(y-x) in [0, 1); t*t*(3-2t)
      // OSL multiplies in the order of its formula: t*t*(3-2t) for a value alone, (3-2t)*t*t
      // when the result carries derivatives (dual.h's smoothstep, with its division and its
      // contracted products; an edge pair with y == x never reaches the quotient: selected
      // away below). tests/shade/smoothstep_derivs_osl.osl.
      Dual tt = derivs ? d.div_dual_h(d.sub(z, x), d.sub(y, x)) : d.div(d.sub(z, x), d.sub(y, x));
      Dual k = d.sub(d.constant(3), d.mul(d.constant(2), tt));
      Dual s = derivs ? d.mul_dual_h(d.mul_dual_h(k, tt), tt) : d.mul(d.mul(tt, tt), k);
      out = d.select(B.CreateFCmpOLT(z.v, x.v), d.constant(0),
                     d.select(B.CreateFCmpOGE(z.v, y.v), d.constant(1), s));
    } else if (o == ir::Opcode::Hypot) {
      Dual s2 = d.add(d.mul(x, x), d.mul(y, y));
      if (a.size() > 2) s2 = d.add(s2, d.mul(z, z));
      out = unary(e, d, ir::Opcode::Sqrt, s2);
    } else if (o == ir::Opcode::Log) { // log(x, base)
      out = d.div(unary(e, d, ir::Opcode::Log, x), unary(e, d, ir::Opcode::Log, y));
    }
    r.push_back(out);
  }
  e.store(op.args[0], e.convert(r, ft, t));
}

void op_log(LayerEmitter& e, const ir::Op& op) {
  if (op.args.size() == 3) return op_nary(e, op);
  op_unary(e, op);
}

void op_sincos(LayerEmitter& e, const ir::Op& op) {
  BaseType t = e.arg(op, 0).type.base;
  Val x = e.load_as(op, 2, t);
  DualOps d(e);
  Val s, c;
  for (const Dual& v : x) {
    s.push_back(unary(e, d, ir::Opcode::Sin, v));
    c.push_back(unary(e, d, ir::Opcode::Cos, v));
  }
  e.store(op.args[0], s);
  e.store(op.args[1], c);
}

// A math_functions.h row's emitter: log's own (its base form), else by arity.
void op_math_function(LayerEmitter& e, const ir::Op& op) {
  if (op.opcode == ir::Opcode::Log) return op_log(e, op);
  if (ir::info(op.opcode).min_args == 2) return op_unary(e, op);
  op_nary(e, op);
}

const OpEntry kMathOps[] = {
// clang-format off
#define LOBE_MATH_EMIT_ROW(x, e, name, arity, max, forms, doc) {ir::Opcode::e, op_math_function},
    LOBE_MATH_FUNCTIONS(LOBE_MATH_EMIT_ROW, _)
#undef LOBE_MATH_EMIT_ROW
    // clang-format on
    {ir::Opcode::Sqrt, op_unary},
    {ir::Opcode::InverseSqrt, op_unary},
    {ir::Opcode::Abs, op_unary},
    {ir::Opcode::Fabs, op_unary},
    {ir::Opcode::Sign, op_unary},
    {ir::Opcode::Floor, op_unary},
    {ir::Opcode::Ceil, op_unary},
    {ir::Opcode::Round, op_unary},
    {ir::Opcode::Trunc, op_unary},
    {ir::Opcode::IsNan, op_isclass},
    {ir::Opcode::IsInf, op_isclass},
    {ir::Opcode::IsFinite, op_isclass},
    {ir::Opcode::Min, op_nary},
    {ir::Opcode::Max, op_nary},
    {ir::Opcode::Clamp, op_nary},
    {ir::Opcode::Mix, op_nary},
    {ir::Opcode::Select, op_nary},
    {ir::Opcode::Step, op_nary},
    {ir::Opcode::SmoothStep, op_nary},
    {ir::Opcode::Hypot, op_nary},
    {ir::Opcode::SinCos, op_sincos},
};

} // namespace

std::span<const OpEntry> math_ops() { return kMathOps; }

} // namespace lobe::codegen

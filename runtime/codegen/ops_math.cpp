// The math library: per-component functions of floats and triples, each with its derivative
// (chain rule). Out-of-domain inputs follow OSL's "safe" math (OIIO safe_* / fast_*, what OSL's
// shadeops use), docs/runtime.md: log/log2/log10/logb clamp the argument to [FLT_MIN, FLT_MAX]
// (log(0) = log(FLT_MIN) = -87.3365), asin/acos clamp to [-1, 1], pow is safe_pow (x^0 = 1,
// 0^y = 0, negative x with a non-integer y gives 0, the result is clamped to +-FLT_MAX), sqrt
// and inversesqrt of values outside the domain are 0, fmod by 0 is 0. Where the argument is
// clamped the derivative is 0, so derivatives stay finite. The constant folder
// (compiler/passes/consteval.cpp) computes pow the same way.
#include "duals.h"
#include "op_tables.h"

#include <llvm/IR/Constants.h>
#include <llvm/IR/Intrinsics.h>

#include <cfloat>
#include <cmath>
#include <functional>

namespace lobe::codegen {
namespace {

using ir::BaseType;
using Fn1 = std::function<Dual(LayerEmitter&, DualOps&, const Dual&)>;

llvm::Value* intr(LayerEmitter& e, llvm::Intrinsic::ID id, llvm::Value* x) {
  return e.b().CreateUnaryIntrinsic(id, x);
}
llvm::Value* libm(LayerEmitter& e, const char* name, llvm::Value* x) { return e.call(name, {x}); }
llvm::Value* fmul(LayerEmitter& e, llvm::Value* a, llvm::Value* b) {
  return e.b().CreateFMul(a, b);
}
llvm::Value* fdiv(LayerEmitter& e, llvm::Value* a, llvm::Value* b) {
  return e.b().CreateFDiv(a, b);
}

// v clamped to [-FLT_MAX, FLT_MAX] (NaN stays NaN).
llvm::Value* clamp_big(LayerEmitter& e, llvm::Value* v) {
  auto& B = e.b();
  v = B.CreateSelect(B.CreateFCmpOGT(v, e.fconst(FLT_MAX)), e.fconst(FLT_MAX), v);
  return B.CreateSelect(B.CreateFCmpOLT(v, e.fconst(-FLT_MAX)), e.fconst(-FLT_MAX), v);
}

// OIIO safe_pow: y == 0 gives 1, x == 0 gives 0, x < 0 with a non-integer y gives 0, otherwise
// pow(x, y) clamped to +-FLT_MAX.
llvm::Value* safe_pow(LayerEmitter& e, llvm::Value* x, llvm::Value* y) {
  auto& B = e.b();
  llvm::Value* p = clamp_big(e, B.CreateBinaryIntrinsic(llvm::Intrinsic::pow, x, y));
  llvm::Value* nonint = B.CreateFCmpUNE(y, intr(e, llvm::Intrinsic::floor, y));
  llvm::Value* zero = B.CreateOr(B.CreateFCmpOEQ(x, e.fconst(0)),
                                 B.CreateAnd(B.CreateFCmpOLT(x, e.fconst(0)), nonint));
  p = B.CreateSelect(zero, e.fconst(0), p);
  return B.CreateSelect(B.CreateFCmpOEQ(y, e.fconst(0)), e.fconst(1), p);
}

// The unary functions: value and derivative.
Dual unary(LayerEmitter& e, DualOps& d, const std::string& name, const Dual& x) {
  auto& B = e.b();
  llvm::Value* v = x.v;
  using I = llvm::Intrinsic::ID;
  auto by_intr = [&](I id, auto slope) { return d.chain(x, intr(e, id, v), slope); };
  auto by_libm = [&](const char* fn, auto slope) { return d.chain(x, libm(e, fn, v), slope); };
  llvm::Value* one = e.fconst(1);
  if (name == "sin")
    return by_intr(llvm::Intrinsic::sin, [&] { return intr(e, llvm::Intrinsic::cos, v); });
  if (name == "cos")
    return by_intr(llvm::Intrinsic::cos,
                   [&] { return B.CreateFNeg(intr(e, llvm::Intrinsic::sin, v)); });
  if (name == "tan")
    return by_libm("tanf", [&] {
      llvm::Value* c = intr(e, llvm::Intrinsic::cos, v);
      return fdiv(e, one, fmul(e, c, c));
    });
  if (name == "asin" || name == "acos") { // OIIO safe_asin / safe_acos: x clamped to [-1, 1]
    bool as = name == "asin";
    llvm::Value* hi = B.CreateFCmpOGE(v, one);
    llvm::Value* lo = B.CreateFCmpOLE(v, e.fconst(-1));
    llvm::Value* r = libm(e, as ? "asinf" : "acosf", v);
    r = B.CreateSelect(hi, e.fconst(as ? float(M_PI_2) : 0.0f),
                       B.CreateSelect(lo, e.fconst(as ? float(-M_PI_2) : float(M_PI)), r));
    return d.chain(x, r, [&] {
      llvm::Value* inside = B.CreateFCmpOLT(intr(e, llvm::Intrinsic::fabs, v), one);
      llvm::Value* s = intr(e, llvm::Intrinsic::sqrt,
                            B.CreateSelect(inside, B.CreateFSub(one, fmul(e, v, v)), one));
      return B.CreateSelect(inside, fdiv(e, e.fconst(as ? 1.0f : -1.0f), s), e.fconst(0));
    });
  }
  if (name == "atan")
    return by_libm("atanf", [&] { return fdiv(e, one, B.CreateFAdd(one, fmul(e, v, v))); });
  if (name == "sinh") return by_libm("sinhf", [&] { return libm(e, "coshf", v); });
  if (name == "cosh") return by_libm("coshf", [&] { return libm(e, "sinhf", v); });
  if (name == "tanh") {
    llvm::Value* t = libm(e, "tanhf", v);
    return d.chain(x, t, [&] { return B.CreateFSub(one, fmul(e, t, t)); });
  }
  if (name == "exp") {
    llvm::Value* r = intr(e, llvm::Intrinsic::exp, v);
    return d.chain(x, r, [&] { return r; });
  }
  if (name == "exp2") {
    llvm::Value* r = intr(e, llvm::Intrinsic::exp2, v);
    return d.chain(x, r, [&] { return fmul(e, r, e.fconst(float(M_LN2))); });
  }
  if (name == "expm1") return by_libm("expm1f", [&] { return intr(e, llvm::Intrinsic::exp, v); });
  if (name == "log" || name == "log2" || name == "log10" || name == "logb") {
    // OIIO safe_log*/fast_logb: the argument (|x| for logb) clamped to [FLT_MIN, FLT_MAX], so
    // log(0) = log(FLT_MIN) = -87.3365, log2(0) = -126, logb(0) = -126; NaN stays NaN.
    llvm::Value* a = name == "logb" ? intr(e, llvm::Intrinsic::fabs, v) : v;
    llvm::Value* below = B.CreateFCmpOLT(a, e.fconst(FLT_MIN));
    llvm::Value* above = B.CreateFCmpOGT(a, e.fconst(FLT_MAX));
    llvm::Value* c =
        B.CreateSelect(below, e.fconst(FLT_MIN), B.CreateSelect(above, e.fconst(FLT_MAX), a));
    if (name == "logb") return Dual{libm(e, "logbf", c)};
    I id = name == "log"    ? llvm::Intrinsic::log
           : name == "log2" ? llvm::Intrinsic::log2
                            : llvm::Intrinsic::log10;
    double k = name == "log" ? 1.0 : name == "log2" ? 1 / M_LN2 : 1 / M_LN10;
    return d.chain(x, intr(e, id, c), [&] {
      return B.CreateSelect(B.CreateOr(below, above), e.fconst(0), fdiv(e, e.fconst(float(k)), c));
    });
  }
  if (name == "sqrt" || name == "inversesqrt") {
    llvm::Value* pos =
        name == "sqrt" ? B.CreateFCmpOGE(v, e.fconst(0)) : B.CreateFCmpOGT(v, e.fconst(0));
    llvm::Value* s = intr(e, llvm::Intrinsic::sqrt, B.CreateSelect(pos, v, one));
    llvm::Value* r = name == "sqrt" ? s : fdiv(e, one, s);
    r = B.CreateSelect(pos, r, e.fconst(0));
    return d.chain(x, r, [&] {
      // sqrt' = 0.5 / sqrt(x); inversesqrt' = -0.5 * x^-1.5; 0 outside the domain
      llvm::Value* k = name == "sqrt" ? fdiv(e, e.fconst(0.5f), s)
                                      : fdiv(e, e.fconst(-0.5f), fmul(e, s, B.CreateFMul(s, s)));
      return B.CreateSelect(B.CreateFCmpOGT(v, e.fconst(0)), k, e.fconst(0));
    });
  }
  if (name == "cbrt") {
    llvm::Value* r = libm(e, "cbrtf", v);
    return d.chain(x, r, [&] { return fdiv(e, one, fmul(e, e.fconst(3), fmul(e, r, r))); });
  }
  if (name == "abs" || name == "fabs") { // fabs keeps IEEE's |-0| = +0
    llvm::Value* neg = B.CreateFCmpOLT(v, e.fconst(0));
    Dual r = d.select(neg, d.neg(x), x);
    r.v = intr(e, llvm::Intrinsic::fabs, v);
    return r;
  }
  if (name == "sign") {
    llvm::Value* s =
        B.CreateSelect(B.CreateFCmpOGT(v, e.fconst(0)), one,
                       B.CreateSelect(B.CreateFCmpOLT(v, e.fconst(0)), e.fconst(-1), e.fconst(0)));
    return Dual{s};
  }
  if (name == "floor") return Dual{intr(e, llvm::Intrinsic::floor, v)};
  if (name == "ceil") return Dual{intr(e, llvm::Intrinsic::ceil, v)};
  if (name == "round") return Dual{intr(e, llvm::Intrinsic::round, v)};
  if (name == "trunc") return Dual{intr(e, llvm::Intrinsic::trunc, v)};
  if (name == "erf" || name == "erfc") {
    llvm::Value* r = libm(e, name == "erf" ? "erff" : "erfcf", v);
    return d.chain(x, r, [&] {
      llvm::Value* g = intr(e, llvm::Intrinsic::exp, B.CreateFNeg(fmul(e, v, v)));
      return fmul(e, g, e.fconst(float((name == "erf" ? 2 : -2) / std::sqrt(M_PI))));
    });
  }
  return x;
}

void op_unary(LayerEmitter& e, const ir::Op& op) {
  BaseType t = e.arg(op, 0).type.base;
  auto& B = e.b();
  if (t == BaseType::Int) { // abs/sign of ints; float functions truncated into int results
    BaseType src = e.arg(op, 1).type.base;
    if (src == BaseType::Int && (op.opcode == "abs" || op.opcode == "sign")) {
      llvm::Value* x = e.load(op.args[1])[0].v;
      llvm::Value* r =
          op.opcode == "abs"
              ? B.CreateSelect(B.CreateICmpSLT(x, e.iconst(0)), B.CreateSub(e.iconst(0), x), x)
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
  llvm::Value* r = op.opcode == "isnan"   ? B.CreateFCmpUNO(x, x)
                   : op.opcode == "isinf" ? B.CreateFCmpOEQ(a, inf)
                                          : B.CreateFCmpOLT(a, inf);
  e.store(op.args[0], Val{Dual{B.CreateZExt(r, e.i32())}});
}

// Binary and ternary per-component functions.
void op_nary(LayerEmitter& e, const ir::Op& op) {
  auto& B = e.b();
  BaseType t = e.arg(op, 0).type.base;
  const std::string& o = op.opcode;
  if (t == BaseType::Int && (o == "min" || o == "max" || o == "clamp")) {
    llvm::Value* a = e.load_as(op, 1, t)[0].v;
    llvm::Value* b = e.load_as(op, 2, t)[0].v;
    llvm::Value* r = o == "max" ? B.CreateSelect(B.CreateICmpSGT(a, b), a, b)
                                : B.CreateSelect(B.CreateICmpSLT(a, b), a, b);
    if (o == "clamp") {
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
  for (size_t c = 0; c < a[0].size(); ++c) {
    const Dual& x = a[0][c];
    const Dual& y = a.size() > 1 ? a[1][c] : x;
    Dual z = a.size() > 2 ? a[2][c] : x;
    Dual out;
    if (o == "pow") {
      llvm::Value* p = safe_pow(e, x.v, y.v);
      out = Dual{p};
      if (x.dx || x.dy) { // y x^(y-1), with safe_pow (0 where x^y is 0 by the safe rule)
        llvm::Value* k =
            clamp_big(e, B.CreateFMul(y.v, safe_pow(e, x.v, B.CreateFSub(y.v, e.fconst(1)))));
        out.dx = d.scale(x.dx, k);
        out.dy = d.scale(x.dy, k);
      }
      if (y.dx || y.dy) { // x^y ln x for x > 0, else 0 (OSL's dual safe_pow)
        llvm::Value* pos = B.CreateFCmpOGT(x.v, e.fconst(0));
        llvm::Value* lx = intr(e, llvm::Intrinsic::log, B.CreateSelect(pos, x.v, e.fconst(1)));
        llvm::Value* k = B.CreateSelect(pos, clamp_big(e, B.CreateFMul(p, lx)), e.fconst(0));
        out.dx = d.dadd(out.dx, d.scale(y.dx, k));
        out.dy = d.dadd(out.dy, d.scale(y.dy, k));
      }
    } else if (o == "atan2") { // d = (x dy - y dx) / (x^2 + y^2) with y = first operand
      out = Dual{e.call("atan2f", {x.v, y.v})};
      if (x.dx || x.dy || y.dx || y.dy) {
        llvm::Value* den = B.CreateFAdd(B.CreateFMul(x.v, x.v), B.CreateFMul(y.v, y.v));
        auto g = [&](llvm::Value* dyv, llvm::Value* dxv) -> llvm::Value* {
          llvm::Value* n = d.dsub(d.scale(dyv, y.v), d.scale(dxv, x.v));
          return n ? B.CreateFDiv(n, den) : nullptr;
        };
        out.dx = g(x.dx, y.dx);
        out.dy = g(x.dy, y.dy);
      }
    } else if (o == "fmod") {
      llvm::Value* b0 = B.CreateFCmpOEQ(y.v, e.fconst(0));
      llvm::Value* m = B.CreateFRem(x.v, B.CreateSelect(b0, e.fconst(1), y.v));
      out = Dual{B.CreateSelect(b0, e.fconst(0), m), x.dx, x.dy};
    } else if (o == "min")
      out = d.select(B.CreateFCmpOLT(y.v, x.v), y, x);
    else if (o == "max")
      out = d.select(B.CreateFCmpOGT(y.v, x.v), y, x);
    else if (o == "clamp") {
      Dual lo = d.select(B.CreateFCmpOGT(y.v, x.v), y, x);
      out = d.select(B.CreateFCmpOLT(z.v, lo.v), z, lo);
    } else if (o == "mix")
      out = d.add(d.mul(x, d.sub(d.constant(1), z)), d.mul(y, z));
    else if (o == "select")
      out = d.select(B.CreateFCmpUNE(z.v, e.fconst(0)), y, x);
    else if (o == "step")
      out = Dual{B.CreateSelect(B.CreateFCmpOLT(y.v, x.v), e.fconst(0), e.fconst(1))};
    else if (o == "smoothstep") { // t = clamp((z-x)/(y-x)); t*t*(3-2t)
      Dual tt = d.div(d.sub(z, x), d.sub(y, x));
      Dual s = d.mul(d.mul(tt, tt), d.sub(d.constant(3), d.mul(d.constant(2), tt)));
      out = d.select(B.CreateFCmpOLT(z.v, x.v), d.constant(0),
                     d.select(B.CreateFCmpOGE(z.v, y.v), d.constant(1), s));
    } else if (o == "hypot") {
      Dual s2 = d.add(d.mul(x, x), d.mul(y, y));
      if (a.size() > 2) s2 = d.add(s2, d.mul(z, z));
      out = unary(e, d, "sqrt", s2);
    } else if (o == "log") { // log(x, base)
      out = d.div(unary(e, d, "log", x), unary(e, d, "log", y));
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
    s.push_back(unary(e, d, "sin", v));
    c.push_back(unary(e, d, "cos", v));
  }
  e.store(op.args[0], s);
  e.store(op.args[1], c);
}

const OpEntry kMathOps[] = {
    {"sin", op_unary},        {"cos", op_unary},       {"tan", op_unary},
    {"asin", op_unary},       {"acos", op_unary},      {"atan", op_unary},
    {"sinh", op_unary},       {"cosh", op_unary},      {"tanh", op_unary},
    {"exp", op_unary},        {"exp2", op_unary},      {"expm1", op_unary},
    {"log", op_log},          {"log2", op_unary},      {"log10", op_unary},
    {"logb", op_unary},       {"sqrt", op_unary},      {"inversesqrt", op_unary},
    {"cbrt", op_unary},       {"abs", op_unary},       {"fabs", op_unary},
    {"sign", op_unary},       {"floor", op_unary},     {"ceil", op_unary},
    {"round", op_unary},      {"trunc", op_unary},     {"erf", op_unary},
    {"erfc", op_unary},       {"isnan", op_isclass},   {"isinf", op_isclass},
    {"isfinite", op_isclass}, {"pow", op_nary},        {"atan2", op_nary},
    {"fmod", op_nary},        {"min", op_nary},        {"max", op_nary},
    {"clamp", op_nary},       {"mix", op_nary},        {"select", op_nary},
    {"step", op_nary},        {"smoothstep", op_nary}, {"hypot", op_nary},
    {"sincos", op_sincos},
};

} // namespace

std::span<const OpEntry> math_ops() { return kMathOps; }

} // namespace lobe::codegen

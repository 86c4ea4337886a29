// Scalar dual-number arithmetic for codegen: value and d/dx, d/dy through the chain rule.
// A null derivative is zero and stays null through ops that cannot make it non-zero, so code
// without derivatives pays nothing.
#pragma once

#include "emitter.h"

namespace lobe::codegen {

class DualOps {
public:
  explicit DualOps(LayerEmitter& e) : e_(e), b_(e.b()) {}

  Dual add(const Dual& x, const Dual& y) {
    return {b_.CreateFAdd(x.v, y.v), dadd(x.dx, y.dx), dadd(x.dy, y.dy)};
  }
  Dual sub(const Dual& x, const Dual& y) {
    return {b_.CreateFSub(x.v, y.v), dsub(x.dx, y.dx), dsub(x.dy, y.dy)};
  }
  Dual mul(const Dual& x, const Dual& y) {
    return {b_.CreateFMul(x.v, y.v), dadd(scale(x.dx, y.v), scale(y.dx, x.v)),
            dadd(scale(x.dy, y.v), scale(y.dy, x.v))};
  }
  // x / y, and 0 where y == 0 (OSL's rule; its derivatives too).
  Dual div(const Dual& x, const Dual& y) {
    llvm::Value* zero = e_.fconst(0);
    llvm::Value* y0 = b_.CreateFCmpOEQ(y.v, zero);
    llvm::Value* safe_y = b_.CreateSelect(y0, e_.fconst(1), y.v);
    llvm::Value* q = b_.CreateFDiv(x.v, safe_y);
    Dual r{b_.CreateSelect(y0, zero, q)};
    // d(x/y) = (dx - q dy) / y
    auto d = [&](llvm::Value* dxv, llvm::Value* dyv) -> llvm::Value* {
      if (!dxv && !dyv) return nullptr;
      llvm::Value* num = dsub(dxv, scale(dyv, q));
      return b_.CreateSelect(y0, zero, b_.CreateFDiv(num, safe_y));
    };
    r.dx = d(x.dx, y.dx);
    r.dy = d(x.dy, y.dy);
    return r;
  }
  // x * y as OSL's Dual product is compiled into its C++ shadeops (dual.h, clang contracting
  // the partial x.val * y.d + x.d * y.val into fmuladd(x.val, y.d, x.d * y.val)).
  Dual mul_dual_h(const Dual& x, const Dual& y) {
    Dual r{b_.CreateFMul(x.v, y.v)};
    auto d = [&](llvm::Value* xd, llvm::Value* yd) -> llvm::Value* {
      if (!xd && !yd) return nullptr;
      if (!yd) return b_.CreateFMul(xd, y.v);
      llvm::Value* rest = xd ? b_.CreateFMul(xd, y.v) : e_.fconst(0);
      return b_.CreateIntrinsic(llvm::Intrinsic::fmuladd, {b_.getFloatTy()}, {x.v, yd, rest});
    };
    r.dx = d(x.dx, y.dx);
    r.dy = d(x.dy, y.dy);
    return r;
  }
  // x / y as OSL's Dual division computes it (dual.h, which its C++ shadeops use): the
  // derivatives are (1 / y) * (dx - q dy), no zero guard.
  Dual div_dual_h(const Dual& x, const Dual& y) {
    llvm::Value* q = b_.CreateFDiv(x.v, y.v);
    Dual r{q};
    if (!x.dx && !x.dy && !y.dx && !y.dy) return r;
    llvm::Value* inv = b_.CreateFDiv(e_.fconst(1), y.v);
    auto d = [&](llvm::Value* dxv, llvm::Value* dyv) -> llvm::Value* {
      if (!dxv && !dyv) return nullptr;
      return b_.CreateFMul(inv, dsub(dxv, scale(dyv, q)));
    };
    r.dx = d(x.dx, y.dx);
    r.dy = d(x.dy, y.dy);
    return r;
  }
  Dual neg(const Dual& x) {
    return {b_.CreateFNeg(x.v), x.dx ? b_.CreateFNeg(x.dx) : nullptr,
            x.dy ? b_.CreateFNeg(x.dy) : nullptr};
  }
  // f(x) with derivative f'(x) = `slope` (evaluated lazily only if x has derivatives).
  template <class Slope> Dual chain(const Dual& x, llvm::Value* fx, Slope slope) {
    Dual r{fx};
    if (x.dx || x.dy) {
      llvm::Value* s = slope();
      r.dx = scale(x.dx, s);
      r.dy = scale(x.dy, s);
    }
    return r;
  }
  // cond ? x : y, derivatives chosen alike.
  Dual select(llvm::Value* cond, const Dual& x, const Dual& y) {
    auto pick = [&](llvm::Value* a, llvm::Value* c) -> llvm::Value* {
      if (!a && !c) return nullptr;
      return b_.CreateSelect(cond, a ? a : e_.fconst(0), c ? c : e_.fconst(0));
    };
    return {b_.CreateSelect(cond, x.v, y.v), pick(x.dx, y.dx), pick(x.dy, y.dy)};
  }
  Dual constant(float f) { return {e_.fconst(f)}; }

  llvm::Value* scale(llvm::Value* d, llvm::Value* s) { return d ? b_.CreateFMul(d, s) : nullptr; }
  llvm::Value* dadd(llvm::Value* a, llvm::Value* c) {
    if (!a) return c;
    if (!c) return a;
    return b_.CreateFAdd(a, c);
  }
  llvm::Value* dsub(llvm::Value* a, llvm::Value* c) {
    if (!c) return a;
    if (!a) return b_.CreateFNeg(c);
    return b_.CreateFSub(a, c);
  }

private:
  LayerEmitter& e_;
  llvm::IRBuilder<>& b_;
};

} // namespace lobe::codegen

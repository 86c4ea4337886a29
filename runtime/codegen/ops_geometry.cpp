// Geometry, colour and matrix functions (dot, cross, normalize, transform, luminance,
// blackbody, determinant, ...) and the derivative ops (Dx, Dy, Dz, filterwidth, area,
// calculatenormal).
#include "color_system.h"
#include "duals.h"
#include "op_tables.h"
#include "shadeops.h"

#include "lobe/shading.h"

#include <llvm/IR/Constants.h>
#include <llvm/IR/Intrinsics.h>

#include <cmath>
#include <limits>

namespace lobe::codegen {
namespace {

using ir::BaseType;

// With derivatives, each product as OSL's Dual product (mul_dual_h: the partial
// fmuladd(x.val, y.d, x.d * y.val)), summed in order: OSL 1.13.12's bits for dot and cross of
// varying triples (Dx(dot(a, P)) on a 16x16 grid: 256 of 256 points, 203 before).
Dual dot3(DualOps& d, const Val& a, const Val& b) {
  return d.add(d.add(d.mul_dual_h(a[0], b[0]), d.mul_dual_h(a[1], b[1])), d.mul_dual_h(a[2], b[2]));
}
Val cross3(DualOps& d, const Val& a, const Val& b) {
  auto m = [&](int i, int j) { return d.mul_dual_h(a[size_t(i)], b[size_t(j)]); };
  return {d.sub(m(1, 2), m(2, 1)), d.sub(m(2, 0), m(0, 2)), d.sub(m(0, 1), m(1, 0))};
}
Dual sqrt_dual(LayerEmitter& e, DualOps& d, const Dual& x) {
  auto& B = e.b();
  llvm::Value* pos = B.CreateFCmpOGT(x.v, e.fconst(0));
  llvm::Value* s =
      B.CreateUnaryIntrinsic(llvm::Intrinsic::sqrt, B.CreateSelect(pos, x.v, e.fconst(0)));
  return d.chain(x, s, [&] {
    return B.CreateSelect(pos, B.CreateFDiv(e.fconst(0.5f), B.CreateSelect(pos, s, e.fconst(1))),
                          e.fconst(0));
  });
}
std::vector<llvm::Value*> values(const Val& v) {
  std::vector<llvm::Value*> out;
  for (const Dual& x : v) out.push_back(x.v);
  return out;
}
Val from_values(const std::vector<llvm::Value*>& v) {
  Val out;
  for (llvm::Value* x : v) out.push_back(Dual{x});
  return out;
}

Val load3(LayerEmitter& e, const ir::Op& op, int i) {
  return e.load_as(op, i, BaseType::Vector, e.wants_derivs(op.args[0]));
}

// Without derivatives OSL computes dot, cross, length, distance and normalize in its shadeops
// (Imath's formulas, clang bitcode), whose multiply-adds clang contracts into llvm.fmuladd: fused
// on the host (FMA) and unfused when LLVM folds constants. The same here: a*b + c*d is
// fmuladd(a, b, c*d), and a*b - c*d fmuladd(a, b, -(c*d)), as clang forms them from the left.
// With derivatives: dot3 and cross3 (each product's partials contracted, as OSL's Dual product).
llvm::Value* fmuladd(LayerEmitter& e, llvm::Value* a, llvm::Value* b, llvm::Value* c) {
  return e.b().CreateIntrinsic(llvm::Intrinsic::fmuladd, {e.b().getFloatTy()}, {a, b, c});
}
llvm::Value* dot_fused(LayerEmitter& e, const Val& a, const Val& b) {
  auto& B = e.b();
  return fmuladd(e, a[2].v, b[2].v, fmuladd(e, a[0].v, b[0].v, B.CreateFMul(a[1].v, b[1].v)));
}
Val cross_fused(LayerEmitter& e, const Val& a, const Val& b) {
  auto& B = e.b();
  auto term = [&](int i, int j) { // a[i] b[j] - a[j] b[i]
    return fmuladd(e, a[size_t(i)].v, b[size_t(j)].v,
                   B.CreateFNeg(B.CreateFMul(a[size_t(j)].v, b[size_t(i)].v)));
  };
  return {Dual{term(1, 2)}, Dual{term(2, 0)}, Dual{term(0, 1)}};
}
// sqrt of a squared length: 0 where it is not positive (and NaN), as sqrt_dual.
llvm::Value* sqrt_pos(LayerEmitter& e, llvm::Value* x) {
  auto& B = e.b();
  llvm::Value* pos = B.CreateFCmpOGT(x, e.fconst(0));
  return B.CreateSelect(
      pos, B.CreateUnaryIntrinsic(llvm::Intrinsic::sqrt, B.CreateSelect(pos, x, e.fconst(0))),
      e.fconst(0));
}

// The components of `a` when all three are constants (folded as OSL's optimiser folds: on the
// host, each product and sum rounded; this file is compiled without contraction).
bool constant3(const Val& a, float out[3]) {
  for (size_t i = 0; i < 3; ++i) {
    auto* c = llvm::dyn_cast<llvm::ConstantFP>(a[i].v);
    if (!c) return false;
    out[i] = c->getValueAPF().convertToFloat();
  }
  return true;
}

// Imath's Vec3::length (OSL's length without derivatives): the square root of the squared
// length, or where that is below 2 * FLT_MIN (it underflowed), lengthTiny: the largest
// |component| m times the length of the vector divided by m. `fused`: the sums of squares as
// dot_fused contracts them, which is how LLVM folds OSL's length shadeop on constants (fma);
// unfused, as OSL's optimiser folds normalize (Imath's normalized(), host code).
float imath_length(const float v[3], bool fused) {
  auto sum2 = [fused](float x, float y, float z) {
    return fused ? std::fma(z, z, std::fma(x, x, y * y)) : x * x + y * y + z * z;
  };
  float len2 = sum2(v[0], v[1], v[2]);
  if (!(len2 < 2 * std::numeric_limits<float>::min())) return std::sqrt(len2);
  float ax = std::fabs(v[0]), ay = std::fabs(v[1]), az = std::fabs(v[2]);
  float m = ax;
  if (m < ay) m = ay;
  if (m < az) m = az;
  if (m == 0.0f) return 0.0f;
  ax /= m, ay /= m, az /= m;
  return m * std::sqrt(sum2(ax, ay, az));
}

// The same at run time, as OSL's shadeop computes it (contracted multiply-adds); lengthTiny on
// its own branch, so the common case pays a compare. A NaN component gives NaN, as in OSL (the
// squared length is not below the threshold, and its square root is NaN).
llvm::Value* length_value(LayerEmitter& e, const Val& a) {
  float c[3];
  if (constant3(a, c)) return e.fconst(imath_length(c, true));
  auto& B = e.b();
  llvm::Value* len2 = dot_fused(e, a, a);
  llvm::Value* normal = B.CreateUnaryIntrinsic(llvm::Intrinsic::sqrt, len2);
  llvm::BasicBlock* from = B.GetInsertBlock();
  llvm::Function* fn = from->getParent();
  auto* tiny = llvm::BasicBlock::Create(e.ctx(), "length_tiny", fn);
  auto* done = llvm::BasicBlock::Create(e.ctx(), "length_done", fn);
  B.CreateCondBr(B.CreateFCmpOLT(len2, e.fconst(2 * std::numeric_limits<float>::min())), tiny,
                 done);
  B.SetInsertPoint(tiny);
  Val m3(3);
  for (size_t i = 0; i < 3; ++i)
    m3[i] = Dual{B.CreateUnaryIntrinsic(llvm::Intrinsic::fabs, a[i].v)};
  llvm::Value* m = m3[0].v;
  m = B.CreateSelect(B.CreateFCmpOLT(m, m3[1].v), m3[1].v, m);
  m = B.CreateSelect(B.CreateFCmpOLT(m, m3[2].v), m3[2].v, m);
  llvm::Value* zero = B.CreateFCmpOEQ(m, e.fconst(0));
  llvm::Value* safe_m = B.CreateSelect(zero, e.fconst(1), m);
  Val s(3);
  for (size_t i = 0; i < 3; ++i) s[i] = Dual{B.CreateFDiv(m3[i].v, safe_m)};
  llvm::Value* t =
      B.CreateFMul(m, B.CreateUnaryIntrinsic(llvm::Intrinsic::sqrt, dot_fused(e, s, s)));
  t = B.CreateSelect(zero, e.fconst(0), t);
  llvm::BasicBlock* tiny_end = B.GetInsertBlock();
  B.CreateBr(done);
  B.SetInsertPoint(done);
  llvm::PHINode* r = B.CreatePHI(B.getFloatTy(), 2);
  r->addIncoming(normal, from);
  r->addIncoming(t, tiny_end);
  return r;
}

void op_dot(LayerEmitter& e, const ir::Op& op) {
  DualOps d(e);
  Val a = load3(e, op, 1), b = load3(e, op, 2);
  e.store(op.args[0], Val{e.wants_derivs(op.args[0]) ? dot3(d, a, b) : Dual{dot_fused(e, a, b)}});
}
void op_cross(LayerEmitter& e, const ir::Op& op) {
  DualOps d(e);
  Val a = load3(e, op, 1), b = load3(e, op, 2);
  e.store(op.args[0], e.wants_derivs(op.args[0]) ? cross3(d, a, b) : cross_fused(e, a, b));
}
void op_length(LayerEmitter& e, const ir::Op& op) {
  DualOps d(e);
  Val a = load3(e, op, 1);
  if (!e.wants_derivs(op.args[0])) {
    e.store(op.args[0], Val{Dual{length_value(e, a)}});
    return;
  }
  e.store(op.args[0], Val{sqrt_dual(e, d, dot3(d, a, a))});
}
// distance(a, b), and distance(a, b, q) from q to the segment a-b as stdosl.h defines it:
// d = b - a; 0-length: |q - a|; else t = dot(q - a, d) / dot(d, d) and |q - (a + clamp(t) d)|.
void op_distance(LayerEmitter& e, const ir::Op& op) {
  DualOps d(e);
  auto& B = e.b();
  bool derivs = e.wants_derivs(op.args[0]);
  auto dot = [&](const Val& x, const Val& y) {
    return derivs ? dot3(d, x, y) : Dual{dot_fused(e, x, y)};
  };
  // Without derivatives, the plain square root of the squared length, as OSL's distance
  // computes it (0 where it underflowed, NaN for a NaN component).
  auto length = [&](const Val& x) {
    return derivs ? sqrt_dual(e, d, dot3(d, x, x))
                  : Dual{e.b().CreateUnaryIntrinsic(llvm::Intrinsic::sqrt, dot_fused(e, x, x))};
  };
  auto minus = [&](const Val& x, const Val& y) {
    Val r(3);
    for (size_t i = 0; i < 3; ++i) r[i] = d.sub(x[i], y[i]);
    return r;
  };
  Val a = load3(e, op, 1), b = load3(e, op, 2);
  if (op.args.size() != 4) {
    e.store(op.args[0], Val{length(minus(a, b))});
    return;
  }
  Val q = load3(e, op, 3), seg = minus(b, a);
  Dual dd = dot(seg, seg);
  Dual t = d.div(dot(minus(q, a), seg), dd);
  t = d.select(B.CreateFCmpOLT(t.v, e.fconst(0)), d.constant(0), t);
  t = d.select(B.CreateFCmpOGT(t.v, e.fconst(1)), d.constant(1), t);
  Val p(3);
  for (size_t i = 0; i < 3; ++i) p[i] = d.add(a[i], d.mul(t, seg[i]));
  Dual far = length(minus(q, p)), near = length(minus(q, a));
  e.store(op.args[0], Val{d.select(B.CreateFCmpOEQ(dd.v, e.fconst(0)), near, far)});
}
void op_normalize(LayerEmitter& e, const ir::Op& op) {
  DualOps d(e);
  Val a = load3(e, op, 1), r;
  bool derivs = e.wants_derivs(op.args[0]);
  float c[3];
  if (!derivs && constant3(a, c)) { // OSL's optimiser folds Imath's normalized(): x / length
    float len = imath_length(c, false);
    for (float x : c) r.push_back(Dual{e.fconst(len == 0.0f ? 0.0f : x / len)});
    e.store(op.args[0], r);
    return;
  }
  if (!derivs) { // OSL: each component times the reciprocal length; the zero vector (+0, so
    // also for -0 components) unless the length is positive (a NaN component gives zeros too)
    auto& B = e.b();
    llvm::Value* len = sqrt_pos(e, dot_fused(e, a, a));
    llvm::Value* pos = B.CreateFCmpOGT(len, e.fconst(0));
    llvm::Value* inv = B.CreateFDiv(e.fconst(1), B.CreateSelect(pos, len, e.fconst(1)));
    for (const Dual& x : a)
      r.push_back(Dual{B.CreateSelect(pos, B.CreateFMul(x.v, inv), e.fconst(0))});
    e.store(op.args[0], r);
    return;
  }
  // With derivatives, OSL's dual arithmetic as its shadeop (C++ compiled with contraction)
  // computes it: a product's partials x * dy + dx * y as fma(x, dy, dx * y); the length
  // sqrt(x*x + y*y + z*z) of those products; the reciprocal length as a dual (1 / len, its
  // partials 1/len * (-(1/len) * partial)); each component times it. A zero length gives the
  // zero vector and zero derivatives. (Dividing by the length instead was 1 ulp off in the
  // value and up to 10 in the derivatives.)
  auto& B = e.b();
  auto fma = [&](llvm::Value* x, llvm::Value* y, llvm::Value* z) {
    return B.CreateIntrinsic(llvm::Intrinsic::fma, {x->getType()}, {x, y, z});
  };
  auto mul = [&](const Dual& x, const Dual& y) {
    auto partial = [&](llvm::Value* xd, llvm::Value* yd) -> llvm::Value* {
      if (!xd && !yd) return nullptr;
      return fma(x.v, yd ? yd : e.fconst(0), B.CreateFMul(xd ? xd : e.fconst(0), y.v));
    };
    return Dual{B.CreateFMul(x.v, y.v), partial(x.dx, y.dx), partial(x.dy, y.dy)};
  };
  Dual sq = d.add(d.add(mul(a[0], a[0]), mul(a[1], a[1])), mul(a[2], a[2]));
  Dual len = sqrt_dual(e, d, sq);
  llvm::Value* pos = B.CreateFCmpOGT(len.v, e.fconst(0));
  llvm::Value* inv = B.CreateFDiv(e.fconst(1), B.CreateSelect(pos, len.v, e.fconst(1)));
  llvm::Value* neg_inv = B.CreateFNeg(inv);
  auto partial = [&](llvm::Value* p) -> llvm::Value* {
    return p ? B.CreateFMul(inv, B.CreateFMul(neg_inv, p)) : nullptr;
  };
  Dual invlen{inv, partial(len.dx), partial(len.dy)};
  for (const Dual& x : a) r.push_back(d.select(pos, mul(x, invlen), Dual{e.fconst(0)}));
  e.store(op.args[0], r);
}

} // namespace

// `x` (its derivatives too when `derivs`) through the 4x4 matrix spilled at `m`, by the rule of
// `kind` (0 point, 1 vector, 2 normal); derivatives transform as vectors (normals as normals),
// a point's through the whole projective map.
Val transform_dual(LayerEmitter& e, llvm::Value* m, const Val& x, int kind, bool derivs) {
  auto apply = [&](std::vector<llvm::Value*> comps, int k) {
    llvm::Value* in = e.spill(comps);
    llvm::Value* out = e.spill(comps);
    e.call("lobe_transform", {out, m, in, e.iconst(k)});
    return e.reload(out, 3);
  };
  Val r = from_values(apply(values(x), kind));
  // Any component's derivatives count (a constructor's constant components have none).
  bool moves = false;
  for (const Dual& c : x) moves = moves || c.dx || c.dy;
  if (kind == 0 && derivs && moves) {
    // A point's derivatives through the whole projective map, as OSL's dual arithmetic
    // computes them: a = p.M's column j (plus its translation), w = p.M's last column, and each
    // component a / w differentiated by the quotient rule, (1/w) (a' - (a/w) w'); 0 where w is
    // 0. (For an affine matrix w is 1 and w' 0; through a perspective one the divide matters:
    // transform("raster", P) with derivatives.)
    auto& B = e.b();
    std::vector<llvm::Value*> M = e.reload(m, 16);
    auto col = [&](int j, llvm::Value* a, llvm::Value* b, llvm::Value* c, bool translate) {
      llvm::Value* s =
          B.CreateFAdd(B.CreateFMul(a, M[size_t(j)]), B.CreateFMul(b, M[size_t(4 + j)]));
      s = B.CreateFAdd(s, B.CreateFMul(c, M[size_t(8 + j)]));
      return translate ? B.CreateFAdd(s, M[size_t(12 + j)]) : s;
    };
    auto part = [&](llvm::Value* v) { return v ? v : e.fconst(0); };
    llvm::Value* w = col(3, x[0].v, x[1].v, x[2].v, true);
    llvm::Value* w0 = B.CreateFCmpOEQ(w, e.fconst(0));
    llvm::Value* winv = B.CreateFDiv(e.fconst(1), B.CreateSelect(w0, e.fconst(1), w));
    llvm::Value* wdx = col(3, part(x[0].dx), part(x[1].dx), part(x[2].dx), false);
    llvm::Value* wdy = col(3, part(x[0].dy), part(x[1].dy), part(x[2].dy), false);
    for (int j = 0; j < 3; ++j) {
      llvm::Value* q = r[size_t(j)].v; // a / w, as lobe_transform computed it (0 where w is 0)
      auto d = [&](llvm::Value* ad, llvm::Value* wd) {
        llvm::Value* v = B.CreateFMul(winv, B.CreateFSub(ad, B.CreateFMul(q, wd)));
        return B.CreateSelect(w0, e.fconst(0), v);
      };
      r[size_t(j)].dx = d(col(j, part(x[0].dx), part(x[1].dx), part(x[2].dx), false), wdx);
      r[size_t(j)].dy = d(col(j, part(x[0].dy), part(x[1].dy), part(x[2].dy), false), wdy);
    }
  } else if (derivs && moves) {
    std::vector<llvm::Value*> dx, dy;
    for (const Dual& c : x) {
      dx.push_back(c.dx ? c.dx : e.fconst(0));
      dy.push_back(c.dy ? c.dy : e.fconst(0));
    }
    auto rx = apply(dx, kind == 0 ? 1 : kind), ry = apply(dy, kind == 0 ? 1 : kind);
    for (size_t i = 0; i < 3; ++i) {
      r[i].dx = rx[i];
      r[i].dy = ry[i];
    }
  }
  return r;
}

namespace {

// transform: (to, p) from common; (from, to, p); (M, p). The last operand's type decides the
// rule (point, vector, normal).
void op_transform(LayerEmitter& e, const ir::Op& op) {
  size_t last = op.args.size() - 1;
  const ir::Symbol& p = e.arg(op, int(last));
  int kind = p.type.base == BaseType::Point ? 0 : (p.type.base == BaseType::Normal ? 2 : 1);
  llvm::Value* m;
  if (e.arg(op, 1).type.base == BaseType::Matrix) {
    m = e.spill(values(e.load_as(op, 1, BaseType::Matrix, false)));
  } else {
    m = e.spill(std::vector<llvm::Value*>(16, e.fconst(0)));
    llvm::Value* from = last == 3 ? e.load(op.args[1])[0].v : e.string_const("common");
    llvm::Value* to = e.load(op.args[last - 1])[0].v;
    e.call("lobe_get_transform", {e.sg(), from, to, m});
  }
  bool derivs = e.wants_derivs(op.args[0]);
  Val x = e.load_as(op, int(last), BaseType::Vector, derivs);
  e.store(op.args[0], transform_dual(e, m, x, kind, derivs));
}

// transformu(["from",] "to", x): x times the ratio of the two length units (names in
// shadeops::unit_scale; the one-name form converts from "common" units, metres in Lobe).
// Constant known names fold to one multiplication; otherwise (names known only at run time,
// or an unknown name, so that -O0 and -O2 agree when specialisation makes a name constant)
// lobe_transformu_scale looks them up per point and reports an unknown name as a run-time
// error (scale 1).
void op_transformu(LayerEmitter& e, const ir::Op& op) {
  bool two = op.args.size() == 4;
  size_t xi = two ? 3 : 2;
  const ir::Symbol* from = two ? &e.arg(op, 1) : nullptr;
  const ir::Symbol& to = e.arg(op, two ? 2 : 1);
  auto known = [](const ir::Symbol* s) {
    return !s || (s->kind == ir::SymKind::Const && shadeops::unit_scale(s->init[0].s) > 0);
  };
  DualOps d(e);
  Val x = e.load_as(op, int(xi), BaseType::Float);
  if (known(from) && known(&to)) {
    double a = from ? shadeops::unit_scale(from->init[0].s) : 1.0;
    double b = shadeops::unit_scale(to.init[0].s);
    e.store(op.args[0], Val{d.mul(x[0], d.constant(float(a / b)))});
    return;
  }
  llvm::Value* f = two ? e.load(op.args[1])[0].v : e.string_const("common");
  llvm::Value* t = e.load(op.args[two ? 2 : 1])[0].v;
  llvm::Value* k =
      e.call("lobe_transformu_scale",
             {e.sg(), f, t, e.string_const(op.loc.file.empty() ? e.shader().name : op.loc.file),
              e.iconst(op.loc.line)});
  e.store(op.args[0], Val{d.mul(x[0], Dual{k})});
}

// transformc [from] to c: through the material's colour system; with derivatives when the
// result has them (OSL differentiates the conversion formulas).
void op_transformc(LayerEmitter& e, const ir::Op& op) {
  size_t last = op.args.size() - 1;
  llvm::Value* from = last == 3 ? e.load(op.args[1])[0].v : e.string_const("rgb");
  llvm::Value* to = e.load(op.args[last - 1])[0].v;
  bool derivs = e.wants_derivs(op.args[0]);
  Val c = e.load_as(op, int(last), BaseType::Color, derivs);
  // The same constant space on both sides: OSL's -O2 folds the call away (the colour as it
  // is); below -O2, and for names known only while shading, it goes through rgb.
  const std::string* cf = last == 3 ? ir::string_value(e.arg(op, 1)) : nullptr;
  const std::string* ct = ir::string_value(e.arg(op, int(last) - 1));
  if (e.group().opt_level >= 2 && cf && ct && *cf == *ct) {
    e.store(op.args[0], c);
    return;
  }
  if (!derivs) {
    llvm::Value* in = e.spill(values(c));
    llvm::Value* out = e.spill({e.fconst(0), e.fconst(0), e.fconst(0)});
    e.call("lobe_transformc", {e.sg(), e.colors_ptr(), from, to, out, in});
    e.store(op.args[0], from_values(e.reload(out, 3)));
    return;
  }
  std::vector<llvm::Value*> planes(9, e.fconst(0));
  for (size_t k = 0; k < 3; ++k) {
    planes[k] = c[k].v;
    if (c[k].dx) planes[3 + k] = c[k].dx;
    if (c[k].dy) planes[6 + k] = c[k].dy;
  }
  llvm::Value* in = e.spill(planes);
  llvm::Value* out = e.spill(std::vector<llvm::Value*>(9, e.fconst(0)));
  e.call("lobe_transformc_d", {e.sg(), e.colors_ptr(), from, to, out, in});
  std::vector<llvm::Value*> r = e.reload(out, 9);
  e.store(op.args[0], Val{Dual{r[0], r[3], r[6]}, Dual{r[1], r[4], r[7]}, Dual{r[2], r[5], r[8]}});
}

// luminance(c): the dot product with the colour system's weights, known when compiling.
void op_luminance(LayerEmitter& e, const ir::Op& op) {
  DualOps d(e);
  Val c = e.load_as(op, 1, BaseType::Color, e.wants_derivs(op.args[0]));
  const shadeops::ColorSystem* cs = e.group().colors;
  const auto& w = (cs ? *cs : shadeops::ColorSystem::rec709()).luminance_weights();
  Val k{d.constant(w[0]), d.constant(w[1]), d.constant(w[2])};
  e.store(op.args[0], Val{dot3(d, c, k)});
}

void op_spectral(LayerEmitter& e, const ir::Op& op) {
  llvm::Value* out = e.spill({e.fconst(0), e.fconst(0), e.fconst(0)});
  e.call(op.opcode == ir::Opcode::Blackbody ? "lobe_blackbody" : "lobe_wavelength_color",
         {e.colors_ptr(), out, e.load_as(op, 1, BaseType::Float, false)[0].v});
  e.store(op.args[0], from_values(e.reload(out, 3)));
}

void op_matrix_fn(LayerEmitter& e, const ir::Op& op) {
  llvm::Value* m = e.spill(values(e.load_as(op, 1, BaseType::Matrix, false)));
  if (op.opcode == ir::Opcode::Determinant) {
    e.store(op.args[0], Val{Dual{e.call("lobe_mat_det", {m})}});
    return;
  }
  llvm::Value* out = e.spill(std::vector<llvm::Value*>(16, e.fconst(0)));
  e.call("lobe_mat_transpose", {out, m});
  e.store(op.args[0], from_values(e.reload(out, 16)));
}

// getmatrix ok M "from" "to" (M is written too).
void op_getmatrix(LayerEmitter& e, const ir::Op& op) {
  llvm::Value* out = e.spill(std::vector<llvm::Value*>(16, e.fconst(0)));
  llvm::Value* ok =
      e.call("lobe_get_matrix", {e.sg(), e.load(op.args[2])[0].v, e.load(op.args[3])[0].v, out});
  e.store(op.args[1], from_values(e.reload(out, 16)));
  e.store(op.args[0], Val{Dual{ok}});
}

// Dx, Dy, Dz, filterwidth, area, calculatenormal: read derivatives, write plain values.
void op_deriv(LayerEmitter& e, const ir::Op& op) {
  const ir::Opcode o = op.opcode;
  BaseType t = e.arg(op, 1).type.base;
  Val x = e.load(op.args[1]);
  auto dxv = [&](const Dual& c) { return c.dx ? c.dx : e.fconst(0); };
  auto dyv = [&](const Dual& c) { return c.dy ? c.dy : e.fconst(0); };
  DualOps d(e);
  Val r;
  if (o == ir::Opcode::Dx || o == ir::Opcode::Dy || o == ir::Opcode::Dz) {
    for (const Dual& c : x)
      r.push_back(Dual{o == ir::Opcode::Dx ? dxv(c) : o == ir::Opcode::Dy ? dyv(c) : e.fconst(0)});
  } else if (o == ir::Opcode::FilterWidth) { // sqrt(dx dx + dy dy), contracted as OSL's
    for (const Dual& c : x)
      r.push_back(Dual{sqrt_pos(e, fmuladd(e, dxv(c), dxv(c), e.b().CreateFMul(dyv(c), dyv(c))))});
  } else { // OSL's shadeops: Imath's cross and length, contracted (dot_fused, cross_fused)
    Val px, py;
    for (const Dual& c : x) {
      px.push_back(Dual{dxv(c)});
      py.push_back(Dual{dyv(c)});
    }
    Val n = cross_fused(e, px, py);
    if (o == ir::Opcode::Area) {
      r = Val{Dual{sqrt_pos(e, dot_fused(e, n, n))}};
    } else {
      llvm::Value* flip = e.b().CreateLoad(
          e.i32(), e.b().CreateConstInBoundsGEP1_64(e.b().getInt8Ty(), e.sg(),
                                                    offsetof(ShaderGlobals, flip_handedness)));
      llvm::Value* f = e.b().CreateICmpNE(flip, e.iconst(0));
      for (const Dual& c : n) r.push_back(d.select(f, d.neg(c), c));
    }
  }
  for (Dual& c : r) c.dx = c.dy = nullptr;
  e.store(op.args[0],
          e.convert(r,
                    t == BaseType::Float || t == BaseType::Int ? BaseType::Float : BaseType::Vector,
                    e.arg(op, 0).type.base));
}

const OpEntry kGeometryOps[] = {
    {ir::Opcode::Dot, op_dot},
    {ir::Opcode::Cross, op_cross},
    {ir::Opcode::Length, op_length},
    {ir::Opcode::Distance, op_distance},
    {ir::Opcode::Normalize, op_normalize},
    {ir::Opcode::Transform, op_transform},
    {ir::Opcode::TransformU, op_transformu},
    {ir::Opcode::TransformC, op_transformc},
    {ir::Opcode::Luminance, op_luminance},
    {ir::Opcode::Blackbody, op_spectral},
    {ir::Opcode::WavelengthColor, op_spectral},
    {ir::Opcode::Determinant, op_matrix_fn},
    {ir::Opcode::Transpose, op_matrix_fn},
    {ir::Opcode::GetMatrix, op_getmatrix},
    {ir::Opcode::Dx, op_deriv},
    {ir::Opcode::Dy, op_deriv},
    {ir::Opcode::Dz, op_deriv},
    {ir::Opcode::FilterWidth, op_deriv},
    {ir::Opcode::Area, op_deriv},
    {ir::Opcode::CalculateNormal, op_deriv},
};

} // namespace

std::span<const OpEntry> geometry_ops() { return kGeometryOps; }

} // namespace lobe::codegen

// Component, matrix-element and array access (with clamped, reported out-of-range indices),
// array copies and lengths, and `construct` (triples and matrices, optionally from a named
// space).
#include "duals.h"
#include "op_tables.h"

#include <llvm/IR/Constants.h>

namespace lobe::codegen {
namespace {

using ir::BaseType;

int array_length(const ir::Symbol& s) {
  if (s.type.arraylen > 0) return s.type.arraylen;
  return std::max<int>(1, int(s.init.size()) / s.type.components());
}

// v[idx] for a run-time index among n components, as a select chain.
Dual pick(LayerEmitter& e, const Val& v, llvm::Value* idx) {
  if (auto* c = llvm::dyn_cast<llvm::ConstantInt>(idx)) return v[size_t(c->getSExtValue())];
  DualOps d(e);
  Dual r = v[0];
  for (size_t i = 1; i < v.size(); ++i)
    r = d.select(e.b().CreateICmpEQ(idx, e.iconst(int(i))), v[i], r);
  return r;
}

// Writes x into component idx of v (run-time index: every component selects).
void place(LayerEmitter& e, Val& v, llvm::Value* idx, const Dual& x) {
  if (auto* c = llvm::dyn_cast<llvm::ConstantInt>(idx)) {
    v[size_t(c->getSExtValue())] = x;
    return;
  }
  DualOps d(e);
  for (size_t i = 0; i < v.size(); ++i)
    v[i] = d.select(e.b().CreateICmpEQ(idx, e.iconst(int(i))), x, v[i]);
}

void op_compref(LayerEmitter& e, const ir::Op& op) {
  llvm::Value* i = e.checked_index(op, 2, 3);
  Val t = e.load(op.args[1], nullptr, e.wants_derivs(op.args[0]));
  e.store(op.args[0], e.convert(Val{pick(e, t, i)}, BaseType::Float, e.arg(op, 0).type.base));
}

void op_compassign(LayerEmitter& e, const ir::Op& op) {
  llvm::Value* i = e.checked_index(op, 1, 3);
  Val t = e.load(op.args[0]);
  place(e, t, i, e.load_as(op, 2, BaseType::Float)[0]);
  e.store(op.args[0], t);
}

void op_mxcompref(LayerEmitter& e, const ir::Op& op) {
  llvm::Value* r = e.checked_index(op, 2, 4);
  llvm::Value* c = e.checked_index(op, 3, 4);
  llvm::Value* idx = e.b().CreateAdd(e.b().CreateMul(r, e.iconst(4)), c);
  Val m = e.load(op.args[1], nullptr, false);
  e.store(op.args[0], e.convert(Val{pick(e, m, idx)}, BaseType::Float, e.arg(op, 0).type.base));
}

void op_mxcompassign(LayerEmitter& e, const ir::Op& op) {
  llvm::Value* r = e.checked_index(op, 1, 4);
  llvm::Value* c = e.checked_index(op, 2, 4);
  llvm::Value* idx = e.b().CreateAdd(e.b().CreateMul(r, e.iconst(4)), c);
  Val m = e.load(op.args[0], nullptr, false);
  place(e, m, idx, e.load_as(op, 3, BaseType::Float, false)[0]);
  e.store(op.args[0], m);
}

void op_aref(LayerEmitter& e, const ir::Op& op) {
  const ir::Symbol& a = e.arg(op, 1);
  llvm::Value* i = e.checked_index(op, 2, array_length(a));
  Val v = e.load(op.args[1], i, e.wants_derivs(op.args[0]));
  e.store(op.args[0], e.convert(v, a.type.base, e.arg(op, 0).type.base));
}

void op_aassign(LayerEmitter& e, const ir::Op& op) {
  const ir::Symbol& a = e.arg(op, 0);
  llvm::Value* i = e.checked_index(op, 1, array_length(a));
  e.store(op.args[0], e.load_as(op, 2, a.type.base, a.derivs), i);
}

void op_arraycopy(LayerEmitter& e, const ir::Op& op) {
  int n = std::min(array_length(e.arg(op, 0)), array_length(e.arg(op, 1)));
  for (int k = 0; k < n; ++k) e.store(op.args[0], e.load(op.args[1], e.iconst(k)), e.iconst(k));
}

void op_arraylength(LayerEmitter& e, const ir::Op& op) {
  e.store(op.args[0], Val{Dual{e.iconst(array_length(e.arg(op, 1)))}});
}

std::vector<llvm::Value*> values(const Val& v) {
  std::vector<llvm::Value*> out;
  for (const Dual& d : v) out.push_back(d.v);
  return out;
}

void construct_matrix(LayerEmitter& e, const ir::Op& op, size_t first) {
  Val m(16, Dual{e.fconst(0)});
  // matrix("from", "to"): the transform from space `from` to space `to`. Both names are
  // strings, so op_construct's "spaced" test set first = 2; decide on the argument types.
  if (op.args.size() == 3 && e.arg(op, 1).type.base == BaseType::String &&
      e.arg(op, 2).type.base == BaseType::String) {
    llvm::Value* out = e.spill(values(m));
    e.call("lobe_get_matrix", {e.sg(), e.load(op.args[1])[0].v, e.load(op.args[2])[0].v, out});
    m.clear();
    for (llvm::Value* v : e.reload(out, 16)) m.push_back(Dual{v});
    e.store(op.args[0], m);
    return;
  }
  size_t n = op.args.size() - first;
  if (n == 1)
    m = e.load_as(op, int(first), BaseType::Matrix, false);
  else
    for (size_t k = 0; k < 16 && k < n; ++k)
      m[k] = e.load_as(op, int(first + k), BaseType::Float, false)[0];
  if (first == 2) { // values given in a named space: (space -> common) * M, as OSL
    llvm::Value* s = e.spill(values(m));
    llvm::Value* out = e.spill(values(m));
    e.call("lobe_space_matrix", {e.sg(), e.load(op.args[1])[0].v, out});
    e.call("lobe_mat_mul", {out, out, s});
    m.clear();
    for (llvm::Value* v : e.reload(out, 16)) m.push_back(Dual{v});
  }
  e.store(op.args[0], m);
}

void op_construct(LayerEmitter& e, const ir::Op& op) {
  const ir::Symbol& dst = e.arg(op, 0);
  bool spaced = op.args.size() > 2 && e.arg(op, 1).type.base == BaseType::String;
  size_t first = spaced ? 2 : 1;
  if (dst.type.base == BaseType::Matrix) return construct_matrix(e, op, first);
  Val t;
  if (op.args.size() - first == 1)
    t = e.load_as(op, int(first), dst.type.base);
  else
    for (size_t k = 0; k < 3; ++k) t.push_back(e.load_as(op, int(first + k), BaseType::Float)[0]);
  if (spaced) {
    llvm::Value* space = e.load(op.args[1])[0].v;
    if (dst.type.base == BaseType::Color) { // (colour conversions drop derivatives, as OSL's)
      llvm::Value* in = e.spill(values(t));
      llvm::Value* out = e.spill(values(t));
      e.call("lobe_color_from", {e.sg(), e.colors_ptr(), space, out, in});
      std::vector<llvm::Value*> r = e.reload(out, 3);
      t = Val{Dual{r[0]}, Dual{r[1]}, Dual{r[2]}};
    } else { // space -> common, derivatives with the value (OSL: a transform op)
      llvm::Value* m = e.spill(std::vector<llvm::Value*>(16, e.fconst(0)));
      e.call("lobe_get_transform", {e.sg(), space, e.string_const("common"), m});
      int kind = dst.type.base == BaseType::Point ? 0 : (dst.type.base == BaseType::Vector ? 1 : 2);
      t = transform_dual(e, m, t, kind, e.wants_derivs(op.args[0]));
    }
  }
  e.store(op.args[0], t);
}

const OpEntry kAccessOps[] = {
    {ir::Opcode::CompRef, op_compref},     {ir::Opcode::CompAssign, op_compassign},
    {ir::Opcode::MxCompRef, op_mxcompref}, {ir::Opcode::MxCompAssign, op_mxcompassign},
    {ir::Opcode::ARef, op_aref},           {ir::Opcode::AAssign, op_aassign},
    {ir::Opcode::ArrayCopy, op_arraycopy}, {ir::Opcode::ArrayLength, op_arraylength},
    {ir::Opcode::Construct, op_construct},
};

} // namespace

std::span<const OpEntry> access_ops() { return kAccessOps; }

} // namespace lobe::codegen

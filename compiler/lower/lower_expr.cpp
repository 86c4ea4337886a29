// Lowering of expressions: rvalues into symbols (with an optional destination hint so that
// `x = a + b` is one `add x a b`), lvalues into LRefs, loads and stores through elements and
// components, conversions, short-circuit logic and `?:` as jumps.
#include "lower/lowerer.h"

#include "ir/edit.h"

#include <algorithm>

namespace lobe::lower {

using ir::SymKind;
using K = ast::ExprKind;

ir::Opcode binop_opcode(ast::BinaryOp op) {
  using B = ast::BinaryOp;
  switch (op) {
  case B::Add:
    return ir::Opcode::Add;
  case B::Sub:
    return ir::Opcode::Sub;
  case B::Mul:
    return ir::Opcode::Mul;
  case B::Div:
    return ir::Opcode::Div;
  case B::Mod:
    return ir::Opcode::Mod;
  case B::Shl:
    return ir::Opcode::Shl;
  case B::Shr:
    return ir::Opcode::Shr;
  case B::BitAnd:
    return ir::Opcode::BitAnd;
  case B::BitOr:
    return ir::Opcode::BitOr;
  case B::BitXor:
    return ir::Opcode::Xor;
  case B::Lt:
    return ir::Opcode::Lt;
  case B::Le:
    return ir::Opcode::Le;
  case B::Gt:
    return ir::Opcode::Gt;
  case B::Ge:
    return ir::Opcode::Ge;
  case B::Eq:
    return ir::Opcode::Eq;
  case B::Ne:
    return ir::Opcode::Neq;
  default:
    return ir::Opcode::Nop;
  }
}

int Lowerer::pick(int hint, const ir::Type& t) {
  if (hint >= 0 && sh_.symbols[hint].type == t) return hint;
  return temp(t);
}

int Lowerer::convert(int sym, const ir::Type& to, const ast::Node* where) {
  if (sh_.symbols[sym].type == to) return sym;
  int t = temp(to);
  emit(to.is_array() ? ir::Opcode::ArrayCopy : ir::Opcode::Assign, {t, sym}, 1, where);
  return t;
}

int Lowerer::int_add(int a, int b, const ast::Node* where) {
  const ir::Symbol& x = sh_.symbols[size_t(a)];
  const ir::Symbol& y = sh_.symbols[size_t(b)];
  if (x.kind == SymKind::Const && x.init.size() == 1 && x.init[0].i == 0) return b;
  if (y.kind == SymKind::Const && y.init.size() == 1 && y.init[0].i == 0) return a;
  if (x.kind == SymKind::Const && y.kind == SymKind::Const && x.init.size() == 1 &&
      y.init.size() == 1)
    return ir::intern_int(sh_, x.init[0].i + y.init[0].i);
  int t = temp(ir::Type{ir::BaseType::Int});
  emit(ir::Opcode::Add, {t, a, b}, 1, where);
  return t;
}

int Lowerer::int_mul(int a, int k, const ast::Node* where) {
  if (k == 1) return a;
  const ir::Symbol& x = sh_.symbols[size_t(a)];
  if (x.kind == SymKind::Const && x.init.size() == 1) return ir::intern_int(sh_, x.init[0].i * k);
  int t = temp(ir::Type{ir::BaseType::Int});
  emit(ir::Opcode::Mul, {t, a, ir::intern_int(sh_, k)}, 1, where);
  return t;
}

int Lowerer::slice_elem(const LRef& r, int k, const ast::Node* where) {
  return int_add(r.index, ir::intern_int(sh_, k), where);
}

// Indexing an array of `len` elements (its leaves `refs`) by `idx`. A leaf holding more than
// `len` elements (array fields of an array of structs) gets a slice of len-th of its elements.
void Lowerer::index_refs(std::vector<LRef>& refs, int len, int idx, const ast::Node* where) {
  for (LRef& r : refs) {
    if (!r.whole() && r.slice == 0) {
      r = LRef{load(r, where)}; // an element of a temporary copy (read-only use)
    }
    int total = r.slice > 0 ? r.slice : sh_.symbols[size_t(r.sym)].type.arraylen;
    int step = len > 0 && total > len ? total / len : 1;
    int start = int_mul(idx, step, where);
    if (r.slice > 0) start = int_add(r.index, start, where);
    r = LRef{r.sym, start, -1, -1, step > 1 ? step : 0};
  }
}

int Lowerer::load(const LRef& r, const ast::Node* where, int hint) {
  if (r.whole()) return r.sym;
  int base = r.sym;
  ir::Type et = sh_.symbols[size_t(base)].type;
  et.arraylen = 0;
  if (r.slice > 0) { // copy the run of elements into an array temporary
    ir::Type at = et;
    at.arraylen = r.slice;
    int a = temp(at);
    int x = temp(et);
    for (int k = 0; k < r.slice; ++k) {
      emit(ir::Opcode::ARef, {x, base, slice_elem(r, k, where)}, 1, where);
      emit(ir::Opcode::AAssign, {a, ir::intern_int(sh_, k), x}, 1, where);
    }
    return a;
  }
  if (r.index >= 0) {
    int t = r.comp < 0 ? pick(hint, et) : temp(et);
    emit(ir::Opcode::ARef, {t, base, r.index}, 1, where);
    base = t;
  }
  if (r.comp < 0) return base;
  int f = pick(hint, ir::Type{ir::BaseType::Float});
  if (r.comp2 >= 0)
    emit(ir::Opcode::MxCompRef, {f, base, r.comp, r.comp2}, 1, where);
  else
    emit(ir::Opcode::CompRef, {f, base, r.comp}, 1, where);
  return f;
}

void Lowerer::store(const LRef& r, int v, const ast::Node* where) {
  if (r.whole()) {
    if (v == r.sym) return;
    emit(sh_.symbols[size_t(r.sym)].type.is_array() ? ir::Opcode::ArrayCopy : ir::Opcode::Assign,
         {r.sym, v}, 1, where);
    return;
  }
  int base = r.sym;
  ir::Type et = sh_.symbols[size_t(base)].type;
  et.arraylen = 0;
  if (r.slice > 0) { // element by element into the run
    int x = temp(et);
    int n = std::min(r.slice, std::max(0, sh_.symbols[size_t(v)].type.arraylen));
    for (int k = 0; k < n; ++k) {
      emit(ir::Opcode::ARef, {x, v, ir::intern_int(sh_, k)}, 1, where);
      emit(ir::Opcode::AAssign, {r.sym, slice_elem(r, k, where), x}, 1, where);
    }
    return;
  }
  if (r.index >= 0 && r.comp < 0) {
    emit(ir::Opcode::AAssign, {r.sym, r.index, v}, 1, where);
    return;
  }
  if (r.index >= 0) {
    base = temp(et);
    emit(ir::Opcode::ARef, {base, r.sym, r.index}, 1, where);
  }
  if (r.comp2 >= 0)
    emit(ir::Opcode::MxCompAssign, {base, r.comp, r.comp2, v}, 1, where);
  else
    emit(ir::Opcode::CompAssign, {base, r.comp, v}, 1, where);
  if (r.index >= 0) emit(ir::Opcode::AAssign, {r.sym, r.index, base}, 1, where);
}

std::vector<LRef> Lowerer::lvalue(const ast::Expr* e) {
  switch (e->kind) {
  case K::Ident: {
    auto* id = static_cast<const ast::IdentExpr*>(e);
    if (id->decl && id->decl->storage == ast::Storage::Global) return {LRef{global(id->decl)}};
    auto it = vars_.find(id->decl);
    if (it == vars_.end()) {
      error(e, diag::DiagId::err_lower_internal, {"unbound variable '" + id->name + "'"});
      return {LRef{temp(irtype(e->type, e))}};
    }
    std::vector<LRef> out;
    for (int s : it->second) out.push_back(LRef{s});
    return out;
  }
  case K::Index: {
    auto* ix = static_cast<const ast::IndexExpr*>(e);
    std::vector<LRef> base = lvalue(ix->base.get());
    int idx = rvalue(ix->index.get());
    if (ix->index_kind == ast::IndexKind::ArrayElement) {
      index_refs(base, ix->base->type.arraylen, idx, e);
      return base;
    }
    int idx2 = ix->index_kind == ast::IndexKind::MatrixElement ? rvalue(ix->index2.get()) : -1;
    for (LRef& r : base) { // a component or matrix element
      if (r.comp >= 0) r = LRef{load(r, e)};
      r.comp = idx;
      r.comp2 = idx2;
    }
    return base;
  }
  case K::Member: {
    auto* m = static_cast<const ast::MemberExpr*>(e);
    std::vector<LRef> base = lvalue(m->base.get());
    if (m->component >= 0) {
      LRef r = base[0];
      if (r.comp >= 0) r = LRef{load(r, e)};
      r.comp = ir::intern_int(sh_, m->component);
      return {r};
    }
    const ast::StructDecl* sd = m->base->type.strct;
    size_t first = 0;
    for (int f = 0; f < m->field; ++f) first += leaves(sd->fields[size_t(f)]->type, e).size();
    size_t n = leaves(sd->fields[size_t(m->field)]->type, e).size();
    return std::vector<LRef>(base.begin() + long(first), base.begin() + long(first + n));
  }
  default:
    if (e->type.base == ast::BaseType::Struct) {
      std::vector<LRef> out;
      for (int s : rvalue_flat(e)) out.push_back(LRef{s});
      return out;
    }
    return {LRef{rvalue(e)}};
  }
}

// The leaf values of a struct built from parts (constructor arguments or an init list).
std::vector<int> Lowerer::struct_parts(const ast::Expr* e, const ast::Type& t) {
  std::vector<const ast::Expr*> parts;
  if (e->kind == K::InitList)
    for (const auto& x : static_cast<const ast::InitListExpr*>(e)->elems) parts.push_back(x.get());
  else
    for (const auto& x : static_cast<const ast::CallExpr*>(e)->args) parts.push_back(x.get());
  std::vector<int> out;
  const auto& fields = t.strct->fields;
  for (size_t i = 0; i < fields.size() && i < parts.size(); ++i) {
    const ast::Type& ft = fields[i]->type;
    if (ft.base == ast::BaseType::Struct && ft.is_array() && parts[i]->kind == K::InitList) {
      // An array of structs from `{ elem, ... }`: one array temporary per leaf (the
      // struct-of-arrays layout), zeroed when the list is short, filled element by element.
      std::vector<LRef> dst;
      auto* l = static_cast<const ast::InitListExpr*>(parts[i]);
      for (const Leaf& leaf : leaves(ft, parts[i])) {
        ir::Type lt = irtype(leaf.type, parts[i]);
        int tmp = temp(lt);
        if (int(l->elems.size()) < ft.arraylen && lt.base != ir::BaseType::Closure)
          store(LRef{tmp},
                ir::intern_const(
                    sh_, lt, std::vector<ir::ConstValue>(size_t(lt.arraylen * lt.components()))),
                parts[i]);
        dst.push_back(LRef{tmp});
        out.push_back(tmp);
      }
      store_init(dst, ft, parts[i]);
    } else if (ft.base == ast::BaseType::Struct) {
      auto sub = parts[i]->kind == K::InitList ? struct_parts(parts[i], ft) : rvalue_flat(parts[i]);
      out.insert(out.end(), sub.begin(), sub.end());
    } else {
      out.push_back(rvalue(parts[i]));
    }
  }
  return out;
}

std::vector<int> Lowerer::rvalue_flat(const ast::Expr* e) {
  if (e->kind == K::InitList) return struct_parts(e, e->type);
  if (e->kind == K::Call) {
    auto* c = static_cast<const ast::CallExpr*>(e);
    if (c->callee.kind == ast::CalleeKind::StructCtor) return struct_parts(e, e->type);
    if (c->callee.kind == ast::CalleeKind::User) {
      std::vector<const ast::Expr*> args;
      for (const auto& a : c->args) args.push_back(a.get());
      return call_user(c->callee.function, args, e);
    }
  }
  if (e->kind == K::Binary && static_cast<const ast::BinaryExpr*>(e)->overload) {
    auto* b = static_cast<const ast::BinaryExpr*>(e);
    return call_user(b->overload, {b->lhs.get(), b->rhs.get()}, e);
  }
  if (e->kind == K::Unary && static_cast<const ast::UnaryExpr*>(e)->overload) {
    auto* u = static_cast<const ast::UnaryExpr*>(e);
    return call_user(u->overload, {u->operand.get()}, e);
  }
  if (e->kind == K::Assign) {
    auto* a = static_cast<const ast::AssignExpr*>(e);
    std::vector<int> v = a->overload ? call_user(a->overload, {a->lhs.get(), a->rhs.get()}, e)
                                     : rvalue_flat(a->rhs.get());
    std::vector<LRef> dst = lvalue(a->lhs.get());
    // A value that is another leaf of the target (`a = vec2(a.y, a.x)`) is read before the
    // stores overwrite it: copy the values first.
    bool alias = false;
    for (size_t i = 0; i < v.size(); ++i)
      for (size_t j = 0; j < dst.size() && v[i] >= 0; ++j)
        alias |= i != j && dst[j].whole() && v[i] == dst[j].sym;
    for (size_t i = 0; alias && i < v.size(); ++i) {
      if (v[i] < 0) continue;
      int t = temp(sh_.symbols[size_t(v[i])].type);
      emit(ir::Opcode::Assign, {t, v[i]}, 1, e);
      v[i] = t;
    }
    for (size_t i = 0; i < dst.size() && i < v.size(); ++i) store(dst[i], v[i], e);
  }
  if (e->kind == K::Ternary) return ternary_flat(static_cast<const ast::TernaryExpr*>(e));
  if (e->kind == K::Comma) {
    auto* c = static_cast<const ast::CommaExpr*>(e);
    for (size_t i = 0; i + 1 < c->exprs.size(); ++i) {
      if (c->exprs[i]->type.base == ast::BaseType::Struct)
        rvalue_flat(c->exprs[i].get());
      else
        rvalue(c->exprs[i].get());
    }
    return rvalue_flat(c->exprs.back().get());
  }
  const ast::Expr* src =
      e->kind == K::Assign ? static_cast<const ast::AssignExpr*>(e)->lhs.get() : e;
  std::vector<int> out;
  for (const LRef& r : lvalue(src)) out.push_back(load(r, e));
  return out;
}

int Lowerer::logical(const ast::BinaryExpr* b) {
  bool is_and = b->op == ast::BinaryOp::LogicalAnd;
  int res = temp(ir::Type{ir::BaseType::Int});
  int zero = ir::intern_int(sh_, 0);
  int a = rvalue(b->lhs.get());
  emit(ir::Opcode::Neq, {res, a, zero}, 1, b);
  int j = emit(ir::Opcode::Cbr, {res}, 0, b, {-1, -1});
  sh_.ops[size_t(j)].jumps[is_and ? 0 : 1] = here();
  int c = rvalue(b->rhs.get());
  emit(ir::Opcode::Neq, {res, c, zero}, 1, b);
  sh_.ops[size_t(j)].jumps[is_and ? 1 : 0] = here();
  return res;
}

int Lowerer::ternary(const ast::TernaryExpr* t, int hint) {
  int res = pick(hint, irtype(t->type, t));
  int c = rvalue(t->cond.get());
  int j = emit(ir::Opcode::Cbr, {c}, 0, t, {-1, -1});
  sh_.ops[size_t(j)].jumps[0] = here();
  store(LRef{res}, rvalue(t->then_expr.get(), res), t);
  int skip = emit(ir::Opcode::Br, {}, 0, t, {-1});
  sh_.ops[size_t(j)].jumps[1] = here();
  store(LRef{res}, rvalue(t->else_expr.get(), res), t);
  sh_.ops[size_t(skip)].jumps[0] = here();
  return res;
}

// A struct-valued `c ? a : b`: one temporary per leaf, filled on either branch.
std::vector<int> Lowerer::ternary_flat(const ast::TernaryExpr* t) {
  std::vector<int> res;
  for (const Leaf& l : leaves(t->type, t)) res.push_back(temp(irtype(l.type, t)));
  int c = rvalue(t->cond.get());
  int j = emit(ir::Opcode::Cbr, {c}, 0, t, {-1, -1});
  sh_.ops[size_t(j)].jumps[0] = here();
  std::vector<int> a = rvalue_flat(t->then_expr.get());
  for (size_t i = 0; i < res.size() && i < a.size(); ++i) store(LRef{res[i]}, a[i], t);
  int skip = emit(ir::Opcode::Br, {}, 0, t, {-1});
  sh_.ops[size_t(j)].jumps[1] = here();
  std::vector<int> b = rvalue_flat(t->else_expr.get());
  for (size_t i = 0; i < res.size() && i < b.size(); ++i) store(LRef{res[i]}, b[i], t);
  sh_.ops[size_t(skip)].jumps[0] = here();
  return res;
}

int Lowerer::assign(const ast::AssignExpr* a, int hint) {
  if (a->lhs->type.base == ast::BaseType::Struct) {
    std::vector<int> v = rvalue_flat(a);
    return v.empty() ? -1 : v[0];
  }
  LRef dst = lvalue(a->lhs.get())[0];
  ir::Type lt = irtype(a->lhs->type, a);
  bool direct = dst.whole() && a->rhs->kind != K::InitList;
  if (!a->compound) {
    int v = rvalue(a->rhs.get(), direct ? dst.sym : -1);
    size_t first = sh_.ops.size();
    store(dst, v, a);
    // `x = f(...)` of a user function: oslc returns into x from inside f's body, so the store
    // counts as the body's (ir::Op::in_function).
    const auto* call =
        a->rhs->kind == K::Call ? static_cast<const ast::CallExpr*>(a->rhs.get()) : nullptr;
    if (direct && call && call->callee.kind == ast::CalleeKind::User && call->callee.function &&
        !call->callee.function->osl_builtin)
      for (size_t k = first; k < sh_.ops.size(); ++k) sh_.ops[k].in_function = true;
    return dst.whole() ? dst.sym : v;
  }
  if (a->overload) { // `x op= s` with a struct s: x = __operator__op__(x, s)
    int v = call_user(a->overload, {a->lhs.get(), a->rhs.get()}, a).at(0);
    store(dst, v, a);
    return dst.whole() ? dst.sym : v;
  }
  int cur = load(dst, a);
  int rhs = rvalue(a->rhs.get());
  int res = dst.whole() ? dst.sym : temp(lt);
  if (a->lhs->type.is_int() && a->rhs->type.is_float()) {
    // `i op= f`: i = int(float(i) op f), as oslc computes it (sema warned).
    int fcur = temp(ir::Type{ir::BaseType::Float});
    emit(ir::Opcode::Assign, {fcur, cur}, 1, a);
    int fres = temp(ir::Type{ir::BaseType::Float});
    emit(binop_opcode(a->op), {fres, fcur, rhs}, 1, a);
    emit(ir::Opcode::Assign, {res, fres}, 1, a);
    store(dst, res, a);
    return res;
  }
  emit(binop_opcode(a->op), {res, cur, rhs}, 1, a);
  store(dst, res, a);
  return res;
}

int Lowerer::incdec(const ast::IncDecExpr* e) {
  LRef dst = lvalue(e->operand.get())[0];
  ir::Type t = irtype(e->operand->type, e);
  int cur = load(dst, e);
  int old = -1;
  if (!e->prefix) {
    old = temp(t);
    emit(ir::Opcode::Assign, {old, cur}, 1, e);
  }
  // 1 for every component: a float for a triple (broadcast by the add), all sixteen elements of
  // a matrix (OSL 1.13.12: `matrix m = matrix(2); m++;` is 3 on the diagonal and 1 elsewhere).
  int one = t.base == ir::BaseType::Int ? ir::intern_int(sh_, 1)
            : t.base == ir::BaseType::Matrix
                ? ir::intern_const(sh_, t,
                                   std::vector<ir::ConstValue>(16, ir::ConstValue::of_float(1.0f)))
                : ir::intern_float(sh_, 1.0f);
  int res = dst.whole() ? dst.sym : temp(t);
  emit(e->increment ? ir::Opcode::Add : ir::Opcode::Sub, {res, cur, one}, 1, e);
  store(dst, res, e);
  return e->prefix ? res : old;
}

int Lowerer::construct(const ast::ConstructExpr* c, int hint) {
  ir::Type t = irtype(c->type, c);
  std::vector<int> args;
  for (const auto& a : c->args) args.push_back(rvalue(a.get()));
  int dst = pick(hint, t);
  if (args.size() == 1 && !c->has_space) {
    emit(ir::Opcode::Assign, {dst, args[0]}, 1, c);
    return dst;
  }
  args.insert(args.begin(), dst);
  emit(ir::Opcode::Construct, args, 1, c);
  return dst;
}

// Casts, constructors and arithmetic whose operands are all constants become one constant
// (`color(1)`, `-2`, `float(1) / 3`): no temporaries holding converted literals.
int Lowerer::folded(const ast::Expr* e) {
  if (e->kind != K::Cast && e->kind != K::Construct && e->kind != K::Unary && e->kind != K::Binary)
    return -1;
  if (e->type.is_array() || e->type.base == ast::BaseType::Struct ||
      e->type.base == ast::BaseType::Closure || e->type.base == ast::BaseType::Void)
    return -1;
  ir::Type t = irtype(e->type, e);
  std::vector<ir::ConstValue> v;
  if (!const_values(e, t, v) || v.size() != size_t(t.components())) return -1;
  return ir::intern_const(sh_, t, v);
}

int Lowerer::rvalue(const ast::Expr* e, int hint) {
  if (int c = folded(e); c >= 0) return c;
  const ast::Node* saved = where_;
  where_ = e;
  int r = -1;
  switch (e->kind) {
  case K::IntLit:
    r = ir::intern_int(sh_, static_cast<const ast::IntLit*>(e)->value);
    break;
  case K::FloatLit:
    r = ir::intern_float(sh_, static_cast<const ast::FloatLit*>(e)->value);
    break;
  case K::StringLit:
    r = ir::intern_string(sh_, static_cast<const ast::StringLit*>(e)->value);
    break;
  case K::Ident:
  case K::Index:
  case K::Member:
    r = load(lvalue(e)[0], e, hint);
    break;
  case K::Unary: {
    auto* u = static_cast<const ast::UnaryExpr*>(e);
    if (u->overload) {
      r = call_user(u->overload, {u->operand.get()}, e).at(0);
      break;
    }
    int x = rvalue(u->operand.get());
    if (u->op == ast::UnaryOp::Plus) {
      r = x;
      break;
    }
    r = pick(hint, irtype(e->type, e));
    emit(u->op == ast::UnaryOp::Neg   ? ir::Opcode::Neg
         : u->op == ast::UnaryOp::Not ? ir::Opcode::Not
                                      : ir::Opcode::Compl,
         {r, x}, 1, e);
    break;
  }
  case K::Binary: {
    auto* b = static_cast<const ast::BinaryExpr*>(e);
    if (b->overload) {
      r = call_user(b->overload, {b->lhs.get(), b->rhs.get()}, e).at(0);
      break;
    }
    if (b->op == ast::BinaryOp::LogicalAnd || b->op == ast::BinaryOp::LogicalOr) {
      r = logical(b);
      break;
    }
    int x = rvalue(b->lhs.get());
    int y = rvalue(b->rhs.get());
    r = pick(hint, irtype(e->type, e));
    emit(binop_opcode(b->op), {r, x, y}, 1, e);
    break;
  }
  case K::Assign:
    r = assign(static_cast<const ast::AssignExpr*>(e), hint);
    break;
  case K::IncDec:
    r = incdec(static_cast<const ast::IncDecExpr*>(e));
    break;
  case K::Ternary:
    r = ternary(static_cast<const ast::TernaryExpr*>(e), hint);
    break;
  case K::Comma: {
    auto* c = static_cast<const ast::CommaExpr*>(e);
    for (size_t i = 0; i < c->exprs.size(); ++i)
      r = rvalue(c->exprs[i].get(), i + 1 == c->exprs.size() ? hint : -1);
    break;
  }
  case K::Call:
    r = call(static_cast<const ast::CallExpr*>(e), hint);
    break;
  case K::Construct:
    r = construct(static_cast<const ast::ConstructExpr*>(e), hint);
    break;
  case K::Cast: {
    auto* c = static_cast<const ast::CastExpr*>(e);
    int x = rvalue(c->operand.get());
    ir::Type t = irtype(c->type, e);
    if (sh_.symbols[x].type == t) {
      r = x;
      break;
    }
    r = pick(hint, t);
    emit(t.is_array() ? ir::Opcode::ArrayCopy : ir::Opcode::Assign, {r, x}, 1,
         e); // point[] -> vector[] for a call
    break;
  }
  case K::InitList: {
    r = temp(irtype(e->type, e));
    store_init({LRef{r}}, e->type, e);
    break;
  }
  }
  where_ = saved;
  if (r < 0 && !e->type.is_void()) r = temp(irtype(e->type, e)); // after an error: keep going
  return r;
}

// Initialises `dst` (the leaves of a variable of type t) from an initialiser expression.
void Lowerer::store_init(const std::vector<LRef>& dst, const ast::Type& t, const ast::Expr* init) {
  if (init->kind == K::InitList && t.is_array() && t.base != ast::BaseType::Struct &&
      dst.size() == 1 && dst[0].whole()) {
    // An array of constants: one array constant and an arraycopy, not one store per element.
    ir::Type at = sh_.symbols[size_t(dst[0].sym)].type;
    std::vector<ir::ConstValue> cv;
    if (at.arraylen > 0 && const_values(init, at, cv) &&
        cv.size() == size_t(at.arraylen * at.components())) {
      store(dst[0], ir::intern_const(sh_, at, cv), init);
      return;
    }
  }
  if (init->kind == K::InitList && t.is_array()) {
    auto* l = static_cast<const ast::InitListExpr*>(init);
    for (size_t i = 0; i < l->elems.size(); ++i) {
      std::vector<LRef> elem = dst;
      index_refs(elem, t.arraylen > 0 ? t.arraylen : int(l->elems.size()),
                 ir::intern_int(sh_, int(i)), init);
      store_init(elem, t.element(), l->elems[i].get());
    }
    return;
  }
  if (t.base == ast::BaseType::Struct) {
    std::vector<int> v = init->kind == K::InitList ? struct_parts(init, t) : rvalue_flat(init);
    for (size_t i = 0; i < dst.size() && i < v.size(); ++i) store(dst[i], v[i], init);
    return;
  }
  bool direct = dst[0].whole() && init->kind != K::InitList;
  store(dst[0], rvalue(init, direct ? dst[0].sym : -1), init);
}

} // namespace lobe::lower

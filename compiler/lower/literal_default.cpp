// Implements literal_default_leaves() (literal_default.h): oslc's notion of a literal default,
// decided on the typed AST, looking through the implicit conversions sema inserted (oslc
// folds before type checking, so `2 * 3.5` is not folded: an int meets a float).
#include "lower/literal_default.h"

namespace lobe::lower {
namespace {

using K = ast::ExprKind;

// What a literal is after oslc's parse-time folding; None for anything else.
enum class Lit { None, Int, Float, String };

const ast::Expr* strip_implicit(const ast::Expr* e) {
  while (e->kind == K::Cast && static_cast<const ast::CastExpr*>(e)->implicit)
    e = static_cast<const ast::CastExpr*>(e)->operand.get();
  return e;
}

bool is_comparison(ast::BinaryOp op) {
  using B = ast::BinaryOp;
  return op == B::Lt || op == B::Le || op == B::Gt || op == B::Ge || op == B::Eq || op == B::Ne;
}

// The operators oslc folds for two literals of kind `k`.
bool folds(ast::BinaryOp op, Lit k) {
  using B = ast::BinaryOp;
  bool arith = op == B::Add || op == B::Sub || op == B::Mul || op == B::Div;
  if (k == Lit::Float) return arith || is_comparison(op);
  if (k != Lit::Int) return false;
  return arith || is_comparison(op) || op == B::Mod || op == B::Shl || op == B::Shr ||
         op == B::BitAnd || op == B::BitOr || op == B::BitXor;
}

Lit literal(const ast::Expr* e) {
  e = strip_implicit(e);
  switch (e->kind) {
  case K::IntLit:
    return Lit::Int;
  case K::FloatLit:
    return Lit::Float;
  case K::StringLit:
    return Lit::String;
  case K::Unary: {
    auto* u = static_cast<const ast::UnaryExpr*>(e);
    if (u->overload || (u->op != ast::UnaryOp::Neg && u->op != ast::UnaryOp::Plus))
      return Lit::None;
    Lit l = literal(u->operand.get());
    return l == Lit::String ? Lit::None : l;
  }
  case K::Binary: {
    auto* b = static_cast<const ast::BinaryExpr*>(e);
    Lit l = literal(b->lhs.get());
    if (b->overload || l != literal(b->rhs.get()) || !folds(b->op, l)) return Lit::None;
    return is_comparison(b->op) ? Lit::Int : l;
  }
  default:
    return Lit::None;
  }
}

bool number(const ast::Expr* e) {
  Lit l = literal(e);
  return l == Lit::Int || l == Lit::Float;
}

// A triple or matrix: a number, or T(number) / T(n numbers) for its own type T.
bool literal_aggregate(const ast::Expr* e, const ast::Type& t) {
  if (number(e)) return true;
  e = strip_implicit(e);
  if (e->kind == K::Cast) { // T(x) with one argument: sema made it an explicit cast
    auto* c = static_cast<const ast::CastExpr*>(e);
    return c->target == t && number(c->operand.get());
  }
  if (e->kind != K::Construct) return false;
  auto* c = static_cast<const ast::ConstructExpr*>(e);
  size_t n = t.is_matrix() ? 16 : 3;
  if (!(c->target == t) || c->has_space || (c->args.size() != 1 && c->args.size() != n))
    return false;
  for (const auto& a : c->args)
    if (!number(a.get())) return false;
  return true;
}

// One element of type `t` (not an array, not a struct).
bool literal_element(const ast::Expr* e, const ast::Type& t) {
  switch (t.base) {
  case ast::BaseType::Int:
    return literal(e) == Lit::Int;
  case ast::BaseType::Float:
    return number(e);
  case ast::BaseType::String:
    return literal(e) == Lit::String;
  case ast::BaseType::Color:
  case ast::BaseType::Point:
  case ast::BaseType::Vector:
  case ast::BaseType::Normal:
  case ast::BaseType::Matrix:
    return literal_aggregate(e, t);
  default:
    return false;
  }
}

const ast::InitListExpr* init_list(const ast::Expr* e) {
  if (!e) return nullptr;
  e = strip_implicit(e);
  return e->kind == K::InitList ? static_cast<const ast::InitListExpr*>(e) : nullptr;
}

// Appends one entry per leaf of `t`; `e` is null when the leaves cannot be literal. `missing`:
// a field a struct's shorter list leaves out, which oslc fills with a literal zero (`S s = {1}`
// of struct S {float a; int b;}: defaults 1 and 0).
void leaves(const ast::Expr* e, const ast::Type& t, bool in_struct, std::vector<bool>& out,
            bool missing = false) {
  const ast::InitListExpr* list = init_list(e);
  if (t.base == ast::BaseType::Struct) {
    const auto& fields = t.strct->fields;
    if (missing && t.is_array()) { // no zero default for it (Lowerer::zero_flat): not literal
      leaves(nullptr, t, true, out);
      return;
    }
    bool ok = missing || (!t.is_array() && list && list->elems.size() <= fields.size());
    for (size_t i = 0; i < fields.size(); ++i) {
      bool absent = missing || (ok && i >= list->elems.size());
      leaves(ok && !absent ? list->elems[i].get() : nullptr, fields[i]->type, true, out, absent);
    }
    return;
  }
  if (missing) {
    out.push_back(true);
    return;
  }
  if (!t.is_array()) {
    out.push_back(e && literal_element(e, t));
    return;
  }
  bool ok = !in_struct && list;
  for (size_t i = 0; ok && i < list->elems.size(); ++i)
    ok = literal_element(list->elems[i].get(), t.element());
  out.push_back(ok);
}

} // namespace

std::vector<bool> literal_default_leaves(const ast::Expr* init, const ast::Type& type) {
  std::vector<bool> out;
  leaves(init, type, false, out);
  return out;
}

} // namespace lobe::lower

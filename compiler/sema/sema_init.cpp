// Sema: explicit casts, type constructors (a one-argument one becomes a cast) and
// initialiser lists typed from their context.
#include "sema/sema_impl.h"

namespace lobe::sema {

using ast::BaseType;
using ast::Type;

namespace {
std::string tname(const Type& t) { return ast::to_string(t); }
} // namespace

// ---- casts, constructors, initialiser lists
// ----------------------------------------------------------

void Sema::cast(ast::CastExpr* e) {
  expr(e->operand, &e->target); // `(color) noise(P)` picks the color-returning overload
  check_cast(e);
}

void Sema::check_cast(ast::CastExpr* e) {
  const Type& from = e->operand->type;
  const Type& to = e->target;
  e->type = to;
  if (from.is_error() || from == to) return;
  bool ok = (to.is_numeric() && from.is_numeric()) ||
            ((to.is_triple() || to.is_matrix()) && (from.is_numeric() || from.is_triple())) ||
            (to.is_matrix() && from.is_matrix());
  if (to.is_matrix() && from.is_triple()) ok = false;
  if (!ok) error(DiagId::err_bad_cast, e->range, {tname(from), tname(to)});
}

// T(x) with one non-string argument is a cast; the other forms stay constructors. What the
// arguments expect follows oslc: T for float(x) and the triples' T(x), nothing for int(x) and
// the matrix forms, float for each component of a triple (not for its space name).
void Sema::construct(ExprPtr& e) {
  auto* c = static_cast<ast::ConstructExpr*>(e.get());
  const Type t = c->target;
  if (c->args.size() == 1 && c->args[0]->kind != ast::ExprKind::StringLit) {
    auto k = std::make_unique<ast::CastExpr>();
    k->range = c->range;
    k->target = t;
    k->operand = std::move(c->args[0]);
    e = std::move(k);
    auto* as_cast = static_cast<ast::CastExpr*>(e.get());
    expr(as_cast->operand, t.is_float() || t.is_triple() ? &t : nullptr);
    check_cast(as_cast);
    return;
  }
  const Type component = t_float();
  for (size_t i = 0; i < c->args.size(); ++i) {
    bool is_space = c->args.size() == 4 && i == 0;
    expr(c->args[i], t.is_triple() && !is_space ? &component : nullptr);
  }
  c->type = t;
  size_t n = c->args.size();
  bool space = n > 0 && c->args[0]->type.is_string();
  size_t first = space ? 1 : 0, rest = n - first;
  bool ok = false;
  if (t.is_triple())
    ok = rest == 3;
  else if (t.is_matrix())
    ok = rest == 16 || (space && rest == 1) || (space && rest == 0);
  if (t.is_matrix() && space && n == 2 && c->args[1]->type.is_string()) {
    c->has_space = true; // matrix("from", "to")
    return;
  }
  for (size_t i = first; i < n && ok; ++i)
    ok = conversion_cost(c->args[i]->type, t_float()) != kNoConversion;
  if (!ok || (t.is_matrix() && space && rest == 0)) {
    std::string types;
    for (size_t i = 0; i < n; ++i) types += (i ? ", " : "") + tname(c->args[i]->type);
    error(DiagId::err_bad_constructor, c->range, {tname(t), types});
    c->type = t.is_triple() || t.is_matrix() ? t : t_error();
    return;
  }
  c->has_space = space;
  for (size_t i = first; i < n; ++i) coerce(c->args[i], t_float());
}

// {a, b, ...} for an array (elements) or a struct (fields). Missing trailing elements or fields
// are zero (documented in docs/language.md). For a triple or a matrix the list is the type's
// constructor, as in OSL: `color c = {1, 2, 3}` is `color(1, 2, 3)`, `{x}` is `color(x)`,
// `{"hsv", h, s, v}` and `matrix m = {"shader", 1}` take a space.
void Sema::init_list(ExprPtr& e, const Type& target) {
  auto* l = static_cast<ast::InitListExpr*>(e.get());
  l->type = t_error();
  if (target.is_error()) return;
  if (!target.is_array() && (target.is_triple() || target.is_matrix())) {
    auto c = std::make_unique<ast::ConstructExpr>();
    c->range = l->range;
    c->target = target;
    for (auto& x : l->elems) {
      if (x->kind == ast::ExprKind::InitList) {
        error(DiagId::err_init_list_context, x->range);
        return;
      }
      c->args.push_back(std::move(x));
    }
    e = std::move(c);
    construct(e);
    return;
  }
  std::vector<Type> slots;
  if (target.is_array()) {
    size_t n = target.arraylen > 0 ? size_t(target.arraylen) : l->elems.size();
    slots.assign(n, target.element());
  } else if (target.is_struct() && target.strct) {
    for (auto& f : target.strct->fields) slots.push_back(f->type);
  } else {
    error(DiagId::err_init_list_context, l->range);
    return;
  }
  if (l->elems.size() > slots.size()) {
    error(DiagId::err_init_count, l->elems[slots.size()]->range, {tname(target)});
    return;
  }
  for (size_t i = 0; i < l->elems.size(); ++i) {
    if (l->elems[i]->kind == ast::ExprKind::InitList) {
      init_list(l->elems[i], slots[i]);
    } else {
      expr(l->elems[i], &slots[i]);
      convert(l->elems[i], slots[i]);
    }
  }
  l->type = target;
  if (target.is_unsized_array()) l->type.arraylen = int(l->elems.size());
}

bool Sema::init_list_fits(const ast::Expr* e, const Type& target) const {
  auto* l = ast::as<ast::InitListExpr>(e);
  if (!l) return false;
  if (!target.is_array() && (target.is_triple() || target.is_matrix())) {
    size_t n = l->elems.size();
    bool space = n > 0 && l->elems[0]->kind == ast::ExprKind::StringLit;
    size_t rest = n - (space ? 1 : 0);
    return target.is_triple() ? (rest == 1 || rest == 3) : (rest == 1 || rest == 16);
  }
  if (target.is_array()) return target.arraylen < 0 || l->elems.size() <= size_t(target.arraylen);
  if (target.is_struct() && target.strct) return l->elems.size() <= target.strct->fields.size();
  // The constructor forms (see init_list): values, optionally after a space name.
  size_t n = l->elems.size();
  bool space = n > 0 && l->elems[0]->kind == ast::ExprKind::StringLit;
  size_t values = n - (space ? 1 : 0);
  if (target.is_triple()) return values == 3 || (!space && values == 1);
  if (target.is_matrix()) return values == 16 || values == 1;
  return false;
}

} // namespace lobe::sema

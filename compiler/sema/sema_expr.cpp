// Sema: expressions other than calls: names, operators (with the struct operator overloads and
// the closure rules), assignment, subscripts, members, casts, constructors, initialiser lists.
#include "sema/sema_impl.h"

namespace lobe::sema {

using ast::BaseType;
using ast::Type;

namespace {
std::string tname(const Type& t) { return ast::to_string(t); }
} // namespace

void Sema::expr(ExprPtr& e, const Type* expected) {
  using K = ast::ExprKind;
  switch (e->kind) {
  case K::IntLit:
    e->type = t_int();
    break;
  case K::FloatLit:
    e->type = t_float();
    break;
  case K::StringLit:
    e->type = t_string();
    break;
  case K::Ident:
    ident(static_cast<ast::IdentExpr*>(e.get()));
    break;
  case K::Unary:
    unary(static_cast<ast::UnaryExpr*>(e.get()), expected);
    break;
  case K::Binary:
    binary(static_cast<ast::BinaryExpr*>(e.get()), expected);
    break;
  case K::Assign:
    assign(static_cast<ast::AssignExpr*>(e.get()));
    break;
  case K::IncDec:
    incdec(static_cast<ast::IncDecExpr*>(e.get()));
    break;
  case K::Ternary:
    ternary(static_cast<ast::TernaryExpr*>(e.get()), expected);
    break;
  case K::Comma: {
    auto* c = static_cast<ast::CommaExpr*>(e.get());
    for (auto& x : c->exprs) expr(x);
    c->type = c->exprs.back()->type;
    break;
  }
  case K::Call:
    call(static_cast<ast::CallExpr*>(e.get()), expected);
    break;
  case K::Construct:
    construct(e);
    break;
  case K::Cast:
    cast(static_cast<ast::CastExpr*>(e.get()));
    break;
  case K::Index:
    index(e);
    break;
  case K::Member:
    member(static_cast<ast::MemberExpr*>(e.get()));
    break;
  case K::InitList:
    if (expected && (expected->is_array() || expected->is_struct() || expected->is_triple() ||
                     expected->is_matrix())) {
      init_list(e, *expected);
    } else {
      error(DiagId::err_init_list_context, e->range);
      e->type = t_error();
    }
    break;
  }
}

bool Sema::is_zero_literal(const ast::Expr* e) const {
  if (auto* i = ast::as<ast::IntLit>(e)) return i->value == 0;
  if (auto* f = ast::as<ast::FloatLit>(e)) return f->value == 0.0f;
  return false;
}

void Sema::convert(ExprPtr& e, const Type& to) {
  if (e->type.is_error() || to.is_error()) return;
  if (conversion_cost(e->type, to, is_zero_literal(e.get())) == kNoConversion) {
    bool arrays = e->type.is_array() && to.is_array() && e->type.base == to.base;
    error(arrays ? DiagId::err_array_assign_size : DiagId::err_cannot_assign, e->range,
          {tname(e->type), tname(to)});
    return;
  }
  coerce(e, to);
}

void Sema::convert_assign(ExprPtr& e, const Type& to, const std::string& name) {
  // A shorter array of the same element type fills the first elements, the rest keeping what
  // they held (oslc accepts it: float[3] into float[5] gives 1 2 3 9 9 over 9s; a longer one is
  // an error, as in oslc).
  if (e->type.is_array() && to.is_array() && !e->type.is_unsized_array() &&
      !to.is_unsized_array() && e->type.base == to.base && e->type.strct == to.strct &&
      e->type.arraylen < to.arraylen)
    return;
  if (e->type.is_float() && to.is_int()) {
    error(DiagId::warn_lose_precision, e->range, {"int", name, "float"});
    coerce(e, to);
    return;
  }
  convert(e, to);
}

// The name oslc gives an assignment's target in its warnings: a plain variable's, else none.
static std::string target_name(const ast::Expr* lhs) {
  auto* id = ast::as<ast::IdentExpr>(lhs);
  return id ? id->name : "";
}

void Sema::coerce(ExprPtr& e, const Type& to) {
  if (e->type == to || e->type.is_error() || to.is_error()) return;
  if (to.is_unsized_array()) { // an unsized parameter: the argument's length, its element type
    if (e->type.base == to.base || e->type.is_unsized_array()) return;
    return coerce(e, Type(to.base, e->type.arraylen, to.strct));
  }
  // An unsized array parameter where a sized array goes: itself, at its instance's length (a
  // function taking a sized one reads it by reference, its indices checked against that).
  if (e->type.is_unsized_array() && to.is_array() && e->type.base == to.base &&
      e->type.strct == to.strct)
    return;
  if (to.is_closure() && e->kind == ast::ExprKind::FloatLit) { // 0.0: the null closure, as 0
    auto zero = std::make_unique<ast::IntLit>();
    zero->range = e->range;
    zero->type = t_int();
    e = std::move(zero);
  }
  auto c = std::make_unique<ast::CastExpr>();
  c->range = e->range;
  c->target = to;
  c->type = to;
  c->implicit = true;
  c->operand = std::move(e);
  e = std::move(c);
}

void Sema::ident(ast::IdentExpr* e) {
  ast::VarDecl* v = lookup_var(e->name);
  if (!v) {
    error(DiagId::err_undeclared, e->range, {e->name});
    e->type = t_error();
    return;
  }
  e->decl = v;
  e->type = v->type;
  e->lvalue = true;
}

// ---- operators ----------------------------------------------------------------------------------

// A user function __operator__<name>__ taking the operands (struct operators).
bool Sema::operator_overload(ast::Expr* e, const char* opname, std::vector<ExprPtr*> operands,
                             ast::FunctionDecl*& out, int exact) {
  std::string fname = std::string("__operator__") + opname + "__";
  ast::FunctionDecl* best = nullptr;
  int best_cost = 1 << 30;
  for (auto* f : lookup_functions(fname)) {
    if (f->params.size() != operands.size()) continue;
    int cost = 0;
    for (size_t i = 0; i < operands.size() && cost >= 0; ++i) {
      int c = conversion_cost((*operands[i])->type, f->params[i]->type);
      if (int(i) == exact && !((*operands[i])->type == f->params[i]->type)) c = kNoConversion;
      cost = c == kNoConversion ? -1 : cost + c;
    }
    if (cost >= 0 && cost < best_cost) {
      best = f;
      best_cost = cost;
    }
  }
  if (!best) return false;
  for (size_t i = 0; i < operands.size(); ++i) coerce(*operands[i], best->params[i]->type);
  out = best;
  e->type = best->return_type;
  if (!functions_.empty()) edges_.push_back({functions_.back(), best, e->range});
  return true;
}

// The operand inherits the expected type of the whole expression, as in oslc (`color c = -f()`
// takes the color overload of f).
void Sema::unary(ast::UnaryExpr* e, const Type* expected) {
  expr(e->operand, expected);
  const Type& t = e->operand->type;
  e->type = t_error();
  if (t.is_error()) return;
  static const char* const kNames[] = {"neg", "", "not", "compl"};
  static const char* const kOps[] = {"-", "+", "!", "~"};
  if (t.is_struct()) {
    if (!operator_overload(e, kNames[int(e->op)], {&e->operand}, e->overload))
      error(DiagId::err_bad_unary, e->range, {kOps[int(e->op)], tname(t)});
    return;
  }
  switch (e->op) {
  case ast::UnaryOp::Neg:
  case ast::UnaryOp::Plus:
    if (t.is_scalar_or_triple() || t.is_matrix() || t.is_closure()) e->type = t;
    break;
  case ast::UnaryOp::Not: // !x is !(x as a condition); "not" itself tests a closure for null
    if (!t.is_closure()) truth(e->operand);
    if (e->operand->type.is_numeric() || e->operand->type.is_closure()) e->type = t_int();
    break;
  case ast::UnaryOp::Compl:
    if (t.is_int()) e->type = t_int();
    break;
  }
  if (e->type.is_error()) error(DiagId::err_bad_unary, e->range, {kOps[int(e->op)], tname(t)});
}

// closure + closure, closure * (float | color), (float | color) * closure.
bool Sema::closure_binary(ast::BinaryExpr* e) {
  const Type &l = e->lhs->type, &r = e->rhs->type;
  if (e->op == ast::BinaryOp::Add && l.is_closure() && r.is_closure()) {
    e->type = t_closure();
    return true;
  }
  if (e->op != ast::BinaryOp::Mul) return false;
  ExprPtr* weight = l.is_closure() ? &e->rhs : &e->lhs;
  const Type& other = l.is_closure() ? l : r;
  if (!other.is_closure()) return false;
  const Type& w = (*weight)->type;
  if (w.is_int())
    coerce(*weight, t_float());
  else if (!w.is_float() && !(w.is_triple() && w.base == BaseType::Color))
    return false;
  e->type = t_closure();
  return true;
}

// Both operands inherit the expected type of the whole expression, as in oslc, even for a
// comparison (`color b = f() == 1` takes the color overload of f).
void Sema::binary(ast::BinaryExpr* e, const Type* expected) {
  expr(e->lhs, expected);
  expr(e->rhs, expected);
  const Type l = e->lhs->type, r = e->rhs->type;
  e->type = t_error();
  if (l.is_error() || r.is_error()) return;
  using Op = ast::BinaryOp;
  auto fail = [&] {
    error(DiagId::err_bad_binary, e->range, {ast::to_string(e->op), tname(l), tname(r)});
  };
  if (l.is_struct() || r.is_struct()) {
    if (!operator_overload(e, ast::operator_name(e->op), {&e->lhs, &e->rhs}, e->overload)) fail();
    return;
  }
  if (e->op == Op::LogicalAnd || e->op == Op::LogicalOr) {
    truth(e->lhs);
    truth(e->rhs);
    if (e->lhs->type.is_numeric() && e->rhs->type.is_numeric()) e->type = t_int();
    return;
  }
  if (l.is_closure() || r.is_closure()) {
    if (!closure_binary(e)) fail();
    return;
  }
  switch (e->op) {
  case Op::BitAnd:
  case Op::BitOr:
  case Op::BitXor:
  case Op::Shl:
  case Op::Shr:
    if (l.is_int() && r.is_int())
      e->type = t_int();
    else
      fail();
    return;
  default:
    break;
  }
  auto ct = common_type(l, r);
  bool ok = ct.has_value();
  if (ok) {
    switch (e->op) {
    case Op::Add:
    case Op::Sub:
      ok = !ct->is_string() && !ct->is_matrix(); // oslc: "Not allowed: 'matrix + matrix'"
      break;
    case Op::Mul:
    case Op::Div:
      ok = !ct->is_string();
      break;
    case Op::Mod:
      ok = ct->is_numeric() || ct->is_triple();
      break;
    case Op::Eq:
    case Op::Ne:
      break;
    default:
      ok = ct->is_numeric();
      break; // < <= > >= : numbers only (not triples)
    }
  }
  if (!ok) {
    fail();
    return;
  }
  // point - point is a vector (the difference of two positions). Two other triple kinds give
  // oslc's result: with + and -, a point if either is one; otherwise the left operand's kind.
  if (e->op == Op::Sub && l.base == BaseType::Point && r.base == BaseType::Point)
    ct = t_vector();
  else if (l.is_triple() && r.is_triple() && !(l == r))
    ct = (e->op == Op::Add || e->op == Op::Sub) &&
                 (l.base == BaseType::Point || r.base == BaseType::Point)
             ? t_point()
             : l;
  // A matrix times or over a number scales it (the number is not made a diagonal matrix: no
  // products of zeros that would lose a -0 or turn an infinity into NaN), as OSL.
  if (ct->is_matrix() && (e->op == Op::Mul || e->op == Op::Div) &&
      !(l.is_matrix() && r.is_matrix())) {
    coerce(e->lhs, l.is_matrix() ? *ct : t_float());
    coerce(e->rhs, r.is_matrix() ? *ct : t_float());
    e->type = *ct;
    return;
  }
  coerce(e->lhs, *ct);
  coerce(e->rhs, *ct);
  bool comparison = e->op >= Op::Lt && e->op <= Op::Ne;
  e->type = comparison ? t_int() : *ct;
}

// The variable an lvalue expression designates (through subscripts and members).
ast::VarDecl* Sema::root_var(ast::Expr* e) const {
  while (e) {
    if (auto* i = ast::as<ast::IdentExpr>(e)) return i->decl;
    if (auto* x = ast::as<ast::IndexExpr>(e))
      e = x->base.get();
    else if (auto* m = ast::as<ast::MemberExpr>(e))
      e = m->base.get();
    else
      return nullptr;
  }
  return nullptr;
}

// As oslc: a shader parameter that is not `output` cannot be written (an error); a function's
// parameters are references to the caller's values, so writing one that is not `output`
// reaches the caller all the same, with oslc's warning (none when it is written as the output
// argument of a call, as oslc gives none); the shading globals but P, I, N and Ci are
// non-output parameters to oslc too: written with that warning, in any kind of shader.
bool Sema::check_writable(ast::Expr* target, SourceRange where, bool output_arg) {
  ast::VarDecl* v = root_var(target);
  if (!v) return true;
  if (v->storage == ast::Storage::ShaderParam && !v->is_output) {
    error(DiagId::err_write_nonoutput_param, where, {v->name});
    return false;
  }
  if (v->storage == ast::Storage::FuncParam && !v->is_output) {
    v->written = true; // lowering passes it by reference (Lowerer::call_user)
    // oslc does not warn for an array element either.
    auto* ix = ast::as<ast::IndexExpr>(target);
    bool element = ix && ix->base->type.is_array();
    if (!output_arg && !element) error(DiagId::warn_write_nonoutput_param, where, {v->name});
    return true;
  }
  if (v->storage == ast::Storage::Global && !v->writable && !output_arg)
    error(DiagId::warn_write_nonoutput_param, where, {v->name});
  return true;
}

void Sema::assign(ast::AssignExpr* e) {
  expr(e->lhs);
  const Type lt = e->lhs->type;
  e->type = lt;
  if (lt.is_error()) {
    if (e->rhs->kind != ast::ExprKind::InitList) expr(e->rhs);
    return;
  }
  if (!e->lhs->lvalue)
    error(DiagId::err_not_assignable, e->lhs->range);
  else
    check_writable(e->lhs.get(), e->lhs->range);
  if (!e->compound) {
    if (e->rhs->kind == ast::ExprKind::InitList) {
      init_list(e->rhs, lt);
    } else {
      expr(e->rhs, &lt);
      convert_assign(e->rhs, lt, target_name(e->lhs.get()));
    }
    return;
  }
  expr(e->rhs, &lt); // `x op= f()` expects x's type, as `x = f()` does
  const Type rt = e->rhs->type;
  if (rt.is_error()) return;
  using Op = ast::BinaryOp;
  auto fail = [&] {
    error(DiagId::err_bad_binary, e->range,
          {std::string(ast::to_string(e->op)) + "=", tname(lt), tname(rt)});
  };
  // OSL rewrites `a op= b` as `a = a op b`: with a struct operand, the operator overload
  // __operator__op__(a, b) applies and its result is assigned to a.
  if (lt.is_struct() || rt.is_struct()) {
    if (!operator_overload(e, ast::operator_name(e->op), {&e->lhs, &e->rhs}, e->overload, 0)) {
      fail();
      return;
    }
    Type result = e->type;
    e->type = lt;
    if (lt.is_struct() ? !(result == lt) : conversion_cost(result, lt) == kNoConversion) {
      error(DiagId::err_cannot_assign, e->range, {tname(result), tname(lt)});
      e->overload = nullptr;
    }
    return;
  }
  if (lt.is_closure()) {
    if (e->op == Op::Add && rt.is_closure()) return;
    if (e->op == Op::Mul && (rt.is_numeric() || rt.base == BaseType::Color) && !rt.is_array()) {
      if (rt.is_int()) coerce(e->rhs, t_float());
      return;
    }
    fail();
    return;
  }
  bool ok;
  switch (e->op) {
  case Op::Add:
  case Op::Sub:
  case Op::Mul:
  case Op::Div:
    // As `a = a op b`: a matrix adds and subtracts only matrices (no float as a diagonal).
    ok = lt.is_scalar_or_triple() ||
         (lt.is_matrix() && (rt.is_matrix() || (e->op != Op::Add && e->op != Op::Sub)));
    break;
  case Op::Mod:
    ok = lt.is_scalar_or_triple();
    break;
  default:
    ok = lt.is_int();
    break; // bit operations and shifts
  }
  if (!ok) {
    fail();
    return;
  }
  // `i op= f` with an int i and a float f is `i = int(i op f)`, computed in float, with
  // oslc's warning (lowering computes it so).
  if (lt.is_int() && rt.is_float() && e->op != Op::BitAnd && e->op != Op::BitOr &&
      e->op != Op::BitXor && e->op != Op::Shl && e->op != Op::Shr) {
    error(DiagId::warn_lose_precision, e->range, {"int", target_name(e->lhs.get()), "float"});
    return;
  }
  if (lt.is_matrix() && !rt.is_matrix()) { // m *= f, m /= f: scaled by the number (binary)
    convert(e->rhs, t_float());
    return;
  }
  convert(e->rhs, lt);
}

void Sema::incdec(ast::IncDecExpr* e) {
  expr(e->operand);
  e->type = e->operand->type;
  if (e->type.is_error()) return;
  // ints and floats, and as oslc allows, triples and matrices (every component steps by 1)
  if (!e->type.is_numeric() && !e->type.is_triple() && !e->type.is_matrix()) {
    error(DiagId::err_bad_unary, e->range, {e->increment ? "++" : "--", tname(e->type)});
    return;
  }
  if (!e->operand->lvalue)
    error(DiagId::err_not_assignable, e->operand->range);
  else
    check_writable(e->operand.get(), e->operand->range);
}

// oslc types the condition expecting an int; the branches inherit the expected type.
void Sema::ternary(ast::TernaryExpr* e, const Type* expected) {
  const Type int_type = t_int();
  expr(e->cond, &int_type);
  truth(e->cond, /*allow_closure=*/false);
  expr(e->then_expr, expected);
  expr(e->else_expr, expected);
  const Type a = e->then_expr->type, b = e->else_expr->type;
  e->type = t_error();
  if (a.is_error() || b.is_error()) return;
  Type result;
  if (a == b)
    result = a;
  else if (a.is_closure() && is_zero_literal(e->else_expr.get()))
    result = a;
  else if (b.is_closure() && is_zero_literal(e->then_expr.get()))
    result = b;
  else if (a.is_triple() && b.is_triple() && !a.is_array() && !b.is_array())
    result = b; // two triple kinds: oslc's result is the second branch's kind
  else if (auto ct = common_type(a, b))
    result = *ct;
  else {
    error(DiagId::err_bad_binary, e->range, {"?:", tname(a), tname(b)});
    return;
  }
  coerce(e->then_expr, result);
  coerce(e->else_expr, result);
  e->type = result;
}

// ---- subscripts and members
// -----------------------------------------------------------------------

// a[i], c[i], and m[i][j] (folded into one MatrixElement node).
void Sema::index(ExprPtr& e) {
  auto* ix = static_cast<ast::IndexExpr*>(e.get());
  auto* inner = ast::as<ast::IndexExpr>(ix->base.get());
  if (!inner || inner->index_kind != ast::IndexKind::Unresolved) {
    expr(ix->base);
    index_checked_base(ix);
    return;
  }
  expr(inner->base);
  if (!inner->base->type.is_matrix()) {
    index_checked_base(inner);
    index_checked_base(ix);
    return;
  }
  ExprPtr m = std::move(inner->base);
  ExprPtr row = std::move(inner->index);
  ix->index2 = std::move(ix->index);
  ix->index = std::move(row);
  ix->base = std::move(m); // destroys `inner`
  for (ExprPtr* i : {&ix->index, &ix->index2}) {
    expr(*i);
    if (!(*i)->type.is_int() && !(*i)->type.is_error())
      error(DiagId::err_index_not_int, (*i)->range, {tname((*i)->type)});
  }
  ix->index_kind = ast::IndexKind::MatrixElement;
  ix->type = t_float();
  ix->lvalue = ix->base->lvalue;
}

void Sema::index_checked_base(ast::IndexExpr* ix) {
  expr(ix->index);
  const Type& it = ix->index->type;
  if (!it.is_int() && !it.is_error())
    error(DiagId::err_index_not_int, ix->index->range, {tname(it)});
  const Type& bt = ix->base->type;
  ix->lvalue = ix->base->lvalue;
  ix->type = t_error();
  if (bt.is_error()) return;
  if (bt.is_array()) {
    ix->index_kind = ast::IndexKind::ArrayElement;
    ix->type = bt.element();
  } else if (bt.is_triple()) {
    ix->index_kind = ast::IndexKind::Component;
    ix->type = t_float();
  } else if (bt.is_matrix()) {
    error(DiagId::err_expected, ix->range, {"two subscripts for a matrix element: m[row][col]"});
  } else {
    error(DiagId::err_not_subscriptable, ix->base->range, {tname(bt)});
  }
}

void Sema::member(ast::MemberExpr* e) {
  expr(e->base);
  const Type& bt = e->base->type;
  e->type = t_error();
  e->lvalue = e->base->lvalue;
  if (bt.is_error()) return;
  if (bt.is_struct() && bt.strct) {
    int f = bt.strct->field_index(e->name);
    if (f >= 0) {
      e->field = f;
      e->type = bt.strct->fields[size_t(f)]->type;
      return;
    }
  } else if (bt.is_triple()) {
    const std::string& n = e->name;
    e->component = (n == "x" || n == "r")   ? 0
                   : (n == "y" || n == "g") ? 1
                   : (n == "z" || n == "b") ? 2
                                            : -1;
    if (e->component >= 0) {
      e->type = t_float();
      return;
    }
  }
  error(DiagId::err_no_member, e->name_range, {tname(bt), e->name});
}

} // namespace lobe::sema

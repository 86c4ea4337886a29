// Sema: statements.
#include "sema/sema_impl.h"

namespace lobe::sema {

void Sema::compound(ast::CompoundStmt* c, bool new_scope) {
  if (new_scope) push_scope();
  for (auto& s : c->stmts) {
    if (diags_.stopped()) break;
    stmt(s.get());
  }
  if (new_scope) pop_scope();
}

// A condition (if, while, for, do-while, ?:, !, &&, ||) follows OSL's truth rules: an int or
// float is true when non-zero, a triple or matrix when any component is, a string when it is not
// empty and a closure when it is not null (a closure is no condition for ?:, as in oslc). Anything
// else is an error. A condition that is not an int or float becomes one here (`c != 0`,
// `s != ""`, `!!cl`), so lowering and codegen only ever branch on numbers.
void Sema::condition(ExprPtr& e, bool allow_closure) {
  expr(e);
  truth(e, allow_closure);
}

void Sema::truth(ExprPtr& e, bool allow_closure) {
  const Type t = e->type;
  if (t.is_error() || t.is_numeric()) return;
  SourceRange r = e->range;
  auto typed = [&](ExprPtr x, const Type& ty) {
    x->range = r;
    x->type = ty;
    return x;
  };
  if (t.is_closure() && !t.is_array() && allow_closure) {
    for (int k = 0; k < 2; ++k) { // !!cl: "not" tests a closure for null
      auto n = std::make_unique<ast::UnaryExpr>();
      n->op = ast::UnaryOp::Not;
      n->operand = std::move(e);
      e = typed(std::move(n), t_int());
    }
    return;
  }
  if (!t.is_array() && (t.is_triple() || t.is_matrix() || t.is_string())) {
    auto ne = std::make_unique<ast::BinaryExpr>();
    ne->op = ast::BinaryOp::Ne;
    ne->lhs = std::move(e);
    if (t.is_string()) {
      ne->rhs = typed(std::make_unique<ast::StringLit>(), t_string());
    } else {
      ne->rhs = typed(std::make_unique<ast::FloatLit>(), t_float());
      coerce(ne->rhs, t);
    }
    e = typed(std::move(ne), t_int());
    return;
  }
  error(DiagId::err_bad_condition, r, {ast::to_string(t)});
}

void Sema::stmt(ast::Stmt* s) {
  switch (s->kind) {
  case ast::StmtKind::Compound:
    compound(static_cast<ast::CompoundStmt*>(s));
    break;
  case ast::StmtKind::Expr:
    expr(static_cast<ast::ExprStmt*>(s)->expr);
    break;
  case ast::StmtKind::Decl:
    for (auto& d : static_cast<ast::DeclStmt*>(s)->decls) decl(d.get());
    break;
  case ast::StmtKind::If: {
    auto* i = static_cast<ast::IfStmt*>(s);
    condition(i->cond);
    stmt(i->then_stmt.get());
    if (i->else_stmt) stmt(i->else_stmt.get());
    break;
  }
  case ast::StmtKind::While: {
    auto* w = static_cast<ast::WhileStmt*>(s);
    condition(w->cond);
    ++loop_depth_;
    stmt(w->body.get());
    --loop_depth_;
    break;
  }
  case ast::StmtKind::DoWhile: {
    auto* w = static_cast<ast::DoWhileStmt*>(s);
    ++loop_depth_;
    stmt(w->body.get());
    --loop_depth_;
    condition(w->cond);
    break;
  }
  case ast::StmtKind::For: {
    auto* f = static_cast<ast::ForStmt*>(s);
    push_scope(); // the init declaration is scoped to the loop
    if (f->init) stmt(f->init.get());
    if (f->cond) condition(f->cond);
    if (f->step) expr(f->step);
    ++loop_depth_;
    stmt(f->body.get());
    --loop_depth_;
    pop_scope();
    break;
  }
  case ast::StmtKind::Break:
  case ast::StmtKind::Continue:
    if (loop_depth_ == 0)
      error(DiagId::err_break_outside_loop, s->range,
            {s->kind == ast::StmtKind::Break ? "break" : "continue"});
    break;
  case ast::StmtKind::Return: {
    auto* r = static_cast<ast::ReturnStmt*>(s);
    ast::FunctionDecl* fn = functions_.empty() ? nullptr : functions_.back();
    r->function = fn;
    ast::Type ret = fn ? fn->return_type : t_void();
    std::string name = fn ? fn->name : (shader_ ? shader_->name : "shader");
    if (r->value) {
      if (ret.is_void()) {
        expr(r->value, &ret); // as oslc: only a void overload fits, else the rank decides
        error(DiagId::err_return_value_in_void, r->value->range, {name});
      } else {
        expr(r->value, &ret);
        convert(r->value, ret);
      }
    } else if (!ret.is_void() && !ret.is_error()) {
      error(DiagId::err_return_without_value, s->range, {name});
    }
    break;
  }
  case ast::StmtKind::Empty:
    break;
  }
}

} // namespace lobe::sema

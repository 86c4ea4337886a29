// S-expression dump of the AST.
#include "ast/ast_dump.h"

#include <cstdio>

namespace lobe::ast {
namespace {

class Dumper {
public:
  explicit Dumper(const DumpOptions& o) : o_(o) {}
  std::string out;

  void expr(const Expr* e) {
    if (!e) {
      out += "_";
      return;
    }
    switch (e->kind) {
    case ExprKind::IntLit:
      leaf(std::to_string(static_cast<const IntLit*>(e)->value), e);
      break;
    case ExprKind::FloatLit:
      leaf(float_text(static_cast<const FloatLit*>(e)->value), e);
      break;
    case ExprKind::StringLit:
      leaf(quote(static_cast<const StringLit*>(e)->value), e);
      break;
    case ExprKind::Ident:
      leaf(static_cast<const IdentExpr*>(e)->name, e);
      break;
    case ExprKind::Unary: {
      auto* u = static_cast<const UnaryExpr*>(e);
      static const char* const kOps[] = {"-", "+", "!", "~"};
      node(kOps[int(u->op)], e, {u->operand.get()});
      break;
    }
    case ExprKind::Binary: {
      auto* b = static_cast<const BinaryExpr*>(e);
      node(to_string(b->op), e, {b->lhs.get(), b->rhs.get()});
      break;
    }
    case ExprKind::Assign: {
      auto* a = static_cast<const AssignExpr*>(e);
      node(a->compound ? std::string(to_string(a->op)) + "=" : "=", e,
           {a->lhs.get(), a->rhs.get()});
      break;
    }
    case ExprKind::IncDec: {
      auto* i = static_cast<const IncDecExpr*>(e);
      node(std::string(i->prefix ? "pre" : "post") + (i->increment ? "++" : "--"), e,
           {i->operand.get()});
      break;
    }
    case ExprKind::Ternary: {
      auto* t = static_cast<const TernaryExpr*>(e);
      node("?", e, {t->cond.get(), t->then_expr.get(), t->else_expr.get()});
      break;
    }
    case ExprKind::Comma:
      list(",", e, static_cast<const CommaExpr*>(e)->exprs);
      break;
    case ExprKind::Call: {
      auto* c = static_cast<const CallExpr*>(e);
      list("call " + c->name, e, c->args);
      break;
    }
    case ExprKind::Construct: {
      auto* c = static_cast<const ConstructExpr*>(e);
      list("construct " + to_string(c->target), e, c->args);
      break;
    }
    case ExprKind::Cast: {
      auto* c = static_cast<const CastExpr*>(e);
      node(std::string(c->implicit ? "icast " : "cast ") + to_string(c->target), e,
           {c->operand.get()});
      break;
    }
    case ExprKind::Index: {
      auto* i = static_cast<const IndexExpr*>(e);
      if (i->index2)
        node("[]", e, {i->base.get(), i->index.get(), i->index2.get()});
      else
        node("[]", e, {i->base.get(), i->index.get()});
      break;
    }
    case ExprKind::Member: {
      auto* m = static_cast<const MemberExpr*>(e);
      node(". " + m->name, e, {m->base.get()});
      break;
    }
    case ExprKind::InitList:
      list("{}", e, static_cast<const InitListExpr*>(e)->elems);
      break;
    }
  }

  void stmt(const Stmt* s) {
    if (!s) {
      out += "_";
      return;
    }
    switch (s->kind) {
    case StmtKind::Compound: {
      out += "{";
      for (auto& c : static_cast<const CompoundStmt*>(s)->stmts) {
        out += " ";
        stmt(c.get());
      }
      out += " }";
      break;
    }
    case StmtKind::Expr:
      expr(static_cast<const ExprStmt*>(s)->expr.get());
      out += ";";
      break;
    case StmtKind::Decl: {
      auto* d = static_cast<const DeclStmt*>(s);
      for (size_t i = 0; i < d->decls.size(); ++i) {
        if (i) out += " ";
        decl(d->decls[i].get());
      }
      break;
    }
    case StmtKind::If: {
      auto* i = static_cast<const IfStmt*>(s);
      out += "(if ";
      expr(i->cond.get());
      out += " ";
      stmt(i->then_stmt.get());
      if (i->else_stmt) {
        out += " ";
        stmt(i->else_stmt.get());
      }
      out += ")";
      break;
    }
    case StmtKind::While: {
      auto* w = static_cast<const WhileStmt*>(s);
      out += "(while ";
      expr(w->cond.get());
      out += " ";
      stmt(w->body.get());
      out += ")";
      break;
    }
    case StmtKind::DoWhile: {
      auto* w = static_cast<const DoWhileStmt*>(s);
      out += "(do ";
      stmt(w->body.get());
      out += " ";
      expr(w->cond.get());
      out += ")";
      break;
    }
    case StmtKind::For: {
      auto* f = static_cast<const ForStmt*>(s);
      out += "(for ";
      stmt(f->init.get());
      out += " ";
      expr(f->cond.get());
      out += " ";
      expr(f->step.get());
      out += " ";
      stmt(f->body.get());
      out += ")";
      break;
    }
    case StmtKind::Break:
      out += "break";
      break;
    case StmtKind::Continue:
      out += "continue";
      break;
    case StmtKind::Return: {
      auto* r = static_cast<const ReturnStmt*>(s);
      out += "(return";
      if (r->value) {
        out += " ";
        expr(r->value.get());
      }
      out += ")";
      break;
    }
    case StmtKind::Empty:
      out += ";";
      break;
    }
  }

  void decl(const Decl* d) {
    switch (d->kind) {
    case DeclKind::Var: {
      auto* v = static_cast<const VarDecl*>(d);
      out += "(var ";
      if (v->is_output) out += "output ";
      out += to_string(v->type) + " " + v->name;
      if (v->init) {
        out += " ";
        expr(v->init.get());
      }
      metadata(v->metadata);
      out += ")";
      break;
    }
    case DeclKind::Function: {
      auto* f = static_cast<const FunctionDecl*>(d);
      out += "(function " + to_string(f->return_type) + " " + f->name + " (";
      params(f->params);
      out += ")";
      metadata(f->metadata);
      if (f->body) {
        out += " ";
        stmt(f->body.get());
      }
      out += ")";
      break;
    }
    case DeclKind::Struct: {
      auto* s = static_cast<const StructDecl*>(d);
      out += "(struct " + s->name + " (";
      params(s->fields);
      out += "))";
      break;
    }
    case DeclKind::Shader: {
      auto* s = static_cast<const ShaderDecl*>(d);
      out += std::string("(") + to_string(s->shader_type) + " " + s->name;
      metadata(s->metadata);
      out += " (";
      params(s->params);
      out += ") ";
      stmt(s->body.get());
      out += ")";
      break;
    }
    }
  }

private:
  void params(const std::vector<VarDeclPtr>& ps) {
    for (size_t i = 0; i < ps.size(); ++i) {
      if (i) out += " ";
      decl(ps[i].get());
    }
  }
  void metadata(const Metadata& md) {
    if (md.empty()) return;
    out += " [[";
    for (auto& m : md) {
      out += " " + to_string(m.type) + " " + m.name + " = ";
      expr(m.value.get());
    }
    out += " ]]";
  }
  void leaf(const std::string& text, const Expr* e) {
    out += text;
    type_suffix(e);
  }
  void node(const std::string& head, const Expr* e, std::initializer_list<const Expr*> kids) {
    out += "(" + head;
    type_suffix(e);
    for (auto* k : kids) {
      out += " ";
      expr(k);
    }
    out += ")";
  }
  void list(const std::string& head, const Expr* e, const std::vector<ExprPtr>& kids) {
    out += "(" + head;
    type_suffix(e);
    for (auto& k : kids) {
      out += " ";
      expr(k.get());
    }
    out += ")";
  }
  void type_suffix(const Expr* e) {
    if (o_.types) out += ":" + to_string(e->type);
  }
  static std::string float_text(float f) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", double(f));
    std::string s = buf;
    if (s.find_first_of(".en") == std::string::npos) s += ".0";
    return s;
  }
  static std::string quote(const std::string& s) {
    std::string r = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\') r += '\\';
      if (c == '\n') {
        r += "\\n";
        continue;
      }
      r += c;
    }
    return r + "\"";
  }
  const DumpOptions& o_;
};

} // namespace

std::string dump(const Expr* e, const DumpOptions& o) {
  Dumper d(o);
  d.expr(e);
  return d.out;
}
std::string dump(const Stmt* s, const DumpOptions& o) {
  Dumper d(o);
  d.stmt(s);
  return d.out;
}
std::string dump(const Decl* x, const DumpOptions& o) {
  Dumper d(o);
  d.decl(x);
  return d.out;
}

std::string dump(const TranslationUnit& tu, const DumpOptions& o) {
  Dumper d(o);
  for (auto& x : tu.decls) {
    if (x->from_stdlib && !o.stdlib) continue;
    d.decl(x.get());
    d.out += "\n";
  }
  return d.out;
}

} // namespace lobe::ast

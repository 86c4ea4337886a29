// Parser: statements.
#include "parse/parser_impl.h"

namespace lobe::parse {

// compound: '{' statement* '}'
std::unique_ptr<ast::CompoundStmt> Parser::compound() {
  auto c = std::make_unique<ast::CompoundStmt>();
  Token open = peek();
  if (!expect(Tok::LBrace, "'{'")) return nullptr;
  DepthGuard g(*this);
  if (!g) return nullptr;
  while (!at(Tok::RBrace) && !done()) {
    size_t before = pos_;
    StmtPtr s = statement();
    if (s) c->stmts.push_back(std::move(s));
    if (panic_ || pos_ == before) sync_statement();
  }
  if (!accept(Tok::RBrace)) {
    if (!fatal_ && !panic_) {
      error_expected("'}'");
      diags_.report(DiagId::note_to_match, open.range, {"{"});
    }
    return nullptr;
  }
  c->range = SourceRange(open.range.begin, prev().range.end);
  return c;
}

StmtPtr Parser::statement() {
  DepthGuard g(*this);
  if (!g) return nullptr;
  SourceLoc begin = peek().range.begin;
  StmtPtr s = statement_inner();
  if (s && !s->range.valid()) s->range = range_from(begin);
  return s;
}

// statement: compound | if | while | do | for | break ';' | continue ';' | return | ';'
//          | struct-declaration | declaration | nested function definition | expression ';'
StmtPtr Parser::statement_inner() {
  switch (peek().kind) {
  case Tok::LBrace:
    return compound();
  case Tok::KwIf:
    return if_statement();
  case Tok::KwWhile:
    return while_statement();
  case Tok::KwDo:
    return do_statement();
  case Tok::KwFor:
    return for_statement();
  case Tok::KwReturn:
    return return_statement();
  case Tok::KwBreak:
  case Tok::KwContinue: {
    bool brk = take().kind == Tok::KwBreak;
    if (!expect(Tok::Semi, brk ? "';' after 'break'" : "';' after 'continue'")) return nullptr;
    if (brk) return std::make_unique<ast::BreakStmt>();
    return std::make_unique<ast::ContinueStmt>();
  }
  case Tok::Semi:
    take();
    return std::make_unique<ast::EmptyStmt>();
  case Tok::KwStruct: {
    auto d = std::make_unique<ast::DeclStmt>();
    auto s = struct_declaration();
    if (s) d->decls.push_back(std::move(s));
    return d;
  }
  default:
    break;
  }
  if (starts_declaration()) return declaration_statement(true);
  return expression_statement();
}

// A declaration starts with a type followed by a name: `color c`, `S s`; but `color(1)` and
// `S(1, 2)` are expressions (constructors).
bool Parser::starts_declaration() const {
  if (!at_type()) return false;
  if (peek().kind == Tok::KwClosure) return true;
  return peek(1).kind == Tok::Ident;
}

// declaration: type IDENT array-suffix? ('=' initializer)? (',' IDENT ...)* ';'
//            | type IDENT '(' params ')' compound          (nested function definition)
StmtPtr Parser::declaration_statement(bool allow_function) {
  auto ds = std::make_unique<ast::DeclStmt>();
  SourceLoc begin = peek().range.begin;
  auto t = type();
  if (!t) return nullptr;
  do {
    Token name = peek();
    if (!expect(Tok::Ident, "a variable name")) return nullptr;
    if (allow_function && ds->decls.empty() && at(Tok::LParen)) {
      auto f = function_rest(*t, name, begin);
      if (f) ds->decls.push_back(std::move(f));
      return ds;
    }
    auto v = std::make_unique<ast::VarDecl>();
    v->storage = ast::Storage::Local;
    v->type = *t;
    v->name = std::string(name.text);
    v->name_range = name.range;
    if (!array_suffix(v->type, true)) return nullptr;
    if (accept(Tok::Assign)) {
      v->init = initializer();
      if (!v->init) return nullptr;
    }
    v->range = range_from(name.range.begin);
    ds->decls.push_back(std::move(v));
  } while (accept(Tok::Comma));
  if (!expect(Tok::Semi, "';' after the declaration")) return nullptr;
  ds->range = range_from(begin);
  return ds;
}

// if: 'if' '(' expression ')' statement ('else' statement)?
StmtPtr Parser::if_statement() {
  auto s = std::make_unique<ast::IfStmt>();
  take();
  if (!expect(Tok::LParen, "'(' after 'if'")) return nullptr;
  s->cond = expression();
  if (!s->cond || !expect(Tok::RParen, "')'")) return nullptr;
  s->then_stmt = statement();
  if (!s->then_stmt) return nullptr;
  if (accept(Tok::KwElse)) {
    s->else_stmt = statement();
    if (!s->else_stmt) return nullptr;
  }
  return s;
}

// while: 'while' '(' expression ')' statement
StmtPtr Parser::while_statement() {
  auto s = std::make_unique<ast::WhileStmt>();
  take();
  if (!expect(Tok::LParen, "'(' after 'while'")) return nullptr;
  s->cond = expression();
  if (!s->cond || !expect(Tok::RParen, "')'")) return nullptr;
  s->body = statement();
  if (!s->body) return nullptr;
  return s;
}

// do: 'do' statement 'while' '(' expression ')' ';'
StmtPtr Parser::do_statement() {
  auto s = std::make_unique<ast::DoWhileStmt>();
  take();
  s->body = statement();
  if (!s->body) return nullptr;
  if (!expect(Tok::KwWhile, "'while' after the 'do' body")) return nullptr;
  if (!expect(Tok::LParen, "'(' after 'while'")) return nullptr;
  s->cond = expression();
  if (!s->cond || !expect(Tok::RParen, "')'")) return nullptr;
  if (!expect(Tok::Semi, "';' after do-while")) return nullptr;
  return s;
}

// for: 'for' '(' (declaration | expression? ';') expression? ';' expression? ')' statement
StmtPtr Parser::for_statement() {
  auto s = std::make_unique<ast::ForStmt>();
  take();
  if (!expect(Tok::LParen, "'(' after 'for'")) return nullptr;
  if (starts_declaration()) {
    s->init = declaration_statement(false);
    if (!s->init) return nullptr;
  } else if (!accept(Tok::Semi)) {
    s->init = expression_statement();
    if (!s->init) return nullptr;
  }
  if (!at(Tok::Semi)) {
    s->cond = expression();
    if (!s->cond) return nullptr;
  }
  if (!expect(Tok::Semi, "';' in 'for'")) return nullptr;
  if (!at(Tok::RParen)) {
    s->step = expression();
    if (!s->step) return nullptr;
  }
  if (!expect(Tok::RParen, "')'")) return nullptr;
  s->body = statement();
  if (!s->body) return nullptr;
  return s;
}

// return: 'return' expression? ';'
StmtPtr Parser::return_statement() {
  auto s = std::make_unique<ast::ReturnStmt>();
  take();
  if (!at(Tok::Semi)) {
    s->value = expression();
    if (!s->value) return nullptr;
  }
  if (!expect(Tok::Semi, "';' after return")) return nullptr;
  return s;
}

StmtPtr Parser::expression_statement() {
  SourceLoc begin = peek().range.begin;
  auto s = std::make_unique<ast::ExprStmt>();
  s->expr = expression();
  if (!s->expr) return nullptr;
  if (!expect(Tok::Semi, "';' after expression")) return nullptr;
  s->range = range_from(begin);
  return s;
}

} // namespace lobe::parse

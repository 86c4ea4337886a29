// Parser: expressions, by precedence climbing for the binary operators.
#include "parse/parser_impl.h"

namespace lobe::parse {

namespace {

struct BinInfo {
  int prec; // 0: not a binary operator
  ast::BinaryOp op;
};

// C's precedence levels: || 1, && 2, | 3, ^ 4, & 5, == != 6, < <= > >= 7, << >> 8, + - 9, * / % 10.
BinInfo binary_info(Tok k) {
  using B = ast::BinaryOp;
  switch (k) {
  case Tok::PipePipe:
  case Tok::KwOr:
    return {1, B::LogicalOr};
  case Tok::AmpAmp:
  case Tok::KwAnd:
    return {2, B::LogicalAnd};
  case Tok::Pipe:
    return {3, B::BitOr};
  case Tok::Caret:
    return {4, B::BitXor};
  case Tok::Amp:
    return {5, B::BitAnd};
  case Tok::EqEq:
    return {6, B::Eq};
  case Tok::NotEq:
    return {6, B::Ne};
  case Tok::Less:
    return {7, B::Lt};
  case Tok::LessEq:
    return {7, B::Le};
  case Tok::Greater:
    return {7, B::Gt};
  case Tok::GreaterEq:
    return {7, B::Ge};
  case Tok::Shl:
    return {8, B::Shl};
  case Tok::Shr:
    return {8, B::Shr};
  case Tok::Plus:
    return {9, B::Add};
  case Tok::Minus:
    return {9, B::Sub};
  case Tok::Star:
    return {10, B::Mul};
  case Tok::Slash:
    return {10, B::Div};
  case Tok::Percent:
    return {10, B::Mod};
  default:
    return {0, B::Add};
  }
}

// Assignment operators: '=' (nullopt op) or a compound one.
bool assign_op(Tok k, bool& compound, ast::BinaryOp& op) {
  using B = ast::BinaryOp;
  compound = true;
  switch (k) {
  case Tok::Assign:
    compound = false;
    return true;
  case Tok::PlusAssign:
    op = B::Add;
    return true;
  case Tok::MinusAssign:
    op = B::Sub;
    return true;
  case Tok::StarAssign:
    op = B::Mul;
    return true;
  case Tok::SlashAssign:
    op = B::Div;
    return true;
  case Tok::PercentAssign:
    op = B::Mod;
    return true;
  case Tok::AmpAssign:
    op = B::BitAnd;
    return true;
  case Tok::PipeAssign:
    op = B::BitOr;
    return true;
  case Tok::CaretAssign:
    op = B::BitXor;
    return true;
  case Tok::ShlAssign:
    op = B::Shl;
    return true;
  case Tok::ShrAssign:
    op = B::Shr;
    return true;
  default:
    return false;
  }
}

template <class T> std::unique_ptr<T> node(SourceRange r) {
  auto n = std::make_unique<T>();
  n->range = r;
  return n;
}

} // namespace

// expression: assignment (',' assignment)*
ExprPtr Parser::expression() {
  SourceLoc begin = peek().range.begin;
  ExprPtr e = assignment();
  if (!e || !at(Tok::Comma)) return e;
  auto c = node<ast::CommaExpr>({});
  c->exprs.push_back(std::move(e));
  while (accept(Tok::Comma)) {
    ExprPtr n = assignment();
    if (!n) return nullptr;
    c->exprs.push_back(std::move(n));
  }
  c->range = range_from(begin);
  return c;
}

// assignment: ternary (assign-op assignment)?   (right associative)
ExprPtr Parser::assignment() {
  DepthGuard g(*this);
  if (!g) return nullptr;
  SourceLoc begin = peek().range.begin;
  ExprPtr lhs = ternary();
  if (!lhs) return nullptr;
  bool compound = false;
  ast::BinaryOp op = ast::BinaryOp::Add;
  if (!assign_op(peek().kind, compound, op)) return lhs;
  take();
  ExprPtr rhs = at(Tok::LBrace) ? init_list() : assignment();
  if (!rhs) return nullptr;
  auto a = node<ast::AssignExpr>({});
  a->compound = compound;
  a->op = op;
  a->lhs = std::move(lhs);
  a->rhs = std::move(rhs);
  a->range = range_from(begin);
  return a;
}

// ternary: binary ('?' expression ':' assignment)?
ExprPtr Parser::ternary() {
  SourceLoc begin = peek().range.begin;
  ExprPtr c = binary(1);
  if (!c || !accept(Tok::Question)) return c;
  auto t = node<ast::TernaryExpr>({});
  t->cond = std::move(c);
  t->then_expr = expression();
  if (!t->then_expr || !expect(Tok::Colon, "':' in conditional expression")) return nullptr;
  t->else_expr = assignment();
  if (!t->else_expr) return nullptr;
  t->range = range_from(begin);
  return t;
}

// binary: unary (binop unary)*, grouped by precedence (left associative).
// Each operator of a chain counts as a nesting level: `1 + 1 + ... + 1` builds a tree as deep
// as it is long, and later stages walk it recursively.
ExprPtr Parser::binary(int min_prec) {
  SourceLoc begin = peek().range.begin;
  ExprPtr lhs = unary();
  int levels = 0;
  struct Release {
    Parser& p;
    int& n;
    ~Release() {
      for (; n > 0; --n) p.leave();
    }
  } release{*this, levels};
  while (lhs) {
    BinInfo info = binary_info(peek().kind);
    if (info.prec < min_prec || info.prec == 0) break;
    take();
    ++levels;
    if (!enter()) return nullptr;
    ExprPtr rhs = binary(info.prec + 1);
    if (!rhs) return nullptr;
    auto b = node<ast::BinaryExpr>({});
    b->op = info.op;
    b->lhs = std::move(lhs);
    b->rhs = std::move(rhs);
    b->range = range_from(begin);
    lhs = std::move(b);
  }
  return lhs;
}

// unary: ('-' | '+' | '!' | 'not' | '~') unary | ('++' | '--') unary | cast | postfix
ExprPtr Parser::unary() {
  DepthGuard g(*this);
  if (!g) return nullptr;
  SourceLoc begin = peek().range.begin;
  Tok k = peek().kind;
  if (k == Tok::Minus || k == Tok::Plus || k == Tok::Bang || k == Tok::KwNot || k == Tok::Tilde) {
    take();
    auto u = node<ast::UnaryExpr>({});
    u->op = k == Tok::Minus   ? ast::UnaryOp::Neg
            : k == Tok::Plus  ? ast::UnaryOp::Plus
            : k == Tok::Tilde ? ast::UnaryOp::Compl
                              : ast::UnaryOp::Not;
    u->operand = unary();
    if (!u->operand) return nullptr;
    u->range = range_from(begin);
    return u;
  }
  if (k == Tok::PlusPlus || k == Tok::MinusMinus) {
    take();
    auto i = node<ast::IncDecExpr>({});
    i->increment = k == Tok::PlusPlus;
    i->prefix = true;
    i->operand = unary();
    if (!i->operand) return nullptr;
    i->range = range_from(begin);
    return i;
  }
  ExprPtr p = primary();
  if (!p) return nullptr;
  return postfix(std::move(p));
}

// postfix: primary ('[' expression ']' | '.' IDENT | '++' | '--')*
ExprPtr Parser::postfix(ExprPtr e) {
  SourceLoc begin = e->range.begin;
  while (true) {
    if (accept(Tok::LBracket)) {
      auto ix = node<ast::IndexExpr>({});
      ix->base = std::move(e);
      ix->index = expression();
      if (!ix->index || !expect(Tok::RBracket, "']'")) return nullptr;
      ix->range = range_from(begin);
      e = std::move(ix);
    } else if (accept(Tok::Dot)) {
      Token name = peek();
      if (!expect(Tok::Ident, "a member name after '.'")) return nullptr;
      auto m = node<ast::MemberExpr>({});
      m->base = std::move(e);
      m->name = std::string(name.text);
      m->name_range = name.range;
      m->range = range_from(begin);
      e = std::move(m);
    } else if (at(Tok::PlusPlus) || at(Tok::MinusMinus)) {
      auto i = node<ast::IncDecExpr>({});
      i->increment = take().kind == Tok::PlusPlus;
      i->prefix = false;
      i->operand = std::move(e);
      i->range = range_from(begin);
      e = std::move(i);
    } else {
      return e;
    }
  }
}

// primary: INT | FLOAT | STRING+ | IDENT | IDENT '(' args ')' | type '(' args ')'
//        | '(' expression ')' | '(' type ')' unary | '{' init-list '}'
ExprPtr Parser::primary() {
  const Token t = peek();
  switch (t.kind) {
  case Tok::IntLit: {
    take();
    auto n = node<ast::IntLit>(t.range);
    n->value = t.ival;
    return n;
  }
  case Tok::FloatLit: {
    take();
    auto n = node<ast::FloatLit>(t.range);
    n->value = t.fval;
    return n;
  }
  case Tok::StringLit: {
    auto n = node<ast::StringLit>({});
    while (at(Tok::StringLit)) n->value += ts_.strings[take().str]; // "a" "b" is "ab"
    n->range = SourceRange(t.range.begin, prev().range.end);
    return n;
  }
  case Tok::Ident: {
    take();
    if (at(Tok::LParen)) return call(t);
    auto n = node<ast::IdentExpr>(t.range);
    n->name = std::string(t.text);
    return n;
  }
  case Tok::LParen:
    return paren_or_cast();
  case Tok::LBrace:
    return init_list();
  default:
    break;
  }
  if (at_type() && peek(1).kind == Tok::LParen && t.kind != Tok::KwVoid &&
      t.kind != Tok::KwClosure) {
    auto ty = type();
    return constructor(*ty, t.range.begin);
  }
  error(DiagId::err_expected_expression, t.range,
        {t.kind == Tok::Eof ? "end of file" : std::string(t.text)});
  return nullptr;
}

// '(' type ')' starts a cast; anything else in parentheses is a grouped expression.
bool Parser::is_cast_ahead() const {
  if (peek().kind != Tok::LParen) return false;
  switch (peek(1).kind) {
  case Tok::KwInt:
  case Tok::KwFloat:
  case Tok::KwColor:
  case Tok::KwPoint:
  case Tok::KwVector:
  case Tok::KwNormal:
  case Tok::KwMatrix:
  case Tok::KwString:
    return peek(2).kind == Tok::RParen;
  case Tok::Ident:
    return struct_names_.count(std::string(peek(1).text)) && peek(2).kind == Tok::RParen;
  default:
    return false;
  }
}

ExprPtr Parser::paren_or_cast() {
  SourceLoc begin = peek().range.begin;
  if (is_cast_ahead()) {
    take();
    auto ty = type();
    take(); // ')'
    auto c = node<ast::CastExpr>({});
    c->target = *ty;
    c->operand = unary();
    if (!c->operand) return nullptr;
    c->range = range_from(begin);
    return c;
  }
  Token open = take();
  ExprPtr e = expression();
  if (!e) return nullptr;
  if (!accept(Tok::RParen)) {
    bool was = panic_;
    error_expected("')'");
    if (!was) diags_.report(DiagId::note_to_match, open.range, {"("});
    return nullptr;
  }
  e->range = range_from(begin); // the parentheses belong to the expression's range
  // oslc's warning, wherever a comma expression stands in parentheses (`color c = (a, b, c)`
  // is color(c)).
  if (e->kind == ast::ExprKind::Comma) diags_.report(DiagId::warn_confusing_comma, e->range);
  return e;
}

// args: (assignment-or-init-list (',' ...)*)? ')'   (the '(' is the current token)
bool Parser::arguments(std::vector<ExprPtr>& args) {
  Token open = take();
  if (accept(Tok::RParen)) return true;
  do {
    ExprPtr a = at(Tok::LBrace) ? init_list() : assignment();
    if (!a) return false;
    args.push_back(std::move(a));
  } while (accept(Tok::Comma));
  if (accept(Tok::RParen)) return true;
  bool was = panic_;
  error_expected("')' or ',' in the argument list");
  if (!was) diags_.report(DiagId::note_to_match, open.range, {"("});
  return false;
}

ExprPtr Parser::call(const Token& name) {
  auto c = node<ast::CallExpr>({});
  c->name = std::string(name.text);
  c->name_range = name.range;
  if (!arguments(c->args)) return nullptr;
  c->range = range_from(name.range.begin);
  return c;
}

ExprPtr Parser::constructor(ast::Type t, SourceLoc begin) {
  if (t.base == ast::BaseType::Struct) {
    // S(a, b): a struct constructor parses as a call of the struct's name.
    auto c = node<ast::CallExpr>({});
    c->name = t.strct ? t.strct->name : "";
    c->name_range = range_from(begin);
    if (!arguments(c->args)) return nullptr;
    c->range = range_from(begin);
    return c;
  }
  auto c = node<ast::ConstructExpr>({});
  c->target = t;
  if (!arguments(c->args)) return nullptr;
  c->range = range_from(begin);
  return c;
}

// init-list: '{' (initializer (',' initializer)* ','?)? '}'
ExprPtr Parser::init_list() {
  DepthGuard g(*this);
  if (!g) return nullptr;
  SourceLoc begin = peek().range.begin;
  Token open = take();
  auto l = node<ast::InitListExpr>({});
  while (!at(Tok::RBrace) && !done()) {
    ExprPtr e = at(Tok::LBrace) ? init_list() : assignment();
    if (!e) return nullptr;
    l->elems.push_back(std::move(e));
    if (!accept(Tok::Comma)) break;
  }
  if (!accept(Tok::RBrace)) {
    bool was = panic_;
    error_expected("'}' to end the initializer list");
    if (!was) diags_.report(DiagId::note_to_match, open.range, {"{"});
    return nullptr;
  }
  l->range = range_from(begin);
  return l;
}

} // namespace lobe::parse

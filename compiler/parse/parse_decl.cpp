// Parser: token helpers, recovery, types and declarations.
#include "parse/parser_impl.h"

namespace lobe::parse {

void parse(const lex::TokenStream& ts, diag::DiagnosticEngine& diags, ast::TranslationUnit& tu,
           const ParseOptions& options) {
  Parser(ts, diags, options).translation_unit(tu);
}

// ---- tokens and errors -------------------------------------------------------------------

const Token& Parser::peek(int ahead) const {
  size_t i = pos_ + size_t(ahead);
  return i < ts_.tokens.size() ? ts_.tokens[i] : ts_.tokens.back();
}

bool Parser::accept(Tok k) {
  if (!at(k)) return false;
  ++pos_;
  return true;
}

bool Parser::expect(Tok k, const char* what) {
  if (accept(k)) return true;
  error_expected(what);
  return false;
}

// Reports a syntax error and enters panic mode (silent until the next sync point). An error
// at a token the lexer already reported is not repeated.
void Parser::error(DiagId id, SourceRange r, std::vector<std::string> args) {
  if (panic_) return;
  panic_ = true;
  if (peek().kind == Tok::Error || prev().kind == Tok::Error) return;
  diags_.report(id, r, std::move(args));
}

void Parser::error_expected(const char* what) {
  const Token& t = peek();
  if (t.kind == Tok::Eof)
    error(DiagId::err_expected_found, t.range, {what, "end of file"});
  else
    error(DiagId::err_expected_found, t.range, {what, std::string(t.text)});
}

bool Parser::enter() {
  if (++depth_ <= opts_.max_depth) return true;
  if (!fatal_) {
    panic_ = false;
    error(DiagId::err_nesting_too_deep, peek().range, {std::to_string(opts_.max_depth)});
    fatal_ = true;
  }
  return false;
}

// Skips to just after the next ';' or to the '}' closing the current block (not consumed),
// keeping track of nested braces and parentheses.
void Parser::sync_statement() {
  int braces = 0;
  while (!done()) {
    Tok k = peek().kind;
    if (k == Tok::LBrace) ++braces;
    if (k == Tok::RBrace) {
      if (braces == 0) break;
      if (--braces == 0) {
        ++pos_;
        break;
      }
    }
    ++pos_;
    if (k == Tok::Semi && braces == 0) break;
  }
  panic_ = false;
}

// Skips to something that can start a global declaration at brace depth 0.
void Parser::sync_declaration() {
  int braces = 0;
  while (!done()) {
    Tok k = peek().kind;
    if (braces == 0 && (k == Tok::KwSurface || k == Tok::KwDisplacement || k == Tok::KwVolume ||
                        k == Tok::KwShader || k == Tok::KwStruct))
      break;
    if (k == Tok::LBrace) ++braces;
    if (k == Tok::RBrace && braces > 0 && --braces == 0) {
      ++pos_;
      break;
    }
    ++pos_;
    if (k == Tok::Semi && braces == 0) break;
  }
  panic_ = false;
}

// ---- types -----------------------------------------------------------------------------------

bool Parser::at_type() const {
  switch (peek().kind) {
  case Tok::KwInt:
  case Tok::KwFloat:
  case Tok::KwColor:
  case Tok::KwPoint:
  case Tok::KwVector:
  case Tok::KwNormal:
  case Tok::KwMatrix:
  case Tok::KwString:
  case Tok::KwVoid:
  case Tok::KwClosure:
    return true;
  case Tok::Ident:
    return struct_names_.count(std::string(peek().text)) > 0;
  default:
    return false;
  }
}

ast::Type Parser::struct_type(const std::string& name) const {
  for (auto it = structs_.rbegin(); it != structs_.rend(); ++it)
    if ((*it)->name == name) return ast::Type(ast::BaseType::Struct, 0, *it);
  return {};
}

// type: int | float | color | point | vector | normal | matrix | string | void
//     | closure color | struct-name
std::optional<ast::Type> Parser::type() {
  using B = ast::BaseType;
  Token t = take();
  switch (t.kind) {
  case Tok::KwInt:
    return ast::Type(B::Int);
  case Tok::KwFloat:
    return ast::Type(B::Float);
  case Tok::KwColor:
    return ast::Type(B::Color);
  case Tok::KwPoint:
    return ast::Type(B::Point);
  case Tok::KwVector:
    return ast::Type(B::Vector);
  case Tok::KwNormal:
    return ast::Type(B::Normal);
  case Tok::KwMatrix:
    return ast::Type(B::Matrix);
  case Tok::KwString:
    return ast::Type(B::String);
  case Tok::KwVoid:
    return ast::Type(B::Void);
  case Tok::KwClosure:
    if (!expect(Tok::KwColor, "'color' after 'closure'")) return std::nullopt;
    return ast::Type(B::Closure);
  case Tok::Ident:
    if (struct_names_.count(std::string(t.text))) return struct_type(std::string(t.text));
    error(DiagId::err_unknown_type, t.range, {std::string(t.text)});
    return std::nullopt;
  default:
    error(DiagId::err_expected_type, t.range,
          {t.kind == Tok::Eof ? "end of file" : std::string(t.text)});
    return std::nullopt;
  }
}

// array-suffix: '[' int-literal ']' | '[' ']' (unsized: parameters, or sized by an initializer)
bool Parser::array_suffix(ast::Type& t, bool allow_unsized) {
  if (!at(Tok::LBracket)) return true;
  SourceLoc b = take().range.begin;
  if (accept(Tok::RBracket)) {
    t.arraylen = -1;
    return true;
  }
  Token n = take();
  if (n.kind != Tok::IntLit || n.ival <= 0) {
    error(DiagId::err_array_size, n.range);
    return false;
  }
  t.arraylen = n.ival;
  (void)allow_unsized;
  (void)b;
  return expect(Tok::RBracket, "']'");
}

// ---- declarations ----------------------------------------------------------------------------

void Parser::translation_unit(ast::TranslationUnit& tu) {
  while (!done()) {
    if (accept(Tok::Semi)) continue;
    size_t before = pos_;
    ast::DeclPtr d = global_declaration();
    if (d) tu.decls.push_back(std::move(d));
    if (panic_ || pos_ == before) sync_declaration();
  }
}

// global-declaration: shader-declaration | struct-declaration | function-declaration
ast::DeclPtr Parser::global_declaration() {
  Tok k = peek().kind;
  if (k == Tok::KwSurface || k == Tok::KwDisplacement || k == Tok::KwVolume || k == Tok::KwShader)
    return shader_declaration();
  if (k == Tok::KwStruct) return struct_declaration();
  if (at_type()) {
    SourceLoc begin = peek().range.begin;
    auto t = type();
    if (!t) return nullptr;
    Token name = peek();
    if (!expect(Tok::Ident, "a function name")) return nullptr;
    if (!at(Tok::LParen)) {
      error_expected("'(' (only shaders, functions and structs may be declared at file scope)");
      return nullptr;
    }
    return function_rest(*t, name, begin);
  }
  const Token& t = peek();
  error(DiagId::err_expected_declaration, t.range, {std::string(t.text)});
  return nullptr;
}

// shader-declaration: shader-type IDENT metadata? '(' shader-params? ')' metadata? compound
// (the shader's metadata may come before the parameters or after them, as oslc takes it)
std::unique_ptr<ast::ShaderDecl> Parser::shader_declaration() {
  auto s = std::make_unique<ast::ShaderDecl>();
  Token kw = take();
  s->shader_type = kw.kind == Tok::KwSurface        ? ast::ShaderType::Surface
                   : kw.kind == Tok::KwDisplacement ? ast::ShaderType::Displacement
                   : kw.kind == Tok::KwVolume       ? ast::ShaderType::Volume
                                                    : ast::ShaderType::Shader;
  Token name = peek();
  if (!expect(Tok::Ident, "a shader name")) return nullptr;
  s->name = std::string(name.text);
  s->name_range = name.range;
  if (!metadata(s->metadata)) return nullptr;
  if (!expect(Tok::LParen, "'('")) return nullptr;
  while (!at(Tok::RParen) && !done()) {
    auto p = shader_param();
    if (!p) {
      // Recover inside the parameter list: skip to the next ',' or the ')'.
      int parens = 0;
      while (!done() && !(parens == 0 && (at(Tok::Comma) || at(Tok::RParen) || at(Tok::LBrace)))) {
        if (at(Tok::LParen)) ++parens;
        if (at(Tok::RParen)) --parens;
        ++pos_;
      }
      panic_ = false;
    } else {
      s->params.push_back(std::move(p));
    }
    if (!accept(Tok::Comma)) break; // a trailing comma is allowed
  }
  if (!expect(Tok::RParen, "')' or ',' after a shader parameter")) return nullptr;
  if (!metadata(s->metadata)) return nullptr;
  s->body = compound();
  if (!s->body) return nullptr;
  s->range = SourceRange(kw.range.begin, prev().range.end);
  return s;
}

// shader-param: 'output'? type IDENT array-suffix? '=' initializer metadata?
ast::VarDeclPtr Parser::shader_param() {
  auto v = std::make_unique<ast::VarDecl>();
  v->storage = ast::Storage::ShaderParam;
  SourceLoc begin = peek().range.begin;
  v->is_output = accept(Tok::KwOutput);
  auto t = type();
  if (!t) return nullptr;
  Token name = peek();
  if (!expect(Tok::Ident, "a parameter name")) return nullptr;
  v->name = std::string(name.text);
  v->name_range = name.range;
  if (!array_suffix(*t, true)) return nullptr;
  v->type = *t;
  if (accept(Tok::Assign)) {
    v->init = initializer();
    if (!v->init) return nullptr;
  } else {
    diags_.report(DiagId::err_param_needs_default, name.range,
                  {v->name}); // not a syntax error: no panic
  }
  if (!metadata(v->metadata)) return nullptr;
  v->range = range_from(begin);
  return v;
}

// initializer: '{' init-list '}' | assignment-expression
ExprPtr Parser::initializer() { return at(Tok::LBrace) ? init_list() : assignment(); }

// metadata: '[[' (type IDENT array-suffix? '=' initializer) (',' ...)* ']' ']'
bool Parser::metadata(ast::Metadata& md) {
  if (!at(Tok::MetaOpen)) return true;
  Token open = take();
  while (!done()) {
    ast::MetadataItem item;
    SourceLoc b = peek().range.begin;
    auto t = type();
    if (!t) return false;
    Token name = peek();
    if (!expect(Tok::Ident, "a metadata name")) return false;
    if (!array_suffix(*t, true)) return false;
    if (!expect(Tok::Assign, "'=' in metadata")) return false;
    item.type = *t;
    item.name = std::string(name.text);
    item.value = initializer();
    if (!item.value) return false;
    item.range = range_from(b);
    md.push_back(std::move(item));
    if (!accept(Tok::Comma)) break;
    if (at(Tok::RBracket)) break; // trailing comma
  }
  if (!(at(Tok::RBracket) && peek(1).kind == Tok::RBracket)) {
    bool was = panic_;
    error_expected("']]' to close the metadata");
    if (!was) diags_.report(DiagId::note_to_match, open.range, {"[["});
    return false;
  }
  pos_ += 2;
  return true;
}

// struct-declaration: 'struct' IDENT '{' (type IDENT array-suffix? (',' IDENT array-suffix?)* ';')*
// '}' ';'
std::unique_ptr<ast::StructDecl> Parser::struct_declaration() {
  auto s = std::make_unique<ast::StructDecl>();
  SourceLoc begin = take().range.begin;
  Token name = peek();
  if (!expect(Tok::Ident, "a struct name")) return s; // partial: later code may already refer to it
  s->name = std::string(name.text);
  s->name_range = name.range;
  // Registered before the body so that later code (and the sema) sees the type.
  struct_names_.insert(s->name);
  structs_.push_back(s.get());
  if (!expect(Tok::LBrace, "'{'")) return s; // partial: later code may already refer to it
  while (!at(Tok::RBrace) && !done()) {
    SourceLoc fb = peek().range.begin;
    auto t = type();
    if (!t) return s; // partial: later code may already refer to it
    do {
      Token fname = peek();
      if (!expect(Tok::Ident, "a field name"))
        return s; // partial: later code may already refer to it
      auto f = std::make_unique<ast::VarDecl>();
      f->storage = ast::Storage::Field;
      f->type = *t;
      if (!array_suffix(f->type, false)) return s; // partial: later code may already refer to it
      f->name = std::string(fname.text);
      f->name_range = fname.range;
      f->range = range_from(fb);
      s->fields.push_back(std::move(f));
    } while (accept(Tok::Comma));
    if (!expect(Tok::Semi, "';' after a struct field"))
      return s; // partial: later code may already refer to it
  }
  if (!expect(Tok::RBrace, "'}'")) return s; // partial: later code may already refer to it
  accept(Tok::Semi);
  s->range = range_from(begin);
  return s;
}

// function-rest: '(' (param (',' param)*)? ')' metadata? (compound | ';')
std::unique_ptr<ast::FunctionDecl> Parser::function_rest(ast::Type ret, const Token& name,
                                                         SourceLoc begin) {
  auto f = std::make_unique<ast::FunctionDecl>();
  f->return_type = ret;
  f->name = std::string(name.text);
  f->name_range = name.range;
  f->enclosing = functions_.empty() ? nullptr : functions_.back();
  expect(Tok::LParen, "'('");
  while (!at(Tok::RParen) && !done()) {
    auto p = function_param();
    if (!p) return nullptr;
    f->params.push_back(std::move(p));
    if (!accept(Tok::Comma)) break;
  }
  if (!expect(Tok::RParen, "')' after the parameters")) return nullptr;
  if (!metadata(f->metadata)) return nullptr;
  for (auto& m : f->metadata) {
    auto* v = ast::as<ast::IntLit>(m.value.get());
    if (m.name == "builtin" && v && v->value != 0) f->is_builtin = true;
    if (m.name == "osl_builtin" && v && v->value != 0) f->osl_builtin = true;
  }
  if (!accept(Tok::Semi)) {
    functions_.push_back(f.get());
    f->body = compound();
    functions_.pop_back();
    if (!f->body) return nullptr;
  }
  f->range = range_from(begin);
  return f;
}

// param: 'output'? type IDENT array-suffix?
ast::VarDeclPtr Parser::function_param() {
  auto v = std::make_unique<ast::VarDecl>();
  v->storage = ast::Storage::FuncParam;
  SourceLoc begin = peek().range.begin;
  v->is_output = accept(Tok::KwOutput);
  auto t = type();
  if (!t) return nullptr;
  v->type = *t;
  Token name = peek();
  // OSL allows unnamed parameters in prototypes.
  if (at(Tok::Ident)) {
    ++pos_;
    v->name = std::string(name.text);
    v->name_range = name.range;
  }
  if (!array_suffix(v->type, true)) return nullptr;
  v->range = range_from(begin);
  return v;
}

} // namespace lobe::parse

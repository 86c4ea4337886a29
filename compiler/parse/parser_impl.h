// The parser's private class, shared by parse_decl.cpp, parse_stmt.cpp and parse_expr.cpp.
#pragma once

#include "parse/parser.h"

#include <optional>
#include <set>
#include <string>

namespace lobe::parse {

using ast::ExprPtr;
using ast::StmtPtr;
using diag::DiagId;
using diag::SourceLoc;
using diag::SourceRange;
using lex::Tok;
using lex::Token;

class Parser {
public:
  Parser(const lex::TokenStream& ts, diag::DiagnosticEngine& diags, const ParseOptions& o)
      : ts_(ts), diags_(diags), opts_(o) {}
  void translation_unit(ast::TranslationUnit& tu);

private:
  friend class DepthGuard;
  // --- tokens
  const Token& peek(int ahead = 0) const;
  const Token& prev() const { return ts_.tokens[pos_ > 0 ? pos_ - 1 : 0]; }
  bool at(Tok k) const { return peek().kind == k; }
  bool accept(Tok k);
  bool expect(Tok k, const char* what);
  Token take() {
    const Token& t = peek();
    if (t.kind != Tok::Eof) ++pos_;
    return t;
  }
  bool done() const { return at(Tok::Eof) || fatal_ || diags_.stopped(); }
  SourceRange range_from(SourceLoc begin) const { return SourceRange(begin, prev().range.end); }
  void error(DiagId id, SourceRange r, std::vector<std::string> args = {});
  void error_expected(const char* what);
  bool enter(); // depth check; false (and an error) when too deep
  void leave() { --depth_; }

  // --- recovery
  void sync_statement();
  void sync_declaration();

  // --- types (parse_decl.cpp)
  bool at_type() const;            // a type starts here (keyword or known struct name)
  std::optional<ast::Type> type(); // base type, without array suffix
  bool array_suffix(ast::Type& t, bool allow_unsized);
  ast::Type struct_type(const std::string& name) const;

  // --- declarations (parse_decl.cpp)
  ast::DeclPtr global_declaration();
  std::unique_ptr<ast::ShaderDecl> shader_declaration();
  std::unique_ptr<ast::StructDecl> struct_declaration();
  std::unique_ptr<ast::FunctionDecl> function_rest(ast::Type ret, const Token& name,
                                                   SourceLoc begin);
  ast::VarDeclPtr shader_param();
  ast::VarDeclPtr function_param();
  bool metadata(ast::Metadata& md);
  ExprPtr initializer();

  // --- statements (parse_stmt.cpp)
  std::unique_ptr<ast::CompoundStmt> compound();
  StmtPtr statement();
  StmtPtr statement_inner();
  StmtPtr declaration_statement(bool allow_function);
  StmtPtr if_statement();
  StmtPtr while_statement();
  StmtPtr do_statement();
  StmtPtr for_statement();
  StmtPtr return_statement();
  StmtPtr expression_statement();
  bool starts_declaration() const;

  // --- expressions (parse_expr.cpp)
  ExprPtr expression(); // with the comma operator
  ExprPtr assignment();
  ExprPtr ternary();
  ExprPtr binary(int min_prec);
  ExprPtr unary();
  ExprPtr postfix(ExprPtr e);
  ExprPtr primary();
  ExprPtr paren_or_cast();
  ExprPtr call(const Token& name);
  ExprPtr constructor(ast::Type t, SourceLoc begin);
  ExprPtr init_list();
  bool arguments(std::vector<ExprPtr>& args);
  bool is_cast_ahead() const;

  const lex::TokenStream& ts_;
  diag::DiagnosticEngine& diags_;
  ParseOptions opts_;
  size_t pos_ = 0;
  int depth_ = 0;
  bool panic_ = false; // an error was reported; silent until the next sync point
  bool fatal_ = false; // nesting cap hit: stop parsing
  std::set<std::string> struct_names_;
  std::vector<const ast::StructDecl*> structs_;
  std::vector<ast::FunctionDecl*> functions_; // enclosing function definitions
};

// RAII depth counter: `DepthGuard g(*this); if (!g) return nullptr;`
class DepthGuard {
public:
  explicit DepthGuard(Parser& p) : p_(p), ok_(p.enter()) {}
  ~DepthGuard() { p_.leave(); }
  explicit operator bool() const { return ok_; }

private:
  Parser& p_;
  bool ok_;
};

} // namespace lobe::parse

// The type checker's private class, shared by sema_decl.cpp, sema_stmt.cpp, sema_expr.cpp and
// sema_call.cpp.
#pragma once

#include "sema/builtins.h"
#include "sema/overload.h"
#include "sema/sema.h"
#include "sema/types.h"

#include <string>
#include <unordered_map>
#include <vector>

namespace lobe::sema {

using ast::ExprPtr;
using diag::DiagId;
using diag::SourceRange;

class Sema {
public:
  Sema(ast::TranslationUnit& tu, diag::DiagnosticEngine& d, const SemaOptions& o)
      : tu_(tu), diags_(d), opts_(o) {}
  bool run();

private:
  struct Scope {
    std::unordered_map<std::string, ast::VarDecl*> vars;
    std::unordered_map<std::string, std::vector<ast::FunctionDecl*>> funcs; // declaration order
    bool file_level = false; // the file's or the shader's (see lookup_functions)
    // The shader's parameters and the outermost block of its body: one scope in OSL, which
    // also holds the shader globals (declare_var).
    bool shader_level = false;
  };
  struct CallEdge {
    ast::FunctionDecl* caller;
    ast::FunctionDecl* callee;
    SourceRange where;
  };
  // A candidate during overload resolution: a user function or a builtin signature.
  struct Candidate {
    ast::FunctionDecl* fn = nullptr;
    const BuiltinSig* builtin = nullptr;
    int score = 0;
    ast::Type ret() const { return fn ? fn->return_type : builtin->ret; }
    std::string signature() const;
    SourceRange where() const; // the declaration (none for a builtin)
  };

  void error(DiagId id, SourceRange r, std::vector<std::string> args = {}) {
    diags_.report(id, r, std::move(args));
  }

  // --- declarations and scopes (sema_decl.cpp)
  void push_scope() { scopes_.emplace_back(); }
  void pop_scope() { scopes_.pop_back(); }
  void declare_var(ast::VarDecl* v);
  void check_param_name(const ast::VarDecl* p, bool from_stdlib);
  void declare_function(ast::FunctionDecl* f);
  void warn_redefinition(ast::FunctionDecl* f);
  static bool redefines(const ast::FunctionDecl* f, const BuiltinSig& b);
  ast::VarDecl* lookup_var(const std::string& name);
  std::vector<ast::FunctionDecl*> lookup_functions(const std::string& name, bool* nested = nullptr);
  ast::VarDecl* global(const std::string& name);
  const ast::StructDecl* find_struct(const std::string& name) const;
  void decl(ast::Decl* d);
  void struct_decl(ast::StructDecl* s);
  void function_decl(ast::FunctionDecl* f);
  void shader_decl(ast::ShaderDecl* s);
  void var_decl(ast::VarDecl* v);
  void metadata(ast::Metadata& md);
  void check_recursion();
  void resolve_prototypes();
  bool has_return(const ast::Stmt* s) const;

  // --- statements (sema_stmt.cpp)
  void stmt(ast::Stmt* s);
  void compound(ast::CompoundStmt* c, bool new_scope = true);
  void condition(ExprPtr& e, bool allow_closure = true);
  void truth(ExprPtr& e, bool allow_closure = true); // e becomes an int condition

  // --- expressions (sema_expr.cpp)
  void expr(ExprPtr& e, const ast::Type* expected = nullptr);
  void convert(ExprPtr& e, const ast::Type& to); // implicit conversion or error
  // As convert, for an assignment or a declaration of `name` ("" when not a plain variable):
  // a float assigned to an int truncates, with oslc's warning.
  void convert_assign(ExprPtr& e, const ast::Type& to, const std::string& name);
  void coerce(ExprPtr& e, const ast::Type& to); // insert the cast (already valid)
  bool is_zero_literal(const ast::Expr* e) const;
  void init_list(ExprPtr& e, const ast::Type& target);
  bool init_list_fits(const ast::Expr* e, const ast::Type& target) const;
  void ident(ast::IdentExpr* e);
  void unary(ast::UnaryExpr* e, const ast::Type* expected);
  void binary(ast::BinaryExpr* e, const ast::Type* expected);
  bool closure_binary(ast::BinaryExpr* e);
  // `exact`: index of an operand that must match its parameter without conversion (the
  // target of a compound assignment, which stays an lvalue), or -1.
  bool operator_overload(ast::Expr* e, const char* opname, std::vector<ExprPtr*> operands,
                         ast::FunctionDecl*& out, int exact = -1);
  void assign(ast::AssignExpr* e);
  void incdec(ast::IncDecExpr* e);
  void ternary(ast::TernaryExpr* e, const ast::Type* expected);
  void index(ExprPtr& e);
  void index_checked_base(ast::IndexExpr* ix);
  void member(ast::MemberExpr* e);
  void cast(ast::CastExpr* e);
  void check_cast(ast::CastExpr* e);
  void construct(ExprPtr& e);
  bool check_writable(ast::Expr* target, SourceRange where, bool output_arg = false);
  void check_builtin_keyword(ast::CallExpr* e, const ast::StringLit* name, ExprPtr& value);
  ast::VarDecl* root_var(ast::Expr* e) const;

  // --- calls (sema_call.cpp)
  void call(ast::CallExpr* e, const ast::Type* expected);
  void struct_constructor(ast::CallExpr* e, const ast::StructDecl* s);
  bool closure_call(ast::CallExpr* e);
  std::vector<Candidate> overloads(const std::string& name, bool is_closure);
  void resolve(ast::CallExpr* e, std::vector<Candidate>& chain, const ast::Type* expected,
               bool is_closure);
  int candidate_score(const Candidate& c, const std::vector<ExprPtr>& args) const;
  void apply_candidate(ast::CallExpr* e, const Candidate& c);
  void check_output_arg(ast::CallExpr* e, size_t i, const ast::Type& pt,
                        const ast::FunctionDecl* fn = nullptr);
  static bool is_declared_closure(const ast::FunctionDecl* f);
  void add_keyword(ast::CallExpr* e, const std::string& name, int param_index, ast::Expr* value);
  void check_format_args(ast::CallExpr* e);
  void report_no_match(ast::CallExpr* e, const std::vector<Candidate>& chain);
  void report_ambiguous(ast::CallExpr* e, const std::vector<Candidate>& chain,
                        const OverloadChoice& choice);
  void note_candidates(ast::CallExpr* e, const std::vector<Candidate>& chain,
                       const std::vector<size_t>& which, DiagId note);
  std::string arg_types(const std::vector<ExprPtr>& args) const;

  ast::TranslationUnit& tu_;
  diag::DiagnosticEngine& diags_;
  const SemaOptions& opts_;
  std::vector<Scope> scopes_;
  std::unordered_map<std::string, ast::VarDecl*> globals_;
  std::unordered_map<std::string, const ast::StructDecl*> structs_;
  std::vector<ast::FunctionDecl*> functions_; // functions being checked (innermost last)
  ast::ShaderDecl* shader_ = nullptr;
  int loop_depth_ = 0;
  std::vector<CallEdge> edges_;
  std::vector<ast::CallExpr*> user_calls_;                                // calls of user functions
  std::unordered_map<ast::FunctionDecl*, ast::FunctionDecl*> defined_by_; // prototype -> definition
};

} // namespace lobe::sema

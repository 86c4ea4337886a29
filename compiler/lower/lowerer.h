// Internal: the state of one lowering (lower.h). Split over lower.cpp (symbols, emission,
// shader parameters), lower_expr.cpp (expressions, lvalues) and lower_stmt.cpp (statements,
// inlined calls).
#pragma once

#include "ast/ast.h"
#include "ir/ir.h"
#include "lower/lower.h"

#include <map>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

namespace lobe::lower {

// A location a value can be stored to or loaded from: a symbol, optionally one array element
// (`index`), and optionally one component (`comp`) or matrix element (`comp`, `comp2`).
// Index operands are int symbols. `slice` > 0 makes the location the `slice` consecutive
// elements starting at `index`: an array field of one element of an array of structs, which
// flattening stores as a run of elements of one long array (`S arr[4]` with `float a[3]` gives
// `arr.a` of type float[12]; `arr[i].a` is the slice [3i, 3i+3)).
struct LRef {
  int sym = -1;
  int index = -1;
  int comp = -1;
  int comp2 = -1;
  int slice = 0;
  bool whole() const { return index < 0 && comp < 0; }
};

// One flattened struct field: its name suffix (".a.b") and type (arrays of structs give
// arrays of fields).
struct Leaf {
  std::string suffix;
  ast::Type type;
};

// The IR opcode of a binary operator ("add", "lt", ...; "nop" for && and ||).
ir::Opcode binop_opcode(ast::BinaryOp op);

class Lowerer {
public:
  Lowerer(const ast::TranslationUnit& tu, diag::DiagnosticEngine& diags, const LowerOptions& opt)
      : tu_(tu), opt_(opt), diags_(diags) {}
  LowerResult run();

  // ---- lower.cpp: symbols, emission, errors
  ir::Type irtype(const ast::Type& t, const ast::Node* where);
  std::vector<Leaf> leaves(const ast::Type& t, const ast::Node* where);
  int new_symbol(const std::string& name, const ir::Type& t, ir::SymKind k, const ast::Node* where);
  int temp(const ir::Type& t);
  int emit(ir::Opcode opcode, std::vector<int> args, uint32_t written, const ast::Node* where,
           std::vector<int> jumps = {});
  int here(); // the index the next op gets; a jump target (resets useparam tracking)
  // Reports `id` at `where` (null: the statement being lowered).
  void error(const ast::Node* where, diag::DiagId id, std::vector<std::string> args = {});
  ir::SourceLoc loc(const ast::Node* where) const;
  std::vector<int> declare(const ast::VarDecl* v, ir::SymKind k); // symbols of a variable
  int global(const ast::VarDecl* v);
  bool const_values(const ast::Expr* e, const ir::Type& t, std::vector<ir::ConstValue>& out);

  // ---- lower_shader.cpp
  void record_struct(const ast::StructDecl* s);

  // ---- lower_expr.cpp
  int rvalue(const ast::Expr* e, int hint = -1); // non-struct value -> symbol
  int folded(const ast::Expr* e); // the constant an all-constant expression folds to, or -1
  std::vector<int> rvalue_flat(const ast::Expr* e); // struct value -> one symbol per leaf
  std::vector<LRef> lvalue(const ast::Expr* e);     // storage of an lvalue (one per leaf)
  // The value at `r`; an element or component read goes into `hint` when it has that type (as
  // oslc writes `x = a[i]` straight into x).
  int load(const LRef& r, const ast::Node* where, int hint = -1);
  // `refs` (the leaves of an array of length `len`) indexed by int symbol `idx`.
  void index_refs(std::vector<LRef>& refs, int len, int idx, const ast::Node* where);
  int int_add(int a, int b, const ast::Node* where); // a + b (folded when both are constants)
  int int_mul(int a, int k, const ast::Node* where); // a * k for a constant k
  int slice_elem(const LRef& r, int k, const ast::Node* where); // index of element k of a slice
  void store(const LRef& r, int value, const ast::Node* where);
  int written_operand(const ast::Expr* e, const ast::Node* where,
                      std::vector<std::pair<LRef, int>>& copy_back);
  void store_init(const std::vector<LRef>& dst, const ast::Type& t, const ast::Expr* init);
  int pick(int hint, const ir::Type& t);
  int logical(const ast::BinaryExpr* b);
  int ternary(const ast::TernaryExpr* t, int hint);
  std::vector<int> ternary_flat(const ast::TernaryExpr* t); // struct-valued ?:
  int assign(const ast::AssignExpr* a, int hint);
  int incdec(const ast::IncDecExpr* e);
  int construct(const ast::ConstructExpr* c, int hint);
  int call(const ast::CallExpr* c, int hint);
  std::vector<int> struct_parts(const ast::Expr* e, const ast::Type& t);
  using ConstLeaf = std::optional<std::vector<ir::ConstValue>>; // a leaf's constant default
  void const_flat(const ast::Expr* e, const ast::Type& t, std::vector<ConstLeaf>& out);
  void zero_flat(const ast::Type& t, std::vector<ConstLeaf>& out);
  int convert(int sym, const ir::Type& to, const ast::Node* where);

  // ---- lower_stmt.cpp
  void stmt(const ast::Stmt* s);
  // Inlines `f` with the given argument expressions; returns the result's symbols. A result of
  // one leaf is returned into `hint` when it has that type (oslc returns into `x` of `x = f()`
  // from inside f's body).
  std::vector<int> call_user(const ast::FunctionDecl* f, const std::vector<const ast::Expr*>& args,
                             const ast::Node* where, int hint = -1);
  int call_builtin(const ast::CallExpr* c, int hint);
  int call_closure(const ast::CallExpr* c, const std::string& key, int hint,
                   ir::Opcode opcode = ir::Opcode::Closure);
  int scratch_copy(const ast::Expr* e, const ast::Node* where);
  int call_arith(const ast::CallExpr* c, int hint); // builtins lowered to arithmetic, or -2
  int floor_mod(const ast::CallExpr* c, int hint);  // OSL mod(): a - b*floor(a/b)

  const ast::TranslationUnit& tu_;
  LowerOptions opt_;
  ir::Shader sh_;
  diag::DiagnosticEngine& diags_;
  int errors_ = 0; // reported by lowering
  std::unordered_map<const ast::VarDecl*, std::vector<int>> vars_;
  std::map<std::string, int> name_counts_;
  int next_temp_ = 0;
  std::set<int> used_params_; // params announced by useparam in the current block
  const ast::Node* where_ = nullptr;

  struct Loop {
    std::vector<int> breaks, continues; // ops to patch
  };
  std::vector<Loop> loops_;
  struct Inline {
    std::vector<int> result;
    std::vector<int> returns; // `br` ops to patch to the end of the body
    bool function = true;     // a function in OSL's sense (not an osl_builtin): Op::in_function
  };
  std::vector<Inline> inlines_;
  int pending_calls_ = 0; // inlined calls with empty bodies, counted on the next op emitted
  void patch(const std::vector<int>& ops, int target);
};

} // namespace lobe::lower

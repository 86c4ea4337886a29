// The abstract syntax tree of Lobe's shading language (OSL's language), and the slots the type
// checker (compiler/sema) fills in. The contract between the front end and the lowering to
// Lobe IR (compiler/lower).
//
// Ownership: every node owns its children through unique_ptr; cross references (an identifier's
// declaration, a call's callee, a struct type) are plain non-owning pointers into the same
// TranslationUnit, which outlives them.
//
// After a successful sema (no errors), the tree satisfies these invariants, so lowering needs no
// type rules of its own:
//  * every Expr has a valid `type` (never BaseType::Error);
//  * every conversion is explicit: an operand whose type differs from what its consumer needs is
//    wrapped in a CastExpr with implicit = true (int -> float, float -> triple, int -> triple,
//    triple -> other triple, float -> matrix (diagonal), struct copy is never converted);
//    this covers binary/unary operands, assignment right-hand sides, call arguments (after
//    overload resolution), return values, initialisers, conditions stay int/float as written;
//  * an IdentExpr's `decl` points at its VarDecl (local, parameter, shader parameter or global);
//  * a CallExpr's `callee` says what was called (user function, struct constructor, builtin
//    table entry, closure registry entry) and, for closures, which keyword arguments were given;
//  * operators applied to structs name the user function that implements them (`overload`);
//  * m[i][j] on a matrix is a single IndexExpr of kind MatrixElement (base, index, index2).
#pragma once

#include "diag/source_location.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lobe::registry {
struct ClosureEntry; // runtime/registry/closure_registry.h
struct ClosureParam;
} // namespace lobe::registry

namespace lobe::diag {
class SourceManager; // diag/source_manager.h
}

namespace lobe::sema {
struct BuiltinSig; // sema/builtins.h: one overload of a standard-library function
}

namespace lobe::ast {

using diag::SourceLoc;
using diag::SourceRange;

struct StructDecl;
struct FunctionDecl;
struct VarDecl;

// ---------------------------------------------------------------------------------------------
// Types
// ---------------------------------------------------------------------------------------------

// `Error` marks an expression whose type could not be determined (an error was reported; sema
// uses it to avoid cascades). `Closure` is `closure color`.
enum class BaseType : uint8_t {
  Error,
  Void,
  Int,
  Float,
  Color,
  Point,
  Vector,
  Normal,
  Matrix,
  String,
  Closure,
  Struct,
};

struct Type {
  BaseType base = BaseType::Error;
  int arraylen = 0;                  // 0: not an array; > 0: fixed length; -1: unsized (`a[]`)
  const StructDecl* strct = nullptr; // BaseType::Struct only

  Type() = default;
  Type(BaseType b, int len = 0, const StructDecl* s = nullptr) : base(b), arraylen(len), strct(s) {}

  bool is_error() const { return base == BaseType::Error; }
  bool is_void() const { return base == BaseType::Void && arraylen == 0; }
  bool is_array() const { return arraylen != 0; }
  bool is_unsized_array() const { return arraylen < 0; }
  bool is_triple() const {
    return !is_array() && (base == BaseType::Color || base == BaseType::Point ||
                           base == BaseType::Vector || base == BaseType::Normal);
  }
  bool is_int() const { return !is_array() && base == BaseType::Int; }
  bool is_float() const { return !is_array() && base == BaseType::Float; }
  bool is_numeric() const { return is_int() || is_float(); } // int or float scalar
  bool is_scalar_or_triple() const { return is_numeric() || is_triple(); }
  bool is_matrix() const { return !is_array() && base == BaseType::Matrix; }
  bool is_string() const { return !is_array() && base == BaseType::String; }
  bool is_closure() const { return !is_array() && base == BaseType::Closure; }
  bool is_struct() const { return !is_array() && base == BaseType::Struct; }
  Type element() const { return Type(base, 0, strct); } // the element type of an array
  friend bool operator==(const Type&, const Type&) = default;
};

std::string to_string(const Type& t); // "float", "color[3]", "float[]", "closure color", "S"
const char* to_string(BaseType b);    // "float", ..., "struct"

// ---------------------------------------------------------------------------------------------
// Metadata: `[[ string help = "text", float min = 0, int builtin = 1 ]]`
// ---------------------------------------------------------------------------------------------
struct Expr;

struct MetadataItem {
  Type type; // as written (arrays allowed: `float range[2] = {0,1}`)
  std::string name;
  std::unique_ptr<Expr> value; // a constant expression (sema checks and converts it)
  SourceRange range;
};
using Metadata = std::vector<MetadataItem>;

// ---------------------------------------------------------------------------------------------
// Nodes
// ---------------------------------------------------------------------------------------------

struct Node {
  SourceRange range;
  virtual ~Node() = default;
};

// ---- Expressions ----------------------------------------------------------------------------

enum class ExprKind : uint8_t {
  IntLit,
  FloatLit,
  StringLit,
  Ident,
  Unary,
  Binary,
  Assign,
  IncDec,
  Ternary,
  Comma,
  Call,
  Construct,
  Cast,
  Index,
  Member,
  InitList,
};

struct Expr : Node {
  const ExprKind kind;
  Type type;           // filled by sema
  bool lvalue = false; // filled by sema: may be assigned (a variable, element, component, field)
  explicit Expr(ExprKind k) : kind(k) {}
};
using ExprPtr = std::unique_ptr<Expr>;

struct IntLit : Expr {
  int32_t value = 0;
  IntLit() : Expr(ExprKind::IntLit) {}
};

struct FloatLit : Expr {
  float value = 0;
  FloatLit() : Expr(ExprKind::FloatLit) {}
};

// Adjacent string literals are concatenated by the parser; escapes are already decoded.
struct StringLit : Expr {
  std::string value;
  StringLit() : Expr(ExprKind::StringLit) {}
};

struct IdentExpr : Expr {
  std::string name;
  VarDecl* decl = nullptr; // sema: the variable named (local, param, shader param, global)
  IdentExpr() : Expr(ExprKind::Ident) {}
};

enum class UnaryOp : uint8_t { Neg, Plus, Not, Compl }; // -x, +x, !x / not x, ~x
struct UnaryExpr : Expr {
  UnaryOp op = UnaryOp::Neg;
  ExprPtr operand;
  FunctionDecl* overload = nullptr; // sema: __operator__neg__ / __not__ / __compl__ on a struct
  UnaryExpr() : Expr(ExprKind::Unary) {}
};

enum class BinaryOp : uint8_t {
  Add,
  Sub,
  Mul,
  Div,
  Mod,
  Shl,
  Shr,
  BitAnd,
  BitOr,
  BitXor,
  Lt,
  Le,
  Gt,
  Ge,
  Eq,
  Ne,
  LogicalAnd,
  LogicalOr, // short-circuit; `and` / `or` are synonyms
};
const char* to_string(BinaryOp op);     // "+", "-", ..., "&&"
const char* operator_name(BinaryOp op); // "add", "sub", ... as in __operator__add__ ("" for && ||)

// After sema: for arithmetic on numbers, triples and matrices both operands have been converted
// to one common operand type (the result type for + - * / %; for == != < etc. the compared type,
// the result being int). A number meeting a matrix is converted to a matrix (diagonal), as in
// `matrix m = 1`. && and || take int or float operands as written and give int. The one
// exception: closure * weight and weight * closure keep the weight's type (float or color).
struct BinaryExpr : Expr {
  BinaryOp op = BinaryOp::Add;
  ExprPtr lhs, rhs;
  FunctionDecl* overload = nullptr; // sema: user operator function for struct operands
  BinaryExpr() : Expr(ExprKind::Binary) {}
};

// `lhs = rhs` or a compound assignment `lhs op= rhs` (op is then the BinaryOp applied).
// After sema the rhs of a plain assignment has the lhs's type; for compound assignment the rhs
// has the type the operation `lhs op rhs` needs (lhs's type, or float/color for closure *=).
struct AssignExpr : Expr {
  bool compound = false;
  BinaryOp op = BinaryOp::Add; // meaningful when compound
  ExprPtr lhs, rhs;
  // sema, compound with a struct operand: the user operator function; the assignment is then
  // `lhs = overload(lhs, rhs)` (rhs coerced to its second parameter, lhs matching exactly).
  FunctionDecl* overload = nullptr;
  AssignExpr() : Expr(ExprKind::Assign) {}
};

struct IncDecExpr : Expr {
  bool increment = true; // ++ or --
  bool prefix = true;    // ++x or x++
  ExprPtr operand;
  IncDecExpr() : Expr(ExprKind::IncDec) {}
};

// cond ? a : b. After sema a and b have the result type.
struct TernaryExpr : Expr {
  ExprPtr cond, then_expr, else_expr;
  TernaryExpr() : Expr(ExprKind::Ternary) {}
};

// a, b, c: evaluates all, value of the last.
struct CommaExpr : Expr {
  std::vector<ExprPtr> exprs;
  CommaExpr() : Expr(ExprKind::Comma) {}
};

// What a call resolved to.
enum class CalleeKind : uint8_t {
  Unresolved,
  User,       // a FunctionDecl with a body (user code or stdosl.h), or a [[builtin=1]] prototype
  StructCtor, // S(a, b, ...): one argument per field, converted to the field types
  Builtin,    // an entry of the builtin table (sema/builtins.h)
  Closure,    // an entry of the closure registry
};

// A keyword argument `"name", value` given to a closure or to a builtin that takes keywords.
// `param_index` indexes ClosureEntry::params (closures); -1 for builtins. When a keyword is
// given several times the last one wins and only it is listed here.
struct KeywordArg {
  std::string name;
  int param_index = -1;
  Expr* value = nullptr; // points into CallExpr::args (owned there)
};

struct Callee {
  CalleeKind kind = CalleeKind::Unresolved;
  FunctionDecl* function = nullptr;                // User
  const StructDecl* strct = nullptr;               // StructCtor
  const sema::BuiltinSig* builtin = nullptr;       // Builtin
  const registry::ClosureEntry* closure = nullptr; // Closure
};

// name(args...). Struct constructors parse as calls too (the name is a struct).
// After sema: args[0 .. num_positional) are the positional arguments converted to the callee's
// parameter types (output parameters are never converted: they have exactly the parameter
// type; an array passed to an unsized array parameter keeps its sized type); the rest are
// keyword pairs (string name, value) summarised in `keywords`. Variadic builtins (printf,
// format, error, warning, concat) keep their extra arguments as written.
struct CallExpr : Expr {
  std::string name;
  SourceRange name_range;
  std::vector<ExprPtr> args;
  Callee callee;                    // sema
  int num_positional = -1;          // sema (-1 before sema: all positional)
  std::vector<KeywordArg> keywords; // sema: closure / builtin keyword arguments, last wins
  CallExpr() : Expr(ExprKind::Call) {}
};

// A type constructor with several arguments: color(r,g,b), color("hsv", h, s, v),
// point("object", x, y, z), matrix(16 floats), matrix("from", "to"), matrix("space", 16 floats),
// matrix("space", f). `has_space` is set by sema when the first argument is a string (it stays
// args[0]); the other arguments are converted to float, except matrix("from", "to") (two
// strings). A one-argument form T(x) (int(x), float(x), color(f), vector(P), matrix(f)) is
// replaced by sema with an explicit CastExpr (implicit = false): lowering never sees it here.
struct ConstructExpr : Expr {
  Type target; // the constructed type (as written)
  std::vector<ExprPtr> args;
  bool has_space = false; // sema: args[0] is a string naming a space / colour space
  ConstructExpr() : Expr(ExprKind::Construct) {}
};

// (type) expr, written by the user, or inserted by sema (implicit = true).
struct CastExpr : Expr {
  Type target;
  ExprPtr operand;
  bool implicit = false;
  CastExpr() : Expr(ExprKind::Cast) {}
};

enum class IndexKind : uint8_t {
  Unresolved,
  ArrayElement,  // a[i]
  Component,     // triple c[i]
  MatrixElement, // m[i][j] (index, index2)
};
// base[index] (and base[index][index2] for matrices, after sema folds the nested form).
struct IndexExpr : Expr {
  ExprPtr base, index, index2;
  IndexKind index_kind = IndexKind::Unresolved; // sema
  IndexExpr() : Expr(ExprKind::Index) {}
};

// base.name: a struct field or a triple component (.x .y .z / .r .g .b).
struct MemberExpr : Expr {
  ExprPtr base;
  std::string name;
  SourceRange name_range;
  int field = -1;     // sema: struct field index
  int component = -1; // sema: 0..2 for a triple component
  MemberExpr() : Expr(ExprKind::Member) {}
};

// { a, b, ... }: an array or struct initialiser; its type comes from context (sema). After
// sema each element has the element / field type. It may be shorter than the array or struct:
// the missing trailing elements / fields are zero.
struct InitListExpr : Expr {
  std::vector<ExprPtr> elems;
  InitListExpr() : Expr(ExprKind::InitList) {}
};

// ---- Declarations -----------------------------------------------------------------------------

enum class DeclKind : uint8_t { Var, Function, Struct, Shader };

struct Decl : Node {
  const DeclKind kind;
  std::string name;
  SourceRange name_range;
  bool from_stdlib = false; // declared by a header built into the compiler (stdosl.h, ...)
  explicit Decl(DeclKind k) : kind(k) {}
};
using DeclPtr = std::unique_ptr<Decl>;

enum class Storage : uint8_t {
  Local,       // variable declared in a function or shader body
  FuncParam,   // function parameter (by reference; written with a warning unless `output`)
  ShaderParam, // shader parameter (its default is `init`)
  Global,      // shading global (P, N, Ci, ...), declared by sema
  Field,       // struct field
};

struct VarDecl : Decl {
  Type type;
  Storage storage = Storage::Local;
  bool is_output = false;     // `output` parameter (function or shader)
  std::unique_ptr<Expr> init; // initialiser / default value (may be null for locals, fields)
  Metadata metadata;          // shader parameters
  bool writable = true;       // sema: false for read-only globals and non-output func params
  bool written = false;       // sema: a non-output function parameter the body writes (OSL
                              // allows it with a warning; the caller's variable is written)
  VarDecl() : Decl(DeclKind::Var) {}
};
using VarDeclPtr = std::unique_ptr<VarDecl>;

struct Stmt;
struct CompoundStmt;

// Function definition or prototype. Operator overloads are functions named __operator__add__
// etc. A prototype with [[ int builtin = 1 ]] declares something the renderer provides.
struct FunctionDecl : Decl {
  Type return_type;
  std::vector<VarDeclPtr> params;     // storage FuncParam
  std::unique_ptr<CompoundStmt> body; // null for a prototype
  Metadata metadata;
  bool is_builtin = false; // parser: metadata has `int builtin = 1`
  // parser: metadata has `int osl_builtin = 1`: a stdosl.h function Lobe writes out that OSL
  // implements as a builtin op, so its body is not a function body in OSL's sense
  // (ir::Op::in_function).
  bool osl_builtin = false;
  FunctionDecl* enclosing = nullptr; // nested definitions: the function defined in (or null)
  FunctionDecl() : Decl(DeclKind::Function) {}
};

struct StructDecl : Decl {
  std::vector<VarDeclPtr> fields; // storage Field; a field may be an array or another struct
  StructDecl() : Decl(DeclKind::Struct) {}
  int field_index(const std::string& n) const {
    for (size_t i = 0; i < fields.size(); ++i)
      if (fields[i]->name == n) return int(i);
    return -1;
  }
};

enum class ShaderType : uint8_t { Surface, Displacement, Volume, Shader };
const char* to_string(ShaderType t);

struct ShaderDecl : Decl {
  ShaderType shader_type = ShaderType::Surface;
  std::vector<VarDeclPtr> params; // storage ShaderParam, every one with an `init` default
  Metadata metadata;              // shader-level metadata
  std::unique_ptr<CompoundStmt> body;
  ShaderDecl() : Decl(DeclKind::Shader) {}
};

// ---- Statements -------------------------------------------------------------------------------

enum class StmtKind : uint8_t {
  Compound,
  Expr,
  Decl, // local variables, nested function definitions, local structs
  If,
  While,
  DoWhile,
  For,
  Break,
  Continue,
  Return,
  Empty,
};

struct Stmt : Node {
  const StmtKind kind;
  explicit Stmt(StmtKind k) : kind(k) {}
};
using StmtPtr = std::unique_ptr<Stmt>;

struct CompoundStmt : Stmt {
  std::vector<StmtPtr> stmts;
  CompoundStmt() : Stmt(StmtKind::Compound) {}
};

struct ExprStmt : Stmt {
  ExprPtr expr;
  ExprStmt() : Stmt(StmtKind::Expr) {}
};

// `float a = 1, b[2] = {1, 2};` gives one DeclStmt with two VarDecls; a nested function
// definition or a struct declaration gives a DeclStmt with that one decl.
struct DeclStmt : Stmt {
  std::vector<DeclPtr> decls;
  DeclStmt() : Stmt(StmtKind::Decl) {}
};

struct IfStmt : Stmt {
  ExprPtr cond;
  StmtPtr then_stmt, else_stmt; // else may be null
  IfStmt() : Stmt(StmtKind::If) {}
};

struct WhileStmt : Stmt {
  ExprPtr cond;
  StmtPtr body;
  WhileStmt() : Stmt(StmtKind::While) {}
};

struct DoWhileStmt : Stmt {
  StmtPtr body;
  ExprPtr cond;
  DoWhileStmt() : Stmt(StmtKind::DoWhile) {}
};

// for (init; cond; step) body. init is a DeclStmt (scoped to the loop) or an ExprStmt or null;
// cond and step may be null.
struct ForStmt : Stmt {
  StmtPtr init;
  ExprPtr cond, step;
  StmtPtr body;
  ForStmt() : Stmt(StmtKind::For) {}
};

struct BreakStmt : Stmt {
  BreakStmt() : Stmt(StmtKind::Break) {}
};
struct ContinueStmt : Stmt {
  ContinueStmt() : Stmt(StmtKind::Continue) {}
};

// return [value]; in a shader body `return` ends the shader (like exit()).
struct ReturnStmt : Stmt {
  ExprPtr value;                    // converted to the function's return type by sema
  FunctionDecl* function = nullptr; // sema: the function returned from (null in a shader)
  ReturnStmt() : Stmt(StmtKind::Return) {}
};

struct EmptyStmt : Stmt {
  EmptyStmt() : Stmt(StmtKind::Empty) {}
};

// ---- Translation unit -------------------------------------------------------------------------

// One compiled file, with the standard header's declarations first (from_stdlib = true, as are
// those of the other built-in headers it includes).
struct TranslationUnit {
  std::vector<DeclPtr> decls;                   // structs, functions, shaders, in source order
  std::vector<VarDeclPtr> globals;              // sema: the shading globals referenced by IdentExpr
  std::shared_ptr<diag::SourceManager> sources; // resolves SourceLoc to file/line/column

  // The (first) shader declared in the file, or null.
  ShaderDecl* shader() const {
    for (auto& d : decls)
      if (d->kind == DeclKind::Shader) return static_cast<ShaderDecl*>(d.get());
    return nullptr;
  }
};

// Checked downcasts by kind (nullptr when the kind differs).
template <class T> T* as(Expr* e);
template <class T> const T* as(const Expr* e);

#define LOBE_AST_KIND_CAST(T, K)                                                                   \
  template <> inline T* as<T>(Expr * e) {                                                          \
    return e && e->kind == ExprKind::K ? static_cast<T*>(e) : nullptr;                             \
  }                                                                                                \
  template <> inline const T* as<T>(const Expr* e) {                                               \
    return e && e->kind == ExprKind::K ? static_cast<const T*>(e) : nullptr;                       \
  }
LOBE_AST_KIND_CAST(IntLit, IntLit)
LOBE_AST_KIND_CAST(FloatLit, FloatLit)
LOBE_AST_KIND_CAST(StringLit, StringLit)
LOBE_AST_KIND_CAST(IdentExpr, Ident)
LOBE_AST_KIND_CAST(UnaryExpr, Unary)
LOBE_AST_KIND_CAST(BinaryExpr, Binary)
LOBE_AST_KIND_CAST(AssignExpr, Assign)
LOBE_AST_KIND_CAST(IncDecExpr, IncDec)
LOBE_AST_KIND_CAST(TernaryExpr, Ternary)
LOBE_AST_KIND_CAST(CommaExpr, Comma)
LOBE_AST_KIND_CAST(CallExpr, Call)
LOBE_AST_KIND_CAST(ConstructExpr, Construct)
LOBE_AST_KIND_CAST(CastExpr, Cast)
LOBE_AST_KIND_CAST(IndexExpr, Index)
LOBE_AST_KIND_CAST(MemberExpr, Member)
LOBE_AST_KIND_CAST(InitListExpr, InitList)
#undef LOBE_AST_KIND_CAST

} // namespace lobe::ast

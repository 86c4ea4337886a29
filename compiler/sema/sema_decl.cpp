// Sema: scopes, globals, and declarations (structs, functions, shaders, variables), plus the
// whole-file checks (recursion).
#include "sema/sema_impl.h"

#include "closure_registry.h"
#include "lobe/shading_globals.h"

#include <algorithm>
#include <functional>
#include <ranges>
#include <set>

namespace lobe::sema {

bool check(ast::TranslationUnit& tu, diag::DiagnosticEngine& diags, const SemaOptions& options) {
  return Sema(tu, diags, options).run();
}

bool Sema::run() {
  int errors_before = diags_.error_count();
  push_scope();
  scopes_.back().file_level = true;
  for (auto& d : tu_.decls) {
    if (diags_.stopped()) break;
    decl(d.get());
  }
  resolve_prototypes();
  check_recursion();
  pop_scope();
  return diags_.error_count() == errors_before;
}

// ---- scopes -----------------------------------------------------------------------------------

// A shader's parameters and the outermost block of its body are one scope in OSL, with the
// shader globals in it: oslc 1.13.12 rejects `shader g(float u = 1)` and `shader g() { float
// a = 1; }` beside a parameter `a` ("\"u\" already declared in this scope"); nested blocks and
// functions may reuse the names.
void Sema::declare_var(ast::VarDecl* v) {
  if (v->name.empty()) return; // unnamed prototype parameter
  auto& vars = scopes_.back().vars;
  auto it = vars.find(v->name);
  if (it != vars.end()) {
    error(DiagId::err_redefinition, v->name_range, {v->name});
    error(DiagId::note_previous_decl, it->second->name_range);
    return;
  }
  if (scopes_.back().shader_level) {
    const ShadingGlobal* g = find_shading_global(v->name);
    if (g && (g->flags & kGlobalNamed)) {
      error(DiagId::err_redeclares_global, v->name_range, {v->name});
      return;
    }
    for (size_t i = scopes_.size() - 1; i-- > 0 && scopes_[i].shader_level;) {
      auto prev = scopes_[i].vars.find(v->name);
      if (prev == scopes_[i].vars.end()) continue;
      error(DiagId::err_redefinition, v->name_range, {v->name});
      error(DiagId::note_previous_decl, prev->second->name_range);
      return;
    }
  }
  vars[v->name] = v;
}

namespace {
bool same_params(const ast::FunctionDecl* a, const ast::FunctionDecl* b) {
  if (a->params.size() != b->params.size()) return false;
  for (size_t i = 0; i < a->params.size(); ++i)
    if (!(a->params[i]->type == b->params[i]->type)) return false;
  return true;
}
// OSL overloads by return type too: `float pick()` and `color pick()` are two functions.
bool same_signature(const ast::FunctionDecl* a, const ast::FunctionDecl* b) {
  return same_params(a, b) && a->return_type == b->return_type;
}
} // namespace

// Functions overload by parameter types and by return type; a prototype is completed by the
// definition of its signature. Defining a signature of the same overload scope again (at file
// level, that includes the builtins) replaces it from here on, with oslc's warning.
void Sema::declare_function(ast::FunctionDecl* f) {
  auto& set = scopes_.back().funcs[f->name];
  auto same = std::find_if(set.begin(), set.end(),
                           [&](ast::FunctionDecl* g) { return same_signature(g, f); });
  if (same != set.end() && (!(*same)->body || !f->body)) { // a prototype and its definition
    if (f->body) {
      defined_by_[*same] = f;
      *same = f;
    }
    return;
  }
  warn_redefinition(f);
  if (same != set.end()) set.erase(same); // the new definition is the newest overload
  set.push_back(f);
}

// oslc's warning when a definition repeats a signature of its overload scope: at file level
// (which includes the shader body and the builtins) or in the same nested scope. Not for the
// standard header, which may restate one.
void Sema::warn_redefinition(ast::FunctionDecl* f) {
  if (!f->body || f->from_stdlib) return;
  bool file_level = scopes_.back().file_level;
  std::vector<ast::FunctionDecl*> previous =
      file_level ? lookup_functions(f->name) : scopes_.back().funcs[f->name];
  for (ast::FunctionDecl* g : previous) {
    if (!g->body || !same_signature(g, f)) continue;
    error(DiagId::warn_function_redefined, f->name_range,
          {diag::oslc_signature(Candidate{f}.signature())});
    error(DiagId::note_previous_decl, g->name_range);
    return;
  }
  for (const BuiltinSig& b : builtins().lookup(f->name)) {
    if (!file_level || !redefines(f, b)) continue;
    error(DiagId::warn_function_redefined, f->name_range,
          {diag::oslc_signature(Candidate{f}.signature())});
    error(DiagId::note_previous_builtin, SourceRange(), {b.signature()});
    return;
  }
}

// A user function with exactly a builtin's signature (return and parameter types) replaces it.
bool Sema::redefines(const ast::FunctionDecl* f, const BuiltinSig& b) {
  if (f->is_builtin || b.extra != BuiltinSig::Extra::None || b.any_param || b.array_param)
    return false;
  if (!(f->return_type == b.ret) || f->params.size() != b.params.size()) return false;
  for (size_t i = 0; i < b.params.size(); ++i)
    if (!(f->params[i]->type == b.params[i].type)) return false;
  return true;
}

ast::VarDecl* Sema::lookup_var(const std::string& name) {
  for (auto s = scopes_.rbegin(); s != scopes_.rend(); ++s) {
    auto it = s->vars.find(name);
    if (it != s->vars.end()) return it->second;
  }
  return global(name);
}

// The functions named `name` in sight, newest declaration first, as oslc sees them. The file
// scope and the shader's parameter and body scopes are one overload scope, which also holds
// the builtins; in any other scope (a function body, a block) a function declared there hides
// every outer overload of its name, the builtins too (`*nested` is then set).
std::vector<ast::FunctionDecl*> Sema::lookup_functions(const std::string& name, bool* nested) {
  std::vector<ast::FunctionDecl*> out;
  if (nested) *nested = false;
  for (auto s = scopes_.rbegin(); s != scopes_.rend(); ++s) {
    auto it = s->funcs.find(name);
    if (it == s->funcs.end() || it->second.empty()) continue;
    auto newest_first = std::views::reverse(it->second);
    if (!s->file_level) {
      if (nested) *nested = true;
      return {newest_first.begin(), newest_first.end()};
    }
    for (auto* f : newest_first) {
      bool hidden = false; // a newer overload of the same signature replaces an older one
      for (auto* o : out) hidden |= same_signature(o, f);
      if (!hidden) out.push_back(f);
    }
  }
  return out;
}

namespace {
// A global's type in the language (lobe/shading_globals.h).
ast::BaseType global_base(GlobalType t) {
  switch (t) {
  case GlobalType::Float:
    return ast::BaseType::Float;
  case GlobalType::Point:
    return ast::BaseType::Point;
  case GlobalType::Vector:
    return ast::BaseType::Vector;
  case GlobalType::Normal:
    return ast::BaseType::Normal;
  case GlobalType::Closure:
    return ast::BaseType::Closure;
  }
  return ast::BaseType::Float;
}
} // namespace

// Globals are declared on first use, so the translation unit lists only those it reads; the
// ones shaders may name are lobe/shading_globals.h's kGlobalNamed rows.
ast::VarDecl* Sema::global(const std::string& name) {
  auto it = globals_.find(name);
  if (it != globals_.end()) return it->second;
  const ShadingGlobal* g = find_shading_global(name);
  if (!g || !(g->flags & kGlobalNamed)) return nullptr;
  auto v = std::make_unique<ast::VarDecl>();
  v->name = name;
  v->type = ast::Type(global_base(g->type));
  v->storage = ast::Storage::Global;
  v->writable = (g->flags & kGlobalWritable) != 0;
  ast::VarDecl* raw = v.get();
  tu_.globals.push_back(std::move(v));
  globals_[name] = raw;
  return raw;
}

const ast::StructDecl* Sema::find_struct(const std::string& name) const {
  auto it = structs_.find(name);
  return it == structs_.end() ? nullptr : it->second;
}

// ---- declarations
// --------------------------------------------------------------------------------

void Sema::decl(ast::Decl* d) {
  switch (d->kind) {
  case ast::DeclKind::Struct:
    struct_decl(static_cast<ast::StructDecl*>(d));
    break;
  case ast::DeclKind::Function:
    function_decl(static_cast<ast::FunctionDecl*>(d));
    break;
  case ast::DeclKind::Shader:
    shader_decl(static_cast<ast::ShaderDecl*>(d));
    break;
  case ast::DeclKind::Var:
    var_decl(static_cast<ast::VarDecl*>(d));
    break;
  }
}

void Sema::struct_decl(ast::StructDecl* s) {
  if (auto* prev = find_struct(s->name); prev && prev != s) {
    error(DiagId::err_redefinition, s->name_range, {s->name});
    error(DiagId::note_previous_decl, prev->name_range);
  }
  structs_[s->name] = s;
  std::set<std::string> seen;
  for (auto& f : s->fields) {
    if (f->type.base == ast::BaseType::Void)
      error(DiagId::err_void_variable, f->name_range, {f->name});
    if (!seen.insert(f->name).second) error(DiagId::err_redefinition, f->name_range, {f->name});
  }
}

// OSL warns (and carries on) when a shader parameter takes the name of a function declared at
// file scope, a builtin or a closure: calls by that name inside still reach the function.
// Function parameters may take such names silently, as in oslc.
void Sema::check_param_name(const ast::VarDecl* p, bool from_stdlib) {
  if (p->name.empty() || from_stdlib) return;
  const ast::FunctionDecl* user = nullptr;
  if (auto it = scopes_.front().funcs.find(p->name); it != scopes_.front().funcs.end())
    if (!it->second.empty()) user = it->second.front();
  bool is_closure = std::any_of(opts_.closures.begin(), opts_.closures.end(),
                                [&](const registry::ClosureEntry& c) { return p->name == c.name; });
  if (!user && builtins().lookup(p->name).empty() && !is_closure) return;
  error(DiagId::warn_param_hides_function, p->name_range, {p->name});
  if (user && !user->from_stdlib) error(DiagId::note_previous_decl, user->name_range);
}

void Sema::function_decl(ast::FunctionDecl* f) {
  for (auto& p : f->params) {
    p->writable = p->is_output;
    if (p->type.base == ast::BaseType::Void)
      error(DiagId::err_void_variable, p->name_range, {p->name});
  }
  if (f->name.rfind("__operator__", 0) == 0) {
    bool has_struct = false;
    for (auto& p : f->params) has_struct |= p->type.base == ast::BaseType::Struct;
    if (!has_struct) error(DiagId::err_operator_not_struct, f->name_range, {f->name});
  }
  metadata(f->metadata);
  declare_function(f); // before the body: a recursive call then resolves, and is reported
  if (!f->body) return;
  functions_.push_back(f);
  int loops = loop_depth_;
  loop_depth_ = 0;
  push_scope();
  for (auto& p : f->params) declare_var(p.get());
  compound(f->body.get(), false);
  pop_scope();
  loop_depth_ = loops;
  functions_.pop_back();
  if (!f->return_type.is_void() && !f->return_type.is_error() && !has_return(f->body.get()))
    error(DiagId::err_missing_return, f->name_range, {f->name});
}

void Sema::shader_decl(ast::ShaderDecl* s) {
  if (shader_) {
    error(DiagId::err_shader_redefinition, s->name_range, {shader_->name});
    return;
  }
  shader_ = s;
  metadata(s->metadata);
  // The parameters' and the body's scopes: for functions, one overload scope with the file's.
  push_scope();
  scopes_.back().file_level = true;
  scopes_.back().shader_level = !s->from_stdlib;
  for (auto& p : s->params) {
    check_param_name(p.get(), s->from_stdlib);
    var_decl(p.get()); // a default may use globals and earlier parameters
    metadata(p->metadata);
  }
  if (s->body) {
    push_scope();
    scopes_.back().file_level = true;
    scopes_.back().shader_level = !s->from_stdlib;
    compound(s->body.get(), false);
    pop_scope();
  }
  pop_scope();
}

// Variable (local or shader parameter): type, initialiser converted to the type, declaration.
void Sema::var_decl(ast::VarDecl* v) {
  if (v->type.base == ast::BaseType::Void) {
    error(DiagId::err_void_variable, v->name_range, {v->name});
    v->type = t_error();
  }
  if (v->init) {
    if (v->init->kind == ast::ExprKind::InitList) {
      init_list(v->init, v->type);
      // A local `float a[] = {...}` takes the list's length; a shader parameter stays unsized
      // (an instance value of another length may replace its default).
      if (v->type.arraylen < 0 && v->init->type.is_array() &&
          v->storage != ast::Storage::ShaderParam)
        v->type.arraylen = v->init->type.arraylen;
    } else {
      expr(v->init, &v->type);
      convert_assign(v->init, v->type, v->name);
    }
  }
  if (v->type.arraylen < 0 && v->storage == ast::Storage::Local) {
    error(DiagId::err_array_size, v->name_range);
    v->type.arraylen = 1;
  }
  declare_var(v);
}

namespace {
// A metadata value: literals and what lowering folds of them (casts, negation, arithmetic,
// constructors, `{...}`).
bool constant_expr(const ast::Expr* e) {
  switch (e->kind) {
  case ast::ExprKind::IntLit:
  case ast::ExprKind::FloatLit:
  case ast::ExprKind::StringLit:
    return true;
  case ast::ExprKind::Unary:
    return constant_expr(static_cast<const ast::UnaryExpr*>(e)->operand.get());
  case ast::ExprKind::Cast:
    return constant_expr(static_cast<const ast::CastExpr*>(e)->operand.get());
  case ast::ExprKind::Binary: { // `1.0 / 3.0`, which oslc folds
    auto* b = static_cast<const ast::BinaryExpr*>(e);
    return constant_expr(b->lhs.get()) && constant_expr(b->rhs.get());
  }
  case ast::ExprKind::InitList:
    for (auto& x : static_cast<const ast::InitListExpr*>(e)->elems)
      if (!constant_expr(x.get())) return false;
    return true;
  case ast::ExprKind::Construct:
    for (auto& x : static_cast<const ast::ConstructExpr*>(e)->args)
      if (!constant_expr(x.get())) return false;
    return true;
  default:
    return false;
  }
}
} // namespace

// Metadata values must be constants of the declared type.
void Sema::metadata(ast::Metadata& md) {
  for (auto& m : md) {
    if (!m.value) continue;
    if (!constant_expr(m.value.get())) {
      error(DiagId::err_metadata_not_const, m.value->range, {m.name});
      continue;
    }
    if (m.value->kind == ast::ExprKind::InitList) {
      init_list(m.value, m.type);
      if (m.type.arraylen < 0 && m.value->type.is_array()) m.type.arraylen = m.value->type.arraylen;
    } else {
      expr(m.value, &m.type);
      convert(m.value, m.type);
    }
  }
}

// True if the statement contains a `return` (nested function definitions excluded); a
// `return;` without a value in a non-void function is reported where it is.
bool Sema::has_return(const ast::Stmt* s) const {
  if (!s) return false;
  switch (s->kind) {
  case ast::StmtKind::Return:
    return true;
  case ast::StmtKind::Compound:
    for (auto& c : static_cast<const ast::CompoundStmt*>(s)->stmts)
      if (has_return(c.get())) return true;
    return false;
  case ast::StmtKind::If: {
    auto* i = static_cast<const ast::IfStmt*>(s);
    return has_return(i->then_stmt.get()) || has_return(i->else_stmt.get());
  }
  case ast::StmtKind::While:
    return has_return(static_cast<const ast::WhileStmt*>(s)->body.get());
  case ast::StmtKind::DoWhile:
    return has_return(static_cast<const ast::DoWhileStmt*>(s)->body.get());
  case ast::StmtKind::For:
    return has_return(static_cast<const ast::ForStmt*>(s)->body.get());
  default:
    return false;
  }
}

// Calls resolved to a prototype that a later definition supplied go to the definition.
void Sema::resolve_prototypes() {
  auto final_decl = [&](ast::FunctionDecl* f) {
    for (int guard = 0; guard < 100 && defined_by_.count(f); ++guard) f = defined_by_[f];
    return f;
  };
  for (auto* c : user_calls_) c->callee.function = final_decl(c->callee.function);
  for (auto& e : edges_) e.callee = final_decl(e.callee);
}

// No recursion: report every call that lies on a cycle of the call graph.
void Sema::check_recursion() {
  std::unordered_map<ast::FunctionDecl*, std::vector<ast::FunctionDecl*>> graph;
  for (auto& e : edges_) graph[e.caller].push_back(e.callee);
  auto reaches = [&](ast::FunctionDecl* from, ast::FunctionDecl* to) {
    std::set<ast::FunctionDecl*> seen;
    std::vector<ast::FunctionDecl*> work{from};
    while (!work.empty()) {
      auto* f = work.back();
      work.pop_back();
      if (f == to) return true;
      if (!seen.insert(f).second) continue;
      for (auto* g : graph[f]) work.push_back(g);
    }
    return false;
  };
  for (auto& e : edges_)
    if (reaches(e.callee, e.caller)) error(DiagId::err_recursion, e.where, {e.callee->name});
}

} // namespace lobe::sema

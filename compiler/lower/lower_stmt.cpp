// Lowering of statements (structured control flow into br/cbr) and calls: user functions are
// inlined, builtins become library opcodes (written operands first), closures `closure` ops.
#include "lower/lowerer.h"

#include "closure_registry.h"
#include "ir/edit.h"
#include "ir/opcodes.h"
#include "sema/builtins.h"

#include <algorithm>
#include <bit>

namespace lobe::lower {

using S = ast::StmtKind;

void Lowerer::stmt(const ast::Stmt* s) {
  if (!s) return;
  const ast::Node* saved = where_;
  where_ = s;
  switch (s->kind) {
  case S::Compound:
    for (const auto& x : static_cast<const ast::CompoundStmt*>(s)->stmts) stmt(x.get());
    break;
  case S::Expr: {
    const ast::Expr* e = static_cast<const ast::ExprStmt*>(s)->expr.get();
    if (e->type.base == ast::BaseType::Struct)
      rvalue_flat(e);
    else
      rvalue(e);
    break;
  }
  case S::Decl:
    for (const auto& d : static_cast<const ast::DeclStmt*>(s)->decls) {
      if (d->kind != ast::DeclKind::Var) continue; // nested functions inline at their calls
      auto* v = static_cast<const ast::VarDecl*>(d.get());
      std::vector<LRef> dst;
      for (int sym : declare(v, ir::SymKind::Local)) dst.push_back(LRef{sym});
      if (v->init) store_init(dst, v->type, v->init.get());
    }
    break;
  case S::If: {
    auto* i = static_cast<const ast::IfStmt*>(s);
    int j = emit(ir::Opcode::Cbr, {rvalue(i->cond.get())}, 0, s, {-1, -1});
    sh_.ops[size_t(j)].jumps[0] = here();
    stmt(i->then_stmt.get());
    int skip = i->else_stmt ? emit(ir::Opcode::Br, {}, 0, s, {-1}) : -1;
    sh_.ops[size_t(j)].jumps[1] = here();
    if (i->else_stmt) {
      stmt(i->else_stmt.get());
      sh_.ops[size_t(skip)].jumps[0] = here();
    }
    break;
  }
  case S::While:
  case S::For: {
    const ast::Expr* cond = nullptr;
    const ast::Expr* step = nullptr;
    const ast::Stmt* body = nullptr;
    if (s->kind == S::While) {
      auto* w = static_cast<const ast::WhileStmt*>(s);
      cond = w->cond.get(), body = w->body.get();
    } else {
      auto* f = static_cast<const ast::ForStmt*>(s);
      stmt(f->init.get());
      cond = f->cond.get(), step = f->step.get(), body = f->body.get();
    }
    int top = here();
    int j = cond ? emit(ir::Opcode::Cbr, {rvalue(cond)}, 0, s, {-1, -1}) : -1;
    if (j >= 0) sh_.ops[size_t(j)].jumps[0] = here();
    loops_.push_back({});
    stmt(body);
    int cont = here();
    if (step) rvalue(step);
    emit(ir::Opcode::Br, {}, 0, s, {top});
    int end = here();
    if (j >= 0) sh_.ops[size_t(j)].jumps[1] = end;
    patch(loops_.back().continues, cont);
    patch(loops_.back().breaks, end);
    loops_.pop_back();
    break;
  }
  case S::DoWhile: {
    auto* d = static_cast<const ast::DoWhileStmt*>(s);
    int top = here();
    loops_.push_back({});
    stmt(d->body.get());
    int cont = here();
    int j = emit(ir::Opcode::Cbr, {rvalue(d->cond.get())}, 0, s, {top, -1});
    int end = here();
    sh_.ops[size_t(j)].jumps[1] = end;
    patch(loops_.back().continues, cont);
    patch(loops_.back().breaks, end);
    loops_.pop_back();
    break;
  }
  case S::Break:
  case S::Continue:
    if (loops_.empty()) {
      error(s, diag::DiagId::err_lower_break_outside_loop);
      break;
    }
    (s->kind == S::Break ? loops_.back().breaks : loops_.back().continues)
        .push_back(emit(ir::Opcode::Br, {}, 0, s, {-1}));
    break;
  case S::Return: {
    auto* r = static_cast<const ast::ReturnStmt*>(s);
    if (inlines_.empty()) {
      emit(ir::Opcode::Exit, {}, 0, s);
      break;
    }
    std::vector<int> result = inlines_.back().result;
    if (r->value && r->value->type.base == ast::BaseType::Struct) {
      std::vector<int> v = rvalue_flat(r->value.get());
      for (size_t i = 0; i < v.size() && i < result.size(); ++i) store(LRef{result[i]}, v[i], s);
    } else if (r->value && !result.empty()) {
      store(LRef{result[0]}, rvalue(r->value.get(), result[0]), s);
    }
    int br = emit(ir::Opcode::Br, {}, 0, s, {-1});
    sh_.ops[size_t(br)].osl_return = true;
    inlines_.back().returns.push_back(br);
    break;
  }
  case S::Empty:
    break;
  }
  where_ = saved;
}

std::vector<int> Lowerer::call_user(const ast::FunctionDecl* f,
                                    const std::vector<const ast::Expr*>& args,
                                    const ast::Node* where, int hint) {
  // As oslc 1.13: a call of a void function without a body does nothing; of a non-void one,
  // it is an error at the call (oslc reports it only where the function is called).
  if (f && !f->body && f->return_type.is_void()) return {};
  if (!f || !f->body) {
    error(where, diag::DiagId::err_lower_no_body, {f ? f->name : std::string("?")});
    return {};
  }
  // Evaluate the arguments first, then bind them (an argument may call the same function).
  std::vector<std::vector<int>> bound;
  std::vector<std::pair<LRef, int>> copy_back;
  for (size_t i = 0; i < f->params.size() && i < args.size(); ++i) {
    const ast::VarDecl* p = f->params[i].get();
    std::vector<int> syms;
    // A non-output parameter the body writes (OSL allows it, with a warning) aliases the
    // caller's variable as an output one does (a shading global too: OSL then writes even u);
    // a constant or an expression is copied, so that the write stays inside the call. An
    // output argument that is no variable (`x + 1`) goes to a temporary, as oslc writes it.
    bool by_ref = p->is_output || (p->written && p->type.base != ast::BaseType::Struct);
    if (by_ref && !args[i]->lvalue && p->type.base != ast::BaseType::Struct) {
      syms = {scratch_copy(args[i], where)};
    } else if (by_ref) {
      // Another triple kind (a point for `output color`) goes through a temporary of the
      // parameter's type, so the body's operations see the type it declares.
      bool retype = args[i]->type.is_triple() && args[i]->type.base != p->type.base;
      for (const LRef& r : lvalue(args[i])) {
        ir::SymKind k = sh_.symbols[r.sym].kind;
        if (!p->is_output && k == ir::SymKind::Const) {
          int v = load(r, where);
          int t = temp(sh_.symbols[v].type);
          emit(ir::Opcode::Assign, {t, v}, 1, where);
          syms.push_back(t);
          continue;
        }
        if (r.whole() && !retype) {
          syms.push_back(r.sym); // alias the caller's variable
          continue;
        }
        int v = load(r, where);
        int t = temp(retype ? irtype(p->type, where) : sh_.symbols[v].type);
        emit(ir::Opcode::Assign, {t, v}, 1, where);
        syms.push_back(t);
        copy_back.push_back({r, t});
      }
    } else if (p->type.base == ast::BaseType::Struct) {
      syms = rvalue_flat(args[i]);
    } else {
      syms = {rvalue(args[i])};
    }
    bound.push_back(std::move(syms));
  }
  std::vector<std::pair<const ast::VarDecl*, std::optional<std::vector<int>>>> saved;
  for (size_t i = 0; i < bound.size(); ++i) {
    const ast::VarDecl* p = f->params[i].get();
    auto it = vars_.find(p);
    saved.push_back({p, it == vars_.end() ? std::nullopt : std::optional(it->second)});
    vars_[p] = bound[i];
  }
  Inline in;
  in.function = !f->osl_builtin;
  if (!f->return_type.is_void()) {
    std::vector<Leaf> ls = leaves(f->return_type, f);
    // Into `hint` even when arguments are written back after the body, as oslc orders them:
    // `c = f(c[0])` stores the result, then the output argument into c[0]; `i = f(a[i])`
    // writes a[i] of the new i (OSL 1.13.12, tests/shade/call_into_osl.osl).
    for (const Leaf& l : ls)
      in.result.push_back(ls.size() == 1 ? pick(hint, irtype(l.type, f)) : temp(irtype(l.type, f)));
  }
  inlines_.push_back(in);
  size_t body_begins = sh_.ops.size();
  stmt(f->body.get());
  if (in.function && sh_.ops.size() > body_begins)
    ++sh_.ops[body_begins].calls_begin;
  else if (in.function)
    ++pending_calls_; // an empty body: OSL's functioncall op still counts, before the next op
  // The body's last op a return's jump: the last statement's return, no op of OSL's.
  if (sh_.ops.size() > body_begins && sh_.ops.back().opcode == ir::Opcode::Br)
    sh_.ops.back().osl_return = false;
  int end = here();
  patch(inlines_.back().returns, end);
  std::vector<int> result = inlines_.back().result;
  inlines_.pop_back();
  for (const auto& [r, t] : copy_back) store(r, t, where);
  for (auto& [p, old] : saved) {
    if (old)
      vars_[p] = *old;
    else
      vars_.erase(p);
  }
  return result;
}

// A temporary holding the value of `e`, an `output` argument that is no variable (`x + 1`):
// the callee writes it and the value is dropped.
int Lowerer::scratch_copy(const ast::Expr* e, const ast::Node* where) {
  int v = rvalue(e);
  ir::Type t = sh_.symbols[size_t(v)].type;
  int s = temp(t);
  emit(t.is_array() ? ir::Opcode::ArrayCopy : ir::Opcode::Assign, {s, v}, 1, where);
  return s;
}

// Builtins lowered to arithmetic instead of an opcode of their own: radians, degrees, and
// arraylength of a sized array (a constant; struct arrays have no single symbol to ask).
// Returns -2 when `c` is not one of them.
int Lowerer::call_arith(const ast::CallExpr* c, int hint) {
  if ((c->name == "radians" || c->name == "degrees") && c->args.size() == 1) {
    // OSL's constants, divided in float: 180 / float(pi) = 57.2957764, float(pi) / 180.
    constexpr float kPi = float(3.14159265358979323846);
    float k = c->name == "radians" ? kPi / 180.0f : 180.0f / kPi;
    int x = rvalue(c->args[0].get());
    int r = pick(hint, irtype(c->type, c));
    emit(ir::Opcode::Mul, {r, x, ir::intern_float(sh_, k)}, 1, c);
    return r;
  }
  if (c->name == "arraylength" && c->args.size() == 1 && c->args[0]->type.arraylen > 0)
    return ir::intern_int(sh_, c->args[0]->type.arraylen);
  if (c->name == "mod" && c->args.size() == 2) return floor_mod(c, hint);
  return -2;
}

// OSL's mod(a, b) is a - b*floor(a/b) (the result has the sign of b), unlike `%` and fmod()
// (the IR's `mod`, the sign of a), from div/floor/mul/sub. For ints stdosl.h's a - b*(int)
// floor(a/b) floors the truncating quotient as a float, so a quotient past 2^24 rounds to a
// float first (mod(2147483647, 3) is -65, as OSL prints it; C's remainder is 1), and
// mod(a, 0) = a.
int Lowerer::floor_mod(const ast::CallExpr* c, int hint) {
  ir::Type t = irtype(c->type, c);
  int a = rvalue(c->args[0].get());
  int b = rvalue(c->args[1].get());
  int r = temp(t);
  emit(ir::Opcode::Div, {r, a, b}, 1, c);
  if (t.base == ir::BaseType::Int) { // through a float and back (its floor is itself)
    int f = temp(ir::Type{ir::BaseType::Float});
    emit(ir::Opcode::Assign, {f, r}, 1, c);
    emit(ir::Opcode::Assign, {r, f}, 1, c);
  } else {
    emit(ir::Opcode::Floor, {r, r}, 1, c);
  }
  emit(ir::Opcode::Mul, {r, r, b}, 1, c);
  int out = pick(hint, t);
  emit(ir::Opcode::Sub, {out, a, r}, 1, c);
  return out;
}

// The operand a call writes for the lvalue `e`: the variable itself when `e` names it whole,
// else a temporary (listed in `copy_back`, stored into `e` after the call) that starts as the
// element's or component's value, so a call that writes nothing (a failed gettextureinfo or
// getattribute) leaves it as it was, as OSL's by-reference argument does.
int Lowerer::written_operand(const ast::Expr* e, const ast::Node* where,
                             std::vector<std::pair<LRef, int>>& copy_back) {
  LRef r = lvalue(e)[0];
  if (r.whole()) return r.sym;
  int s = temp(irtype(e->type, where));
  int cur = load(r, where, s);
  if (cur != s)
    emit(sh_.symbols[size_t(s)].type.is_array() ? ir::Opcode::ArrayCopy : ir::Opcode::Assign,
         {s, cur}, 1, where);
  copy_back.push_back({r, s});
  return s;
}

// Builtins: `name [result] [outputs...] inputs... ["kw" value]...`: written operands first
// (the result, then the `output` arguments in call order), then the other arguments in call
// order, then keyword pairs. Which arguments are outputs comes from the builtin table's
// signature, or a [[ builtin = 1 ]] prototype's `output` params; without either, from the
// opcode table's written mask (the last arguments, OSL's convention).
int Lowerer::call_builtin(const ast::CallExpr* c, int hint) {
  if (c->name == "exit") {
    emit(ir::Opcode::Exit, {}, 0, c);
    return -1;
  }
  int arith = call_arith(c, hint);
  if (arith != -2) return arith;
  std::optional<ir::Opcode> code = ir::opcode_from_name(c->name);
  if (!code) {
    error(c, diag::DiagId::err_lower_no_opcode, {c->name});
    return -1;
  }
  bool returns = !c->type.is_void();
  size_t npos = c->num_positional < 0 ? c->args.size() : size_t(c->num_positional);
  std::vector<bool> is_out(npos, false);
  if (c->callee.kind == ast::CalleeKind::User && c->callee.function) {
    const auto& ps = c->callee.function->params;
    for (size_t i = 0; i < npos && i < ps.size(); ++i) is_out[i] = ps[i]->is_output;
  } else if (c->callee.builtin) {
    const auto& ps = c->callee.builtin->params;
    for (size_t i = 0; i < npos && i < ps.size(); ++i) is_out[i] = ps[i].output;
  } else {
    size_t nout =
        std::min(npos, size_t(std::popcount(ir::info(*code).written)) - (returns ? 1 : 0));
    for (size_t i = npos - nout; i < npos; ++i) is_out[i] = true;
  }
  std::vector<int> args;
  uint32_t mask = 0;
  if (returns) {
    args.push_back(pick(hint, irtype(c->type, c)));
    mask |= 1;
  }
  std::vector<std::pair<LRef, int>> copy_back;
  for (size_t i = 0; i < npos; ++i) {
    if (!is_out[i]) continue;
    mask |= 1u << args.size();
    if (!c->args[i]->lvalue) { // oslc writes such an argument to a temporary
      args.push_back(scratch_copy(c->args[i].get(), c));
      continue;
    }
    args.push_back(written_operand(c->args[i].get(), c, copy_back));
  }
  for (size_t i = 0; i < npos; ++i)
    if (!is_out[i]) args.push_back(rvalue(c->args[i].get()));
  // A texture lookup's "alpha" keyword names a variable the lookup writes (the channel after
  // the result's), and so does "errormessage" (why it failed, or "").
  bool texture = *code == ir::Opcode::Texture || *code == ir::Opcode::Texture3d ||
                 *code == ir::Opcode::Environment;
  for (const ast::KeywordArg& k : c->keywords) {
    args.push_back(ir::intern_string(sh_, k.name));
    if (texture && (k.name == "alpha" || k.name == "errormessage") && k.value->lvalue &&
        args.size() < 32) {
      mask |= 1u << args.size();
      args.push_back(written_operand(k.value, c, copy_back));
      continue;
    }
    args.push_back(rvalue(k.value));
  }
  emit(*code, args, mask, c);
  for (const auto& [r, s] : copy_back) store(r, s, c);
  return returns ? args[0] : -1;
}

// `closure` (a registry entry, by key) or `declared_closure` (one the shader declares with
// [[ int builtin = 1 ]], by name, then its number of positional arguments: its operands'
// types are its layout).
int Lowerer::call_closure(const ast::CallExpr* c, const std::string& key, int hint,
                          ir::Opcode opcode) {
  int dst = pick(hint, ir::Type{ir::BaseType::Closure});
  std::vector<int> args = {dst, ir::intern_string(sh_, key)};
  size_t npos = c->num_positional < 0 ? c->args.size() : size_t(c->num_positional);
  if (opcode == ir::Opcode::DeclaredClosure) args.push_back(ir::intern_int(sh_, int(npos)));
  for (size_t i = 0; i < npos; ++i) args.push_back(rvalue(c->args[i].get()));
  for (const ast::KeywordArg& k : c->keywords) {
    args.push_back(ir::intern_string(sh_, k.name));
    args.push_back(rvalue(k.value));
  }
  emit(opcode, args, 1, c);
  return dst;
}

int Lowerer::call(const ast::CallExpr* c, int hint) {
  switch (c->callee.kind) {
  case ast::CalleeKind::Closure:
    return call_closure(c, c->callee.closure->key, hint);
  case ast::CalleeKind::Builtin:
    return call_builtin(c, hint);
  case ast::CalleeKind::User: {
    const ast::FunctionDecl* f = c->callee.function;
    if (f && !f->body) {
      if (f->return_type.is_closure())
        return call_closure(c, f->name, hint, ir::Opcode::DeclaredClosure);
      // A prototype of a builtin (with [[ int builtin = 1 ]] or of an IR opcode's name) is the
      // builtin; any other function without a body has nothing to run (call_user says so).
      if (f->is_builtin || ir::opcode_from_name(c->name)) return call_builtin(c, hint);
    }
    std::vector<const ast::Expr*> args;
    for (const auto& a : c->args) args.push_back(a.get());
    std::vector<int> r = call_user(f, args, c, hint);
    return r.empty() ? -1 : r[0];
  }
  default:
    error(c, diag::DiagId::err_lower_internal, {"unresolved call to '" + c->name + "'"});
    return -1;
  }
}

} // namespace lobe::lower

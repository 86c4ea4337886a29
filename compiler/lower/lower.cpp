// Lowering driver: symbols and their names, op emission (with source locations and useparam
// marks), shader parameters with their defaults and metadata, constant expressions.
#include "lower/lowerer.h"

#include "diag/source_manager.h"
#include "ir/edit.h"
#include "ir/opcodes.h"
#include "passes/consteval.h"
#include "passes/constfold.h"
#include "passes/dce.h"
#include "passes/derivs.h"

#include <algorithm>
#include <utility>

namespace lobe::lower {

using ir::SymKind;

ir::SourceLoc Lowerer::loc(const ast::Node* where) const {
  ir::SourceLoc l;
  if (!where || !where->range.valid() || !tu_.sources) return l;
  diag::PresumedLoc p = tu_.sources->presumed(where->range.begin);
  if (!p.valid()) return l;
  l.file = p.file;
  l.line = p.line;
  l.column = p.column;
  return l;
}

void Lowerer::error(const ast::Node* where, diag::DiagId id, std::vector<std::string> args) {
  const ast::Node* at_node = where ? where : where_;
  // One caret, at the start of the construct (as lowering errors have always been shown).
  diags_.report(id, at_node ? diag::SourceRange(at_node->range.begin) : diag::SourceRange(),
                std::move(args));
  ++errors_;
}

ir::Type Lowerer::irtype(const ast::Type& t, const ast::Node* where) {
  using B = ast::BaseType;
  ir::Type r;
  r.arraylen = t.arraylen;
  switch (t.base) {
  case B::Int:
    r.base = ir::BaseType::Int;
    break;
  case B::Float:
    r.base = ir::BaseType::Float;
    break;
  case B::Color:
    r.base = ir::BaseType::Color;
    break;
  case B::Point:
    r.base = ir::BaseType::Point;
    break;
  case B::Vector:
    r.base = ir::BaseType::Vector;
    break;
  case B::Normal:
    r.base = ir::BaseType::Normal;
    break;
  case B::Matrix:
    r.base = ir::BaseType::Matrix;
    break;
  case B::String:
    r.base = ir::BaseType::String;
    break;
  case B::Closure:
    r.base = ir::BaseType::Closure;
    break;
  default:
    error(where, diag::DiagId::err_lower_internal, {"no IR type for this value"});
    break;
  }
  return r;
}

// Flattens a (possibly array-of-) struct type into its leaves, depth first in field order.
// In an array of n structs each leaf holds the n structs' fields one after the other: a field
// that is itself an array of m gives an array of n*m (see LRef::slice).
std::vector<Leaf> Lowerer::leaves(const ast::Type& t, const ast::Node* where) {
  if (t.base != ast::BaseType::Struct) return {Leaf{"", t}};
  std::vector<Leaf> out;
  for (const auto& f : t.strct->fields) {
    for (Leaf l : leaves(f->type, f.get())) {
      if (t.arraylen > 0)
        l.type.arraylen = t.arraylen * std::max(1, l.type.arraylen);
      else if (t.arraylen < 0) {
        if (l.type.arraylen != 0) error(where, diag::DiagId::err_lower_unsized_struct_array);
        l.type.arraylen = -1;
      }
      out.push_back(Leaf{"." + f->name + l.suffix, l.type});
    }
  }
  return out;
}

int Lowerer::new_symbol(const std::string& name, const ir::Type& t, SymKind k,
                        const ast::Node* where) {
  std::string n = name;
  int& count = name_counts_[name];
  if (count++ > 0 || sh_.find_symbol(n) >= 0) {
    do n = name + "~" + std::to_string(count++);
    while (sh_.find_symbol(n) >= 0);
  }
  ir::Symbol s;
  s.name = n;
  s.type = t;
  s.kind = k;
  s.loc = loc(where);
  sh_.symbols.push_back(std::move(s));
  return int(sh_.symbols.size()) - 1;
}

// Every temporary is a symbol of its own, never reused for another expression: derivatives are
// tracked per symbol (passes/derivs.h), so a temporary shared by an expression that needs
// derivatives and one that does not would give the second derivatives too — and change its
// value where OSL's derivative forms compute differently (pow: u * u^(v-1)). oslc gives each
// temporary its own symbol as well. LLVM keeps them in registers.
int Lowerer::temp(const ir::Type& t) {
  return new_symbol("$t" + std::to_string(next_temp_++), t, SymKind::Temp, nullptr);
}

int Lowerer::here() {
  used_params_.clear();
  return int(sh_.ops.size());
}

void Lowerer::patch(const std::vector<int>& ops, int target) {
  for (int op : ops)
    for (int& j : sh_.ops[op].jumps)
      if (j < 0) {
        j = target;
        break;
      }
}

// Appends an op; before it, a `useparam` naming the parameters it reads that this basic block
// has not announced yet. Returns the op's index. Unpatched jump targets are -1.
int Lowerer::emit(ir::Opcode opcode, std::vector<int> args, uint32_t written,
                  const ast::Node* where, std::vector<int> jumps) {
  ir::Op op;
  op.opcode = opcode;
  op.args = std::move(args);
  op.written_mask = written;
  op.jumps = std::move(jumps);
  op.loc = loc(where ? where : where_);
  op.in_function =
      std::any_of(inlines_.begin(), inlines_.end(), [](const Inline& in) { return in.function; });
  op.calls_begin = std::exchange(pending_calls_, 0);
  std::vector<int> reads;
  for (size_t i = 0; i < op.args.size(); ++i) {
    int s = op.args[i];
    SymKind k = sh_.symbols[s].kind;
    // isconnected(p) asks about p's connections, not its value: it does not use p (OSL runs no
    // upstream layer for it).
    if ((k == SymKind::Param || k == SymKind::OutputParam) && ir::op_reads(op, int(i)) &&
        opcode != ir::Opcode::IsConnected && used_params_.insert(s).second)
      reads.push_back(s);
  }
  if (!reads.empty()) {
    ir::Op u;
    u.opcode = ir::Opcode::UseParam;
    u.args = reads;
    u.loc = op.loc;
    sh_.ops.push_back(std::move(u));
  }
  sh_.ops.push_back(std::move(op));
  if (ir::is_jump(opcode)) used_params_.clear();
  return int(sh_.ops.size()) - 1;
}

int Lowerer::global(const ast::VarDecl* v) {
  auto it = vars_.find(v);
  if (it != vars_.end()) return it->second[0];
  // A global's symbol must carry the global's own name (the runtime binds it by name): a
  // local that took the name first (`vector v` in an inlined function) is renamed.
  int s = sh_.find_symbol(v->name);
  if (s >= 0 && sh_.symbols[size_t(s)].kind == SymKind::Local) {
    std::string n;
    int& count = name_counts_[v->name];
    do n = v->name + "~" + std::to_string(count++);
    while (sh_.find_symbol(n) >= 0);
    sh_.symbols[size_t(s)].name = n;
    s = -1;
  }
  if (s < 0 || sh_.symbols[size_t(s)].kind != SymKind::Global) {
    bool free_name = s < 0;
    s = new_symbol(v->name, irtype(v->type, v), SymKind::Global, nullptr);
    if (free_name) sh_.symbols[size_t(s)].name = v->name;
  }
  vars_[v] = {s};
  return s;
}

std::vector<int> Lowerer::declare(const ast::VarDecl* v, SymKind k) {
  std::vector<int> syms;
  for (const Leaf& l : leaves(v->type, v)) {
    int s = new_symbol(v->name + l.suffix, irtype(l.type, v), k, v);
    if (v->type.base == ast::BaseType::Struct) sh_.symbols[s].struct_name = v->type.strct->name;
    syms.push_back(s);
  }
  vars_[v] = syms;
  return syms;
}

// The value of a constant expression (literals, casts, negation, arithmetic and comparisons
// on constants, constructors without a space name, initialiser lists), converted to `t`.
bool Lowerer::const_values(const ast::Expr* e, const ir::Type& t,
                           std::vector<ir::ConstValue>& out) {
  using K = ast::ExprKind;
  std::vector<ir::ConstValue> v;
  ir::Type et = irtype(e->type, e);
  switch (e->kind) {
  case K::IntLit:
    v.resize(1);
    v[0].i = static_cast<const ast::IntLit*>(e)->value;
    break;
  case K::FloatLit:
    v.resize(1);
    v[0].f = static_cast<const ast::FloatLit*>(e)->value;
    break;
  case K::StringLit:
    v.resize(1);
    v[0].s = static_cast<const ast::StringLit*>(e)->value;
    break;
  case K::Cast: {
    auto* c = static_cast<const ast::CastExpr*>(e);
    ir::Type ot = irtype(c->operand->type, e);
    if (!const_values(c->operand.get(), ot, v)) return false;
    if (et.base == ir::BaseType::Matrix && !et.is_array() && !ot.is_array() &&
        (ot.base == ir::BaseType::Int || ot.base == ir::BaseType::Float)) {
      // A number as a matrix: the diagonal matrix (`matrix m = 1` is the identity).
      float d = ot.base == ir::BaseType::Int ? float(v[0].i) : v[0].f;
      v.assign(16, ir::ConstValue{});
      for (int i = 0; i < 4; ++i) v[size_t(i * 5)].f = d;
      break;
    }
    auto cv = passes::convert_const(ot, v, et);
    if (!cv) return false;
    v = *cv;
    break;
  }
  case K::Unary: {
    auto* u = static_cast<const ast::UnaryExpr*>(e);
    if (u->overload || u->op == ast::UnaryOp::Not) return false;
    if (!const_values(u->operand.get(), et, v)) return false;
    if (u->op == ast::UnaryOp::Plus) break;
    auto r = passes::evaluate(u->op == ast::UnaryOp::Neg ? ir::Opcode::Neg : ir::Opcode::Compl, et,
                              {{et, &v}});
    if (!r) return false;
    v = *r;
    break;
  }
  case K::Binary: {
    auto* b = static_cast<const ast::BinaryExpr*>(e);
    ir::Opcode op = binop_opcode(b->op);
    if (b->overload || op == ir::Opcode::Nop) return false;
    ir::Type lt = irtype(b->lhs->type, e), rt = irtype(b->rhs->type, e);
    std::vector<ir::ConstValue> lv, rv;
    if (lt.is_array() || rt.is_array() || !const_values(b->lhs.get(), lt, lv) ||
        !const_values(b->rhs.get(), rt, rv))
      return false;
    auto r = passes::evaluate(op, et, {{lt, &lv}, {rt, &rv}});
    if (!r) return false;
    v = *r;
    break;
  }
  case K::Construct: {
    auto* c = static_cast<const ast::ConstructExpr*>(e);
    if (c->has_space) return false;
    for (const auto& a : c->args) {
      std::vector<ir::ConstValue> av;
      if (!const_values(a.get(), ir::Type{ir::BaseType::Float}, av)) return false;
      v.insert(v.end(), av.begin(), av.end());
    }
    if (et.base == ir::BaseType::Matrix && v.size() == 1) {
      ir::ConstValue d = v[0];
      v.assign(16, ir::ConstValue{});
      for (int i = 0; i < 4; ++i) v[size_t(i * 5)] = d;
    } else if (v.size() == 1) {
      v.assign(size_t(et.components()), v[0]);
    }
    if (v.size() != size_t(et.components())) return false;
    break;
  }
  case K::InitList: {
    auto* l = static_cast<const ast::InitListExpr*>(e);
    if (!t.is_array()) return false;
    ir::Type elem = t;
    elem.arraylen = 0;
    for (const auto& x : l->elems) {
      std::vector<ir::ConstValue> xv;
      if (!const_values(x.get(), elem, xv)) return false;
      v.insert(v.end(), xv.begin(), xv.end());
    }
    // A sized array given fewer values than its length: the rest are zero (and "" for
    // strings), as oslc fills them (`float p[4] = {1}` is [1 0 0 0]).
    if (t.arraylen > 0 && v.size() < size_t(t.arraylen) * size_t(elem.components()))
      v.resize(size_t(t.arraylen) * size_t(elem.components()));
    out = v;
    return true;
  }
  default:
    return false;
  }
  if (et.is_array()) return false;
  auto conv = passes::convert_const(et, v, t);
  if (!conv) return false;
  out = *conv;
  return true;
}

} // namespace lobe::lower

// Implements fold_constants: one forward walk over the ops with a per-block map from symbol to
// the Const symbol holding its current value (cleared at jump targets, region starts and after
// jumps, where values from other paths could arrive), and, in the runtime's pass, the locals
// known in every block (once_assigned_constants).
#include "passes/constfold.h"
#include "ir/edit.h"
#include "ir/opcodes.h"
#include "passes/consteval.h"

#include <algorithm>
#include <climits>
#include <iterator>
#include <set>
#include <unordered_map>
#include <unordered_set>

namespace lobe::passes {

using namespace ir;

namespace {

class Folder {
public:
  Folder(Shader& sh, const EvalOptions& options, bool algebraic, bool late)
      : sh_(sh), options_(options), algebraic_(algebraic), late_(late) {}
  bool run();

private:
  bool is_const(int s) const { return sh_.symbols[s].kind == SymKind::Const; }
  bool is_closure(int s) const { return sh_.symbols[s].type == Type{BaseType::Closure}; }
  bool is_null(int s) const {
    return null_.count(s) || (is_const(s) && sh_.symbols[s].type == Type{BaseType::Int});
  }
  void substitute(Op& op);
  bool fold(Op& op);
  bool fold_pow(Op& op);
  bool fold_closure(Op& op);
  bool fold_algebraic(Op& op);
  bool fold_zero_operand(Op& op);
  int root(int s) const {
    auto it = alias_.find(s);
    return it == alias_.end() ? s : it->second;
  }
  void clear_block() { known_.clear(), null_.clear(), alias_.clear(); }
  void once_assigned_constants();
  bool all_zero(int s) const;
  void make_assign(Op& op, int dst, int src);
  void record(const Op& op);

  Shader& sh_;
  EvalOptions options_;
  bool algebraic_;
  std::unordered_map<int, int> known_; // symbol -> Const symbol with its value
  // Locals known everywhere they are read (algebraic_: once_assigned_constants()).
  std::unordered_map<int, int> fixed_;
  std::unordered_map<int, int> alias_; // symbol -> the symbol it was copied from (algebraic_)
  std::unordered_set<int> null_;       // closure symbols known to hold the null closure
  bool changed_ = false;
  bool late_; // pow(0, x) = 0 may fold (fold_constants' `late`)
};

void Folder::substitute(Op& op) {
  if (op.opcode == Opcode::UseParam || op.opcode == Opcode::IsConnected ||
      op.opcode == Opcode::IsConstant)
    return;
  for (size_t i = 0; i < op.args.size(); ++i) {
    if (op.writes(int(i))) continue;
    auto it = known_.find(op.args[i]);
    if (it == known_.end() && (it = fixed_.find(op.args[i])) == fixed_.end()) continue;
    op.args[i] = it->second;
    changed_ = true;
  }
}

bool Folder::all_zero(int s) const { return is_const(s) && const_all(sh_.symbols[s], 0); }

void Folder::make_assign(Op& op, int dst, int src) {
  op.opcode = Opcode::Assign;
  op.args = {dst, src};
  op.written_mask = 1;
  op.identity_copy = false;
  op.jumps.clear();
  changed_ = true;
}

// add/mul/neg on closures with a null operand or a zero weight.
bool Folder::fold_closure(Op& op) {
  int dst = op.args[0];
  if (op.opcode == Opcode::Add && op.args.size() == 3) {
    int a = op.args[1], b = op.args[2];
    if (is_null(a)) return make_assign(op, dst, b), true;
    if (is_null(b)) return make_assign(op, dst, a), true;
  } else if (op.opcode == Opcode::Mul && op.args.size() == 3) {
    int a = op.args[1], b = op.args[2];
    int k = is_closure(a) ? a : b, w = is_closure(a) ? b : a;
    if (is_null(k) || all_zero(w)) return make_assign(op, dst, intern_int(sh_, 0)), true;
  } else if (op.opcode == Opcode::Neg && op.args.size() == 2 && is_null(op.args[1])) {
    return make_assign(op, dst, intern_int(sh_, 0)), true;
  }
  return false;
}

// pow(x, k) of a varying x and a constant float k, as OSL's optimizer rewrites it: k = 2 is
// x * x (OSL 1.13.12 prints "inf 3.40282347e+38" for printf("%.9g %.9g", pow(x, 2), pow(x, 2 +
// z)) with x = 1e20 + floor(u) and z = floor(u), testshade -g 1 1), k = 0.5 is
// sqrt(x), -0.5 inversesqrt(x), 1/3 cbrt(x) (so pow(-8, 1.0/3) is -2 for a varying -8, while
// fully constant pow folds with pow's own rules, to 0). OSL 1.13.12 prints "pw -2 0 0" for
// printf("pw %g %g %g", pow(a, 1.0/3), pow(a, 0.5), pow(a, -0.5)) with a = -8 a lockgeom=0
// parameter (testshade at its default -O2; at -O0 it prints "pw 0 0 0", as Lobe does unfolded).
bool Folder::fold_pow(Op& op) {
  if (op.opcode != Opcode::Pow || op.args.size() != 3 || is_const(op.args[1]) ||
      !is_const(op.args[2]))
    return false;
  const Symbol& k = sh_.symbols[op.args[2]];
  if (k.type != Type{BaseType::Float} || k.init.size() != 1) return false;
  float e = k.init[0].f;
  if (e == 2.0f) { // x * x: a square that overflows is inf, where pow gives the largest float
    op.opcode = Opcode::Mul;
    op.args[2] = op.args[1];
    changed_ = true;
    return true;
  }
  std::optional<Opcode> fn = e == 0.5f               ? Opcode::Sqrt
                             : e == -0.5f            ? Opcode::InverseSqrt
                             : e == float(1.0 / 3.0) ? std::optional(Opcode::Cbrt)
                                                     : std::nullopt;
  if (!fn) return false;
  op.opcode = *fn;
  op.args.pop_back();
  changed_ = true;
  return true;
}

// OSL's runtime optimizer's identities, for a varying x and a constant all of whose components
// are 0 or 1: x * 0 = 0 * x = 0 (also for a constant x, and for matrices), x - x = 0, x + 0 = 0 + x
// = x - 0 = x * 1 = 1 * x = x / 1 = x. OSL 1.13.12, `testshade` at its default -O2, prints "0 0 0 0
// | -0 -0" for printf("%g %g %g %g | %g %g", nan * 0, 0 * nan, nan - nan, nan - y, nz + 0, nz * 1)
// with nan a varying NaN, y = nan and nz a varying -0 ("-nan -nan -nan -nan | 0 -0" at -O0, as the
// arithmetic computes).
bool Folder::fold_algebraic(Op& op) {
  if (!algebraic_ || op.args.size() != 3) return false;
  const Type& t = sh_.symbols[op.args[0]].type;
  bool matrix = t.base == BaseType::Matrix;
  if (t.is_array() ||
      !(t.base == BaseType::Float || t.base == BaseType::Int || t.is_triple() || matrix))
    return false;
  int a = op.args[1], b = op.args[2];
  Opcode o = op.opcode;
  // A product with an all-zero constant is +0, whatever the other factor, a constant too (OSL
  // 1.13.12 -O2 prints "0 0 0 | 0" for vector(-1, 2, -3) * 0 and -2.0 * 0; -0 at -O0) or a
  // matrix.
  if (o == Opcode::Mul && (all_zero(a) || all_zero(b)))
    return make_assign(op, op.args[0], intern_int(sh_, 0)), true;
  if (matrix) return false;
  if (o == Opcode::Sub && root(a) == root(b) && !is_const(a))
    return make_assign(op, op.args[0], intern_int(sh_, 0)), true;
  if (is_const(a) == is_const(b)) return false; // two constants fold as they compute
  int k = is_const(a) ? a : b, x = is_const(a) ? b : a;
  bool k_second = k == b;
  if (const_all(sh_.symbols[k], 0)) {
    if (o == Opcode::Mul) return make_assign(op, op.args[0], intern_int(sh_, 0)), true;
    if (o == Opcode::Add || (o == Opcode::Sub && k_second))
      return make_assign(op, op.args[0], x), op.identity_copy = true, true;
  } else if (const_all(sh_.symbols[k], 1)) {
    if (o == Opcode::Mul || (o == Opcode::Div && k_second))
      return make_assign(op, op.args[0], x), op.identity_copy = true, true;
  }
  return false;
}

// More of OSL's runtime optimizer's folds (-O2): pow(0, x) = 0 for any x still varying once
// nothing else folds (`late_`: OSL 1.13.12 prints 0 for pow(0.0, u - 0.5) at -O2, 1 at -O0 as
// its pow computes, and 1 for pow(0.0, z) with z = a - a: its z is 0 by then), and a dot product
// with an all-zero constant is 0 whatever the other vector holds (0 for dot(V, vector(0)) with a
// varying V holding an inf, where the arithmetic gives nan).
bool Folder::fold_zero_operand(Op& op) {
  if (!algebraic_ || op.args.size() != 3) return false;
  const Type& t = sh_.symbols[op.args[0]].type;
  if (t.is_array() || !(t.base == BaseType::Float || t.is_triple())) return false;
  int a = op.args[1], b = op.args[2];
  bool zero = (op.opcode == Opcode::Pow && late_ && all_zero(a) && !is_const(b)) ||
              (op.opcode == Opcode::Dot && (all_zero(a) || all_zero(b)));
  if (!zero) return false;
  make_assign(op, op.args[0], intern_int(sh_, 0));
  return true;
}

bool Folder::fold(Op& op) {
  if (op.opcode == Opcode::Cbr && !op.args.empty() && is_const(op.args[0]) &&
      op.jumps.size() == 2) {
    const Symbol& c = sh_.symbols[op.args[0]];
    bool taken = c.type.base == BaseType::Int ? c.init[0].i != 0 : c.init[0].f != 0.0f;
    op.opcode = Opcode::Br;
    op.jumps = {op.jumps[taken ? 0 : 1]};
    op.args.clear();
    op.written_mask = 0;
    changed_ = true;
    return true;
  }
  if (op.args.empty() || op.written_mask != 1 || is_const(op.args[0])) return false;
  if (is_closure(op.args[0])) return fold_closure(op);
  const ir::OpcodeInfo* info = &ir::info(op.opcode);
  if (!(info->flags & kPure)) return false;
  if (fold_pow(op)) return true;
  if (fold_algebraic(op)) return true;
  if (fold_zero_operand(op)) return true;
  std::vector<ConstArg> srcs;
  for (size_t i = 1; i < op.args.size(); ++i) {
    if (!is_const(op.args[i])) return false;
    const Symbol& s = sh_.symbols[op.args[i]];
    srcs.push_back({s.type, &s.init});
  }
  Type dt = sh_.symbols[op.args[0]].type;
  auto v = evaluate(op.opcode, dt, srcs, options_);
  if (!v) return false;
  int c = intern_const(sh_, dt, *v);
  if (op.opcode == Opcode::Assign && op.args[1] == c) return false;
  make_assign(op, op.args[0], c);
  return true;
}

// Updates the known values after `op` ran.
void Folder::record(const Op& op) {
  for (size_t i = 0; i < op.args.size(); ++i) {
    if (!op.writes(int(i))) continue;
    int w = op.args[i];
    known_.erase(w);
    null_.erase(w);
    if (alias_.empty()) continue;
    alias_.erase(w);
    for (auto it = alias_.begin(); it != alias_.end();) // copies of w no longer equal it
      it = it->second == w ? alias_.erase(it) : std::next(it);
  }
  if (algebraic_ && op.opcode == Opcode::Assign && op.args.size() == 2 && !is_const(op.args[1]) &&
      op.args[0] != op.args[1] && sh_.symbols[op.args[0]].type == sh_.symbols[op.args[1]].type &&
      !sh_.symbols[op.args[0]].type.is_array() && !is_closure(op.args[0]))
    alias_[op.args[0]] = root(op.args[1]);
  if (op.opcode != Opcode::Assign || op.args.size() != 2 || !is_const(op.args[1])) return;
  int dst = op.args[0], src = op.args[1];
  if (is_closure(dst)) {
    null_.insert(dst);
    return;
  }
  const Symbol& s = sh_.symbols[src];
  Type dt = sh_.symbols[dst].type;
  auto v = convert_const(s.type, s.init, dt);
  if (v && !dt.is_array()) known_[dst] = intern_const(sh_, dt, *v);
}

// OSL's runtime optimiser knows a local's value beyond its block when one assignment of a
// constant is the local's only write and comes before every read, even inside a branch (a read
// where it did not run would read an uninitialised value): OSL 1.13.12 -O2 folds
// format("%.0f", x) to "2" after a loop that follows `float x = 2.5`, where the unfolded format
// prints "3", and prints 1 at both points of `float x; if (u > 0.5) x = 1; printf("%g", x)` over
// a 2x1 grid. Blocks otherwise start knowing nothing (run()).
void Folder::once_assigned_constants() {
  std::vector<int> writes(sh_.symbols.size(), 0), writer(sh_.symbols.size(), -1),
      first_read(sh_.symbols.size(), INT_MAX);
  for (size_t i = 0; i < sh_.ops.size(); ++i) {
    const Op& op = sh_.ops[i];
    for (size_t a = 0; a < op.args.size(); ++a) {
      int s = op.args[a];
      if (op.writes(int(a))) {
        ++writes[size_t(s)];
        writer[size_t(s)] = int(i);
      } else {
        first_read[size_t(s)] = std::min(first_read[size_t(s)], int(i));
      }
    }
  }
  for (size_t s = 0; s < sh_.symbols.size(); ++s) {
    const Symbol& sym = sh_.symbols[s];
    if ((sym.kind != SymKind::Local && sym.kind != SymKind::Temp) || sym.type.is_array() ||
        is_closure(int(s)) || writes[s] != 1 || writer[s] < sh_.main_begin ||
        first_read[s] <= writer[s])
      continue;
    const Op& w = sh_.ops[size_t(writer[s])];
    if (w.opcode != Opcode::Assign || w.args.size() != 2 || w.args[0] != int(s) ||
        !is_const(w.args[1]))
      continue;
    const Symbol& c = sh_.symbols[size_t(w.args[1])];
    if (auto v = convert_const(c.type, c.init, sym.type))
      fixed_[int(s)] = intern_const(sh_, sym.type, *v);
  }
}

bool Folder::run() {
  if (algebraic_) once_assigned_constants();
  std::set<int> starts = {sh_.main_begin};
  for (const Op& op : sh_.ops) starts.insert(op.jumps.begin(), op.jumps.end());
  for (const Symbol& s : sh_.symbols)
    if (s.init_begin >= 0) starts.insert(s.init_begin);
  for (size_t i = 0; i < sh_.ops.size(); ++i) {
    if (starts.count(int(i))) clear_block();
    Op& op = sh_.ops[i];
    substitute(op);
    fold(op);
    record(sh_.ops[i]);
    const ir::OpcodeInfo* info = &ir::info(sh_.ops[i].opcode);
    if (info->flags & kJump) clear_block();
  }
  return changed_;
}

} // namespace

bool fold_constants(Shader& shader, const EvalOptions& options, bool algebraic, bool late) {
  return Folder(shader, options, algebraic, late).run();
}

} // namespace lobe::passes

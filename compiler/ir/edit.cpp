// Implements the editing helpers of edit.h.
#include "ir/edit.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace lobe::ir {

namespace {
// Constants are the same value when their bits are: -0 is not 0 (cos(pi/2) folds to -0, which
// prints as such), and a NaN is a NaN.
bool same_bits(const std::vector<ConstValue>& a, const std::vector<ConstValue>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].i != b[i].i || std::memcmp(&a[i].f, &b[i].f, sizeof(float)) != 0 || a[i].s != b[i].s)
      return false;
  return true;
}
} // namespace

int intern_const(Shader& sh, const Type& t, const std::vector<ConstValue>& v) {
  for (size_t i = 0; i < sh.symbols.size(); ++i) {
    const Symbol& s = sh.symbols[i];
    if (s.kind == SymKind::Const && s.type == t && same_bits(s.init, v)) return int(i);
  }
  int n = 0;
  for (const Symbol& s : sh.symbols)
    if (s.kind == SymKind::Const) ++n;
  std::string name;
  do name = "$c" + std::to_string(n++);
  while (sh.find_symbol(name) >= 0);
  Symbol s;
  s.name = name;
  s.type = t;
  s.kind = SymKind::Const;
  s.init = v;
  sh.symbols.push_back(std::move(s));
  return int(sh.symbols.size()) - 1;
}

bool const_all(const Symbol& s, int value) {
  for (const ConstValue& c : s.init)
    if (s.type.base == BaseType::Int ? c.i != value : c.f != float(value)) return false;
  return !s.init.empty();
}

int intern_int(Shader& sh, int value) {
  return intern_const(sh, Type{BaseType::Int}, {ConstValue::of_int(value)});
}

int intern_float(Shader& sh, float value) {
  return intern_const(sh, Type{BaseType::Float}, {ConstValue::of_float(value)});
}

int intern_string(Shader& sh, const std::string& value) {
  return intern_const(sh, Type{BaseType::String}, {ConstValue::of_string(value)});
}

void remove_ops(Shader& sh, const std::vector<bool>& keep) {
  int n = int(sh.ops.size());
  // new_index[i]: the new index of the first kept op at or after i (same region), for i <= n.
  std::vector<int> new_index(n + 1);
  int kept = 0;
  for (int i = 0; i < n; ++i) {
    new_index[i] = kept;
    if (keep[i]) ++kept;
  }
  new_index[n] = kept;
  // A jump to a removed last op of the init region must land at the init region's end, which
  // is the new main_begin: new_index already gives that (the count of kept ops before it).
  std::vector<Op> ops;
  ops.reserve(kept);
  for (int i = 0; i < n; ++i) {
    if (!keep[i]) continue;
    Op op = std::move(sh.ops[i]);
    for (int& j : op.jumps) j = new_index[std::clamp(j, 0, n)];
    ops.push_back(std::move(op));
  }
  for (Symbol& s : sh.symbols) {
    if (s.init_begin < 0) continue;
    s.init_begin = new_index[s.init_begin];
    s.init_end = new_index[s.init_end];
  }
  sh.main_begin = new_index[std::clamp(sh.main_begin, 0, n)];
  sh.ops = std::move(ops);
}

bool remove_unused_symbols(Shader& sh) {
  std::vector<bool> used(sh.symbols.size(), false);
  for (const Op& op : sh.ops)
    for (int a : op.args) used[a] = true;
  std::vector<int> remap(sh.symbols.size(), -1);
  std::vector<Symbol> syms;
  for (size_t i = 0; i < sh.symbols.size(); ++i) {
    SymKind k = sh.symbols[i].kind;
    bool removable = k == SymKind::Temp || k == SymKind::Local || k == SymKind::Const;
    if (removable && !used[i]) continue;
    remap[i] = int(syms.size());
    syms.push_back(std::move(sh.symbols[i]));
  }
  bool changed = syms.size() != sh.symbols.size();
  sh.symbols = std::move(syms);
  for (Op& op : sh.ops)
    for (int& a : op.args) a = remap[a];
  return changed;
}

bool op_reads(const Op& op, int argi) {
  if (!op.writes(argi)) return true;
  return argi == 0 && (op.opcode == Opcode::CompAssign || op.opcode == Opcode::MxCompAssign ||
                       op.opcode == Opcode::AAssign);
}

} // namespace lobe::ir

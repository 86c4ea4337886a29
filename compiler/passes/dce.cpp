// Implements eliminate_dead_code. Liveness is per symbol over the whole shader (not per path):
// simple, and exact enough for lowered code, where temporaries are written and read nearby;
// plus dead stores within one basic block (lowering reuses temporaries, so a temporary is
// often written, overwritten and read again in one block).
#include "passes/dce.h"
#include "ir/edit.h"
#include "ir/opcodes.h"

#include <algorithm>
#include <vector>

namespace lobe::passes {

using namespace ir;

namespace {

// Marks ops reachable from `start` within [start, region_end).
void reach(const Shader& sh, int start, int region_end, std::vector<bool>& live) {
  std::vector<int> work = {start};
  while (!work.empty()) {
    int i = work.back();
    work.pop_back();
    if (i < 0 || i >= region_end || live[i]) continue;
    live[i] = true;
    const Op& op = sh.ops[i];
    if (op.opcode == "exit") continue;
    if (op.opcode == "br" || op.opcode == "cbr") {
      for (int j : op.jumps) work.push_back(j);
      continue;
    }
    work.push_back(i + 1);
  }
}

// An op that does nothing: nop, a jump to the next op, x = x.
bool trivial(const Op& op, int index) {
  if (op.opcode == "nop") return true;
  if (op.opcode == "br" && op.jumps.size() == 1 && op.jumps[0] == index + 1) return true;
  return op.opcode == "assign" && op.args.size() == 2 && op.args[0] == op.args[1];
}

bool observable(const Symbol& s) {
  return s.kind == SymKind::Global || s.kind == SymKind::Param || s.kind == SymKind::OutputParam;
}

// Ops whose every written symbol is unobservable and never read by a kept op.
bool drop_unread_writes(const Shader& sh, std::vector<bool>& keep) {
  bool any = false;
  for (bool grew = true; grew;) {
    grew = false;
    std::vector<int> reads(sh.symbols.size(), 0);
    for (size_t i = 0; i < sh.ops.size(); ++i) {
      if (!keep[i]) continue;
      const Op& op = sh.ops[i];
      for (size_t a = 0; a < op.args.size(); ++a)
        if (op_reads(op, int(a))) ++reads[op.args[a]];
    }
    for (size_t i = 0; i < sh.ops.size(); ++i) {
      const Op& op = sh.ops[i];
      const OpcodeInfo* info = find_opcode(op.opcode);
      if (!keep[i] || !info || (info->flags & (kEffect | kJump)) || op.written_mask == 0) continue;
      bool dead = true;
      for (size_t a = 0; a < op.args.size() && dead; ++a) {
        if (!op.writes(int(a))) continue;
        int s = op.args[a];
        // A read-modify-write op (aassign) counts its own read: discount it.
        int own = op_reads(op, int(a)) ? 1 : 0;
        dead = !observable(sh.symbols[s]) && reads[s] - own == 0;
      }
      if (dead) keep[i] = false, grew = any = true;
    }
  }
  return any;
}

// True if `op` overwrites the whole of operand `a` (so an earlier value is dead): a pure op
// writing it without reading it; arraycopy only between arrays of the same length.
bool full_write(const Shader& sh, const Op& op, int a) {
  const OpcodeInfo* info = find_opcode(op.opcode);
  if (!info || !(info->flags & kPure) || !op.writes(a) || op_reads(op, a)) return false;
  if (op.opcode == "arraycopy") {
    const Type& d = sh.symbols[size_t(op.args[0])].type;
    const Type& s = sh.symbols[size_t(op.args[1])].type;
    return d.arraylen > 0 && d.arraylen == s.arraylen;
  }
  return true;
}

// Dead stores within a basic block of the main body: a pure op whose written temporaries and
// locals are all overwritten later in the same block before anything reads them.
bool drop_dead_stores(const Shader& sh, std::vector<bool>& keep) {
  int n = int(sh.ops.size());
  std::vector<bool> leader(size_t(n) + 1, false);
  for (int i = sh.main_begin; i < n; ++i) {
    const Op& op = sh.ops[size_t(i)];
    for (int j : op.jumps) leader[size_t(std::clamp(j, 0, n))] = true;
    if (!op.jumps.empty() || op.opcode == "exit") leader[size_t(i) + 1] = true;
  }
  bool any = false;
  std::vector<char> killed(sh.symbols.size(), 0);
  std::vector<int> touched;
  for (int i = n - 1; i >= sh.main_begin; --i) {
    if (leader[size_t(i) + 1]) { // block boundary after op i: nothing is known dead
      for (int s : touched) killed[size_t(s)] = 0;
      touched.clear();
    }
    if (!keep[size_t(i)]) continue;
    const Op& op = sh.ops[size_t(i)];
    const OpcodeInfo* info = find_opcode(op.opcode);
    bool pure = info && (info->flags & kPure) && !(info->flags & (kEffect | kJump));
    bool dead = pure && op.written_mask != 0;
    for (size_t a = 0; a < op.args.size() && dead; ++a)
      if (op.writes(int(a))) dead = killed[size_t(op.args[a])] && !op_reads(op, int(a));
    if (dead) {
      keep[size_t(i)] = false;
      any = true;
      continue;
    }
    for (size_t a = 0; a < op.args.size(); ++a) {
      int s = op.args[a];
      SymKind k = sh.symbols[size_t(s)].kind;
      if (full_write(sh, op, int(a)) && (k == SymKind::Temp || k == SymKind::Local)) {
        killed[size_t(s)] = 1;
        touched.push_back(s);
      }
    }
    for (size_t a = 0; a < op.args.size(); ++a)
      if (op_reads(op, int(a))) killed[size_t(op.args[a])] = 0;
  }
  return any;
}

} // namespace

// One round; removing ops can expose more (a jump now to the next op): the entry loops.
static bool dce_round(Shader& sh) {
  int n = int(sh.ops.size());
  std::vector<bool> keep(n, false);
  reach(sh, sh.main_begin, n, keep);
  for (const Symbol& s : sh.symbols)
    if (s.init_begin >= 0)
      for (int i = s.init_begin; i < s.init_end; ++i) keep[i] = true; // conservatively whole range
  bool changed = false;
  for (int i = 0; i < n; ++i) {
    if (!keep[i]) {
      changed = true;
      continue;
    }
    Op& op = sh.ops[i];
    if (op.opcode == "cbr" && op.jumps.size() == 2 && op.jumps[0] == op.jumps[1]) {
      op.opcode = "br";
      op.args.clear();
      op.written_mask = 0;
      op.jumps.resize(1);
      changed = true;
    }
    if (trivial(op, i)) keep[i] = false, changed = true;
  }
  changed |= drop_dead_stores(sh, keep);
  changed |= drop_unread_writes(sh, keep);
  if (changed) remove_ops(sh, keep);
  changed |= remove_unused_symbols(sh);
  return changed;
}

bool eliminate_dead_code(Shader& sh) {
  bool changed = false;
  while (dce_round(sh)) changed = true;
  return changed;
}

} // namespace lobe::passes

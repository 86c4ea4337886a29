// Implements eliminate_dead_code. Liveness is per symbol over the whole shader (not per path):
// simple, and exact enough for lowered code, where temporaries are written and read nearby;
// plus dead stores found by liveness over the main body's control-flow graph (lowering reuses
// temporaries, so a temporary is often written, overwritten and read again elsewhere).
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
    if (op.opcode == Opcode::Exit) continue;
    if (op.opcode == Opcode::Br || op.opcode == Opcode::Cbr) {
      for (int j : op.jumps) work.push_back(j);
      continue;
    }
    work.push_back(i + 1);
  }
}

// An op that does nothing: nop, a jump to the next op, x = x.
bool trivial(const Op& op, int index) {
  if (op.opcode == Opcode::Nop) return true;
  if (op.opcode == Opcode::Br && op.jumps.size() == 1 && op.jumps[0] == index + 1) return true;
  return op.opcode == Opcode::Assign && op.args.size() == 2 && op.args[0] == op.args[1];
}

bool observable(const Symbol& s) {
  return s.kind == SymKind::Global || s.kind == SymKind::Param ||
         (s.kind == SymKind::OutputParam && !s.unread);
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
      for (size_t a = 0; a < op.args.size(); ++a) {
        // `useparam` readies an output for the ops after it; of an unread output it reads
        // nothing anyone observes.
        if (op.opcode == Opcode::UseParam && sh.symbols[size_t(op.args[a])].unread) continue;
        if (op_reads(op, int(a))) ++reads[op.args[a]];
      }
    }
    for (size_t i = 0; i < sh.ops.size(); ++i) {
      const Op& op = sh.ops[i];
      const ir::OpcodeInfo* info = &ir::info(op.opcode);
      if (!keep[i] || (info->flags & (kEffect | kJump)) || op.written_mask == 0) continue;
      bool dead = true;
      for (size_t a = 0; a < op.args.size() && dead; ++a) {
        if (!op.writes(int(a))) continue;
        int s = op.args[a];
        // The op's own reads of what it writes (aassign's read-modify-write, `add x x y`)
        // are discounted.
        int own = 0;
        for (size_t b = 0; b < op.args.size(); ++b) own += op.args[b] == s && op_reads(op, int(b));
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
  const ir::OpcodeInfo* info = &ir::info(op.opcode);
  if (!(info->flags & kPure) || !op.writes(a) || op_reads(op, a)) return false;
  if (op.opcode == Opcode::ArrayCopy) {
    const Type& d = sh.symbols[size_t(op.args[0])].type;
    const Type& s = sh.symbols[size_t(op.args[1])].type;
    return d.arraylen > 0 && d.arraylen == s.arraylen;
  }
  return true;
}

bool tracked(const Symbol& s) { return s.kind == SymKind::Temp || s.kind == SymKind::Local; }

// Basic blocks of the main body: [begin, end) and successor blocks.
struct Block {
  int begin = 0, end = 0;
  std::vector<int> succ;
};

std::vector<Block> main_blocks(const Shader& sh, std::vector<int>& block_of) {
  int n = int(sh.ops.size());
  std::vector<bool> leader(size_t(n) + 1, false);
  leader[size_t(sh.main_begin)] = true;
  for (int i = sh.main_begin; i < n; ++i) {
    const Op& op = sh.ops[size_t(i)];
    for (int j : op.jumps) leader[size_t(std::clamp(j, sh.main_begin, n))] = true;
    if (!op.jumps.empty() || op.opcode == Opcode::Exit) leader[size_t(i) + 1] = true;
  }
  std::vector<Block> blocks;
  block_of.assign(size_t(n) + 1, -1);
  for (int i = sh.main_begin; i < n; ++i) {
    if (leader[size_t(i)]) blocks.push_back({i, i, {}});
    blocks.back().end = i + 1;
    block_of[size_t(i)] = int(blocks.size()) - 1;
  }
  for (size_t b = 0; b < blocks.size(); ++b) {
    const Op& last = sh.ops[size_t(blocks[b].end - 1)];
    std::vector<int> targets = last.jumps;
    if (last.opcode != Opcode::Br && last.opcode != Opcode::Cbr && last.opcode != Opcode::Exit)
      targets.push_back(blocks[b].end);
    for (int t : targets)
      if (t >= sh.main_begin && t < n) blocks[b].succ.push_back(block_of[size_t(t)]);
  }
  return blocks;
}

// Updates `live` (backwards) across op `op`: its full writes end liveness, its reads start it.
void step_back(const Shader& sh, const Op& op, std::vector<char>& live) {
  for (size_t a = 0; a < op.args.size(); ++a)
    if (full_write(sh, op, int(a))) live[size_t(op.args[a])] = 0;
  for (size_t a = 0; a < op.args.size(); ++a)
    if (op_reads(op, int(a))) live[size_t(op.args[a])] = 1;
}

// Dead stores in the main body by liveness over its control-flow graph: a pure op whose
// written temporaries and locals are read on no path before being overwritten (with
// `part_stores`, an element or component store: read on no path after it). (Init ops
// run before the main body, so nothing they read is written here.)
bool drop_dead_stores(const Shader& sh, std::vector<bool>& keep, bool part_stores) {
  std::vector<int> block_of;
  std::vector<Block> blocks = main_blocks(sh, block_of);
  size_t ns = sh.symbols.size();
  std::vector<std::vector<char>> live_in(blocks.size(), std::vector<char>(ns, 0));
  auto live_out = [&](const Block& b) {
    std::vector<char> out(ns, 0);
    for (int s : b.succ)
      for (size_t k = 0; k < ns; ++k) out[k] |= live_in[size_t(s)][k];
    return out;
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t b = blocks.size(); b-- > 0;) {
      std::vector<char> live = live_out(blocks[b]);
      for (int i = blocks[b].end - 1; i >= blocks[b].begin; --i)
        if (keep[size_t(i)]) step_back(sh, sh.ops[size_t(i)], live);
      if (live != live_in[b]) live_in[b] = std::move(live), changed = true;
    }
  }
  bool any = false;
  for (const Block& b : blocks) {
    std::vector<char> live = live_out(b);
    for (int i = b.end - 1; i >= b.begin; --i) {
      if (!keep[size_t(i)]) continue;
      const Op& op = sh.ops[size_t(i)];
      const ir::OpcodeInfo* info = &ir::info(op.opcode);
      bool dead =
          (info->flags & kPure) && !(info->flags & (kEffect | kJump)) && op.written_mask != 0;
      for (size_t a = 0; a < op.args.size() && dead; ++a) {
        if (!op.writes(int(a))) continue;
        int s = op.args[a];
        // An element or component store reads its target only to keep the rest of it: with
        // `part_stores`, dead when the target is not read afterwards.
        bool part_store =
            part_stores && (op.opcode == Opcode::AAssign || op.opcode == Opcode::CompAssign ||
                            op.opcode == Opcode::MxCompAssign);
        dead = tracked(sh.symbols[size_t(s)]) && !live[size_t(s)] &&
               (part_store || !op_reads(op, int(a)));
      }
      if (dead) {
        keep[size_t(i)] = false;
        any = true;
      } else {
        step_back(sh, op, live);
      }
    }
  }
  return any;
}

} // namespace

// One round; removing ops can expose more (a jump now to the next op): the entry loops.
static bool dce_round(Shader& sh, bool part_stores) {
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
    if (op.opcode == Opcode::Cbr && op.jumps.size() == 2 && op.jumps[0] == op.jumps[1]) {
      op.opcode = Opcode::Br;
      op.args.clear();
      op.written_mask = 0;
      op.jumps.resize(1);
      changed = true;
    }
    if (trivial(op, i)) keep[i] = false, changed = true;
  }
  changed |= drop_dead_stores(sh, keep, part_stores);
  changed |= drop_unread_writes(sh, keep);
  if (changed) remove_ops(sh, keep);
  changed |= remove_unused_symbols(sh);
  return changed;
}

bool eliminate_dead_code(Shader& sh, bool part_stores) {
  bool changed = false;
  while (dce_round(sh, part_stores)) changed = true;
  return changed;
}

} // namespace lobe::passes

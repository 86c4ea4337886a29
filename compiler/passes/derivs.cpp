// Implements analyze_derivatives: seeds from the opcode table's `derivs` masks, then a
// fixed-point backward propagation over all ops (control flow does not matter: a symbol
// needs derivatives if any write of it feeds a derivative read on some path, and symbols are
// not SSA, so the flag is per symbol, as in OSL).
#include "passes/derivs.h"
#include "ir/edit.h"
#include "ir/opcodes.h"

#include <vector>

namespace lobe::passes {

using namespace ir;

static bool can_carry(const Symbol& s) {
  if (s.kind == SymKind::Const) return false;
  BaseType b = s.type.base;
  return b == BaseType::Float || s.type.is_triple();
}

static bool is_string(const Shader& sh, int sym) {
  return sh.symbols[size_t(sym)].type.base == BaseType::String;
}

// Gabor noise filters over its position's footprint, so it reads the position's derivatives
// (as OSL's does): noise/pnoise whose kind is "gabor", or a kind known only while shading.
static bool reads_position_derivs(const Shader& sh, const Op& op) {
  if ((op.opcode != Opcode::Noise && op.opcode != Opcode::PNoise) || op.args.size() < 3 ||
      !is_string(sh, op.args[1]))
    return false;
  const Symbol& kind = sh.symbols[size_t(op.args[1])];
  return kind.kind != SymKind::Const || (!kind.init.empty() && kind.init[0].s == "gabor");
}

bool analyze_derivatives(Shader& sh) {
  std::vector<bool> need(sh.symbols.size(), false);
  auto mark = [&](int sym) {
    if (need[sym] || !can_carry(sh.symbols[sym])) return false;
    need[sym] = true;
    return true;
  };
  for (const Op& op : sh.ops) {
    const ir::OpcodeInfo* info = &ir::info(op.opcode);
    for (size_t i = 0; i < op.args.size() && i < 32; ++i)
      if ((info->derivs >> i) & 1u) mark(op.args[i]);
    if (reads_position_derivs(sh, op)) {
      // The position: the operands after the kind up to the first keyword — for pnoise the
      // first half of them (the periods follow).
      size_t end = 2;
      while (end < op.args.size() && !is_string(sh, op.args[end])) ++end;
      if (op.opcode == Opcode::PNoise) end = 2 + (end - 2) / 2;
      for (size_t i = 2; i < end; ++i) mark(op.args[i]);
    }
  }
  for (bool grew = true; grew;) {
    grew = false;
    for (const Op& op : sh.ops) {
      const ir::OpcodeInfo* info = &ir::info(op.opcode);
      if (!(info->flags & kPropagates)) continue;
      bool result_needs = false;
      for (size_t i = 0; i < op.args.size(); ++i)
        if (op.writes(int(i)) && need[op.args[i]]) result_needs = true;
      if (!result_needs) continue;
      for (size_t i = 0; i < op.args.size(); ++i)
        if (op_reads(op, int(i))) grew |= mark(op.args[i]);
    }
  }
  bool changed = false;
  for (size_t i = 0; i < sh.symbols.size(); ++i) {
    changed |= sh.symbols[i].derivs != need[i];
    sh.symbols[i].derivs = need[i];
  }
  return changed;
}

} // namespace lobe::passes

// The op emitter of every opcode by direct index: the family tables (ops_*.cpp) merged once
// into an array indexed by ir::Opcode. The control flow ops are LayerEmitter::emit_op's own
// (they shape the function's blocks), listed here with no emitter so that every opcode is
// in exactly one table (codegen_test checks it).
#include "op_tables.h"

namespace lobe::codegen {

namespace {
const OpEntry kFlowOps[] = {
    {ir::Opcode::Nop, nullptr},  {ir::Opcode::Br, nullptr},       {ir::Opcode::Cbr, nullptr},
    {ir::Opcode::Exit, nullptr}, {ir::Opcode::UseParam, nullptr},
};

std::array<std::span<const OpEntry>, 7> families() {
  return {core_ops(),    access_ops(), math_ops(), geometry_ops(),
          library_ops(), data_ops(),   flow_ops()};
}
} // namespace

std::span<const OpEntry> flow_ops() { return kFlowOps; }

std::array<int, ir::kOpcodeCount> op_emitter_rows() {
  std::array<int, ir::kOpcodeCount> rows{};
  for (std::span<const OpEntry> table : families())
    for (const OpEntry& e : table) ++rows[size_t(e.op)];
  return rows;
}

OpEmitFn op_emitter(ir::Opcode op) {
  static const std::array<OpEmitFn, ir::kOpcodeCount> kByOpcode = [] {
    std::array<OpEmitFn, ir::kOpcodeCount> a{};
    for (std::span<const OpEntry> table : families())
      for (const OpEntry& e : table) a[size_t(e.op)] = e.fn;
    return a;
  }();
  return kByOpcode[size_t(op)];
}

} // namespace lobe::codegen

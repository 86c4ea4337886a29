// The op emitter tables of each family (ops_*.cpp), merged into one array indexed by opcode
// (ops_dispatch.cpp): every opcode is in exactly one table.
#pragma once

#include "emitter.h"
#include "shadeops.h"

#include <array>
#include <span>

namespace lobe::codegen {

struct OpEntry {
  ir::Opcode op;
  OpEmitFn fn; // null only for the control flow LayerEmitter::emit_op does itself
};

std::span<const OpEntry> core_ops();     // ops_core.cpp
std::span<const OpEntry> access_ops();   // ops_access.cpp
std::span<const OpEntry> math_ops();     // ops_math.cpp
std::span<const OpEntry> geometry_ops(); // ops_geometry.cpp
std::span<const OpEntry> library_ops();  // ops_library.cpp
std::span<const OpEntry> data_ops();     // ops_data.cpp
std::span<const OpEntry> flow_ops();     // ops_dispatch.cpp: nop, br, cbr, exit, useparam

// How many rows of the family tables name each opcode (for the test that it is one each).
std::array<int, ir::kOpcodeCount> op_emitter_rows();

// A call of math shadeop `f` in `form` with `args` and the group's math mode (ops_math.cpp).
llvm::Value* call_math(LayerEmitter& e, math::Fn f, shadeops::MathForm form,
                       std::vector<llvm::Value*> args);

// `x` through the matrix spilled at `m` as a point (kind 0), vector (1) or normal (2), with its
// derivatives when `derivs` (ops_geometry.cpp; transform() and the spaced constructors).
Val transform_dual(LayerEmitter& e, llvm::Value* m, const Val& x, int kind, bool derivs);

} // namespace lobe::codegen

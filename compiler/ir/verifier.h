// The IR verifier: checks the invariants codegen relies on (docs/ir.md): unique symbol names,
// constant values of the right size, opcodes from the table with operand counts in range,
// operand types per opcode class, written operands never Const, jump targets inside the op's
// region (init range or main body), parameter init ranges inside the init region.
#pragma once

#include "ir/ir.h"

#include <string>
#include <vector>

namespace lobe::ir {

// Returns one message per problem ("op 12 (add @f.osl:3:4): ..."); empty when valid.
std::vector<std::string> verify(const Shader& shader);

} // namespace lobe::ir

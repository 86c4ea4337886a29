// Editing helpers shared by lowering and the passes: constant interning, op removal with jump
// and init-range remapping, removal of unreferenced symbols.
#pragma once

#include "ir/ir.h"

#include <vector>

namespace lobe::ir {

// Index of a Const symbol of type `t` with value `v`, created ("$cN", first free N) if no
// equal constant exists yet: literal constants are deduplicated.
int intern_const(Shader& sh, const Type& t, const std::vector<ConstValue>& v);
int intern_int(Shader& sh, int value);
int intern_float(Shader& sh, float value);
int intern_string(Shader& sh, const std::string& value);

// True if `s` has a value and every component of it equals `value` (ints compared as ints,
// the rest as floats, so -0 equals 0).
bool const_all(const Symbol& s, int value);

// Removes the ops with keep[i] == false. A jump to a removed op goes to the next kept op of
// the same region; init ranges and main_begin shrink accordingly.
void remove_ops(Shader& sh, const std::vector<bool>& keep);

// Removes Temp, Local and Const symbols no op references (params and globals stay);
// returns whether any was removed.
bool remove_unused_symbols(Shader& sh);

// True if symbol `s` is read by op `op` (an operand not written, or written and also read:
// compassign/mxcompassign/aassign read their destination).
bool op_reads(const Op& op, int argi);

} // namespace lobe::ir

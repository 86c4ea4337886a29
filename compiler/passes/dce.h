// Dead-code elimination, on any ir::Shader (the runtime re-runs it after specialisation):
//  * ops no path reaches (from main_begin, or from a parameter's init_begin) are removed;
//  * jumps to the next op, `nop`s and self-assignments are removed; a `cbr` whose targets are
//    equal becomes a `br`;
//  * ops without effects (not kEffect, not a jump) whose written symbols are never read, and
//    are not observable (globals, parameters; not an output marked `unread`), are removed, to
//    a fixed point;
//  * Temp, Local and Const symbols no op references any more are removed.
// `part_stores` (OSL's run-time -O2): an element or component store (aassign, compassign,
// mxcompassign) into a local or temporary that no path reads afterwards is dead too, and goes
// with its index's range check, as OSL's -O2 drops it; without it, such a store stays (its
// range error prints, as at OSL's -O0 and -O1).
#pragma once

#include "ir/ir.h"

namespace lobe::passes {

// Returns whether the shader changed.
bool eliminate_dead_code(ir::Shader& shader, bool part_stores = false);

} // namespace lobe::passes

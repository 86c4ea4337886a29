// The op emitter tables of each family (ops_*.cpp), merged by find_op_emitter.
#pragma once

#include "emitter.h"

#include <span>

namespace lobe::codegen {

struct OpEntry {
  const char* name;
  OpEmitFn fn;
};

std::span<const OpEntry> core_ops();     // ops_core.cpp
std::span<const OpEntry> access_ops();   // ops_access.cpp
std::span<const OpEntry> math_ops();     // ops_math.cpp
std::span<const OpEntry> geometry_ops(); // ops_geometry.cpp
std::span<const OpEntry> library_ops();  // ops_library.cpp
std::span<const OpEntry> data_ops();     // ops_data.cpp

} // namespace lobe::codegen

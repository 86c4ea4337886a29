// `lobe compile --emit=llvm|asm`: one shader compiled as a one-layer group, the way the
// ShadingSystem compiles it (defaults as instance values, specialisation when opt_level > 0
// and options.specialize), printed as LLVM IR after the JIT's -O pipeline, or as the host
// assembly the JIT's TargetMachine makes of it. Nothing is JIT-linked or run.
#pragma once

#include "lobe/shadingsys.h"

#include <string>

namespace lobe::group {

enum class EmitForm { LlvmIr, Assembly };

// `path` is an .osl or .lir file. Returns false with diagnostics on error.
bool emit_shader_text(const std::string& path, const CompileOptions& options, EmitForm form,
                      std::string& out, DiagnosticList& diags);

} // namespace lobe::group

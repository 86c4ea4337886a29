// The runtime's side of the compile driver (compiler/driver/driver.h): finding a shader on the
// ShadingSystem's search path, loading it as IR, and the compiler's diagnostics turned into the
// public lobe::Diagnostic (the compiler knows nothing of the runtime's API).
#pragma once

#include "diag/diagnostics.h"
#include "ir/ir.h"
#include "lobe/shadingsys.h"
#include "public_diag.h"

#include <optional>
#include <string>
#include <vector>

namespace lobe::group {

// The ShadingSystem's search path: options.include_dirs in order, then the current directory.
std::vector<std::string> search_dirs(const CompileOptions& options);
// Finds shader `name` on that path (the one search order, compiler/driver/search.h). "" if none.
std::string find_shader_file(const std::string& name, const CompileOptions& options);

// Compiles the file (.osl through the front end, .lir through the IR parser); stage times go
// to `stats`. Nullopt with diagnostics on failure.
std::optional<ir::Shader> compile_shader_file(const std::string& path,
                                              const CompileOptions& options, DiagnosticList& diags,
                                              CompileStats& stats);

// OSL source text compiled as if read from `path` (which names it in diagnostics).
std::optional<ir::Shader> compile_osl_source(const std::string& path, const std::string& text,
                                             const CompileOptions& options, DiagnosticList& diags,
                                             CompileStats& stats);

std::optional<ir::Shader> parse_ir_text(const std::string& text, const std::string& where,
                                        DiagnosticList& diags);

} // namespace lobe::group

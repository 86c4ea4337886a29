// Finding a shader by name and turning it into IR: an in-memory IR registration
// (ShadingSystem::add_shader_ir), else a file on the search path: `name` itself, or
// `name.osl` / `name.lir` (IR text) in each include dir, then the current directory.
#pragma once

#include "ir/ir.h"
#include "lobe/shadingsys.h"

#include <optional>
#include <string>

namespace lobe::group {

// Finds shader `name`: name.osl or name.lir in options.include_dirs then ".", else an .osl
// there that declares a shader called `name` (oslc names its .oso so). "" if none.
std::string find_shader_file(const std::string& name, const CompileOptions& options);
// The shader name an OSL source declares ("" if none is found).
std::string declared_shader_name(const std::string& text);

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

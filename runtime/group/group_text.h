// OSL's shader-group text, read into a ShaderGroup (ShadingSystem::parse_group):
//
//   param float Kd 0.5 ; param color Cs 1 0 0 ; shader matte m1 ;
//   param string name "tex.png" ; shader texlayer t1 ;
//   connect t1.Cout m1.Cs ;
//
// `param` statements give instance values to the next `shader`; the value text is kept as
// written (strings unquoted). Statements end with `;` or a newline before the next keyword.
#pragma once

#include "lobe/shadingsys.h"

#include <memory>
#include <string>

namespace lobe::group {

std::unique_ptr<ShaderGroup> parse_group_text(const std::string& text, const std::string& where,
                                              DiagnosticList& diags);

} // namespace lobe::group

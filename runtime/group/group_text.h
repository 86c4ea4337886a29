// OSL's shader-group text, read into a ShaderGroup; the one reader, used by
// ShadingSystem::parse_group, `lobe shade -group` and the scene loaders (a leaf library with no
// LLVM, so scenes load without the JIT).
//
//   param float Kd 0.5 ; param color Cs 1 0 0 ; shader matte m1 ;
//   param string name "tex.png" ; shader texlayer t1 ;
//   connect t1.Cout m1.Cs ;
//
// `param TYPE NAME VALUE... [[ metadata ]]` gives an instance value to the next `shader`; its
// words are kept as written (quoted strings unquoted), typed per InstanceValue's OSL rules; of
// the metadata, `int lockgeom = 0|1` is kept. `shader SHADER [LAYER]` adds a layer (named
// SHADER_i, i its index, when LAYER is missing); `connect A.x B.y` connects (an endpoint may
// name a member, element or component). Statements end with `;` or `,` (as in OSL), or where
// the next keyword starts; `#` starts a comment to the end of the line.
#pragma once

#include "lobe/shadingsys.h"

#include <memory>
#include <string>

namespace lobe::group {

struct GroupTextOptions {
  // OSL testrender's XML: a statement starting with a type name is a `param` without the
  // keyword (`color Cs 0.8 0.1 0.1 ;`).
  bool allow_bare_params = false;
  // The file line the text starts on (> 0: messages say "where:L"); 0: "where:N", N counted
  // inside the text.
  int first_line = 0;
};

std::unique_ptr<ShaderGroup> parse_group_text(const std::string& text, const std::string& where,
                                              DiagnosticList& diags,
                                              const GroupTextOptions& options = {});

// True for OSL parameter type names: int float color point vector normal string matrix,
// optionally with an array suffix ("float[3]").
bool is_param_type(const std::string& word);

} // namespace lobe::group

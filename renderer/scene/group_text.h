// OSL shader-group text -> lobe::ShaderGroup, for scene files.
//
//   param float Kd 0.5 ;  shader matte m1 ;  connect tex.Cout m1.Cs ;
//
// A `param` statement gives an instance value to the next `shader`. With `allow_bare` (OSL's
// testrender XML), a statement starting with a type name is a `param` without the keyword:
// `color Cs 0.8 0.1 0.1 ;`. String values are written quoted and stored unquoted.
// The runtime's ShadingSystem::parse_group reads the same text; the scene loader has its own
// reader so that scenes load (and report errors with scene-file locations) without the JIT.
#pragma once

#include "lobe/shadingsys.h"

#include <optional>
#include <string>

namespace lobe::scene {

// `where` prefixes messages: "where: line N: msg" with N counted inside the text; or, with
// `first_line` > 0 (the file line the text starts on), "where:L: msg" with L the file line.
std::optional<ShaderGroup> parse_group_text(const std::string& text, const std::string& where,
                                            bool allow_bare, std::string& error,
                                            int first_line = 0);

// True for OSL parameter type names: int float color point vector normal string matrix,
// optionally with an array suffix ("float[3]").
bool is_param_type(const std::string& word);

} // namespace lobe::scene

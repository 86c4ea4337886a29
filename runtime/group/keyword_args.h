// The keyword arguments a builtin or closure does not take: the type checker keeps them as oslc
// does (ir::option_fits, sema's closure calls), and the group builder drops them from a layer's
// copy of its shader with OSL's messages, as OSL's shading system does when it sets a shader up.
#pragma once

#include "ir/ir.h"
#include "lobe/shadingsys.h"

namespace lobe::group {

// Drops, from every op of `sh`, each `"keyword", value` pair its lookup or closure does not
// take or whose value does not fit, once per call whether or not it runs, with OSL's message:
//   texture lookups  `Unknown texture optional argument: "foo", <int> (x.osl:3)` (an error in
//                    testshade's words, texture3d's naming itself), id builtin_option;
//   gabor noise      `Unknown noise optional argument: ...` (pnoise's naming itself), likewise;
//                    other noise kinds take none and drop them silently, as OSL ignores them;
//   closures         `Unsupported closure keyword arg "foo" for diffuse (x.osl:2)`, a warning,
//                    id closure_keyword.
// All are diagnostics of severity Warning: the shader runs without them.
void drop_misfit_keywords(ir::Shader& sh, DiagnosticList& diags);

} // namespace lobe::group

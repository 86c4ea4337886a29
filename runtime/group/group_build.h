// From a ShaderGroup and its layers' IR to what codegen needs: instance values parsed against
// each parameter's type, connections resolved to symbols (whole params, struct members, array
// elements, components), specialisation (instance values and defaults of unconnected,
// never-written params become constants, then constant folding and dead-code elimination),
// derivative analysis across layers, the group-data layout and its initial contents.
//
// Only layers the last layer depends on (through connections) are kept; the others can never
// run (lazy layers), so they are not compiled.
#pragma once

#include "codegen.h"
#include "instance_values.h"
#include "lobe/shadingsys.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lobe::group {

struct GroupBuild {
  std::vector<std::unique_ptr<ir::Shader>> shaders; // specialised layers, in execution order
  std::vector<std::string> layer_names;
  codegen::GroupPlan plan;
  std::vector<unsigned char> groupdata; // initial group data (instance values, defaults)
  uint64_t globals_read = 0;            // bit i: kGlobalFields[i] is read
};

// `sources[i]` is the compiled IR of group.layers[i]. Returns false with diagnostics on error.
// `lockgeom_default`: CompileOptions::lockgeom_default. The caller sets out.plan.env and
// out.plan.fast_math (CompileOptions::fast_math, which constant folding follows too).
// `elide_known_outputs` (OSL's -O2, with `specialize`): a whole connection from an upstream
// output whose value at the end of its layer is known (a constant, or a copy of a shading
// global) is replaced by that value, and an upstream layer no remaining connection reads is
// not compiled and does not run, its printf output then disappearing as in OSL (docs/language.md).
// `merge_instances` (OSL's opt_merge_instances, with `specialize`): a layer identical to an
// earlier one is merged into it. `eager`: CompileOptions' lazy_globals, lazy_unconnected and
// lazy_error turned off make the layers they name entry layers (with no --entry given).
struct EagerLayers {
  bool global_writers = false, unconnected = false, error_callers = false;
};
// A type as OSL's messages name it: a closure is a "closure color" ("closure color[2]").
std::string osl_type_name(const ir::Type& t);

bool build_group(const ShaderGroup& group, const std::vector<const ir::Shader*>& sources,
                 bool specialize, GroupBuild& out, DiagnosticList& diags,
                 bool lockgeom_default = true, bool elide_known_outputs = false,
                 bool merge_instances = true, const EagerLayers& eager = {});

} // namespace lobe::group

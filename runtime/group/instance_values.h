// Instance values read for a parameter's type (instance_values.cpp), by the rules of
// InstanceValue (lobe/shadingsys.h). Apart from group_build.h so that a reader of values alone
// (the native material twins, renderer/native) needs no code generator.
#pragma once

#include "ir/ir.h"
#include "lobe/shadingsys.h"

#include <string>
#include <vector>

namespace lobe::group {

// An instance value for a parameter of type `param` (the rules are InstanceValue's). `ok`:
// use `values` (`arraylen` sizes an unsized array); else `warning` (OSL's: the value is ignored
// and the default kept) or `error` (the value cannot be read) says why.
struct ValueFit {
  bool ok = false;
  std::vector<ir::ConstValue> values;
  int arraylen = 0;
  std::string warning, error;
  std::string note; // a remark on a value that was used (Lobe's; OSL is silent)
};
ValueFit fit_instance_value(const InstanceValue& v, const ir::Type& param);

// The note after OSL's "attempting to set nonexistent parameter" warning, naming what the
// shader has: "layer 'l': shader 's' has no parameter 'p' (its parameters: a, b)".
std::string nonexistent_param_note(const std::string& layer, const std::string& shader,
                                   const std::string& param,
                                   const std::vector<std::string>& params);

// Whether parameter `s` of layer `l` is interactive, as OSL takes it: by its instance value's
// `interactive` mark when one is given (a plain value overrides the shader's metadata), else by
// the shader's `[[ int interactive = 1 ]]`. An interactive parameter is never folded.
bool interactive_param(const ShaderGroup::Layer& l, const ir::Symbol& s);

// An int as OSL reads one (OpenImageIO's stoi): a number past the range of int is the nearest
// int (99999999999 is 2147483647), not its low 32 bits. `end` as strtol's.
int32_t read_int(const char* text, char** end);

// The shader's own `[[ int lockgeom = N ]]` on parameter `s`: N, or -1 when it says nothing.
// `[[ int interpolated = N ]]` says the same as lockgeom = !N (as OSL reads it); of several, the
// last counts.
int metadata_lockgeom(const ir::Symbol& s);

// The same kind of value: one base type, or both triples (color, point, vector, normal).
bool same_kind(const ir::Type& a, const ir::Type& b);

} // namespace lobe::group

// The Lobe IR opcode table: every opcode the compiler emits and codegen implements, once.
//
// Columns:
//   name      the opcode as printed (`add`, `sin`, `closure`); library functions keep OSL's names
//   min_args  fewest operands
//   max_args  most operands, or kVariadic
//   written   default written mask: bit i set means operand i is written (written come first)
//   derivs    mask of operands whose d/dx, d/dy the op READS (derivative-taking ops, filtered
//             texture lookups): the seeds of the derivative analysis
//   flags     kPropagates: the written operand's derivatives follow from the read operands'
//                          (chain rule), so needing derivs of the result needs them of inputs
//             kPure:       result depends only on operand values (constant folding may evaluate
//                          it, dead-code elimination may drop it when the result is unread)
//             kEffect:     observable effect besides the written operands (never dropped)
//             kJump:       control flow (Op::jumps used)
//   doc       one line of semantics; docs/ir.md has the full type rules
//
// Operand type rules are in docs/ir.md ("Opcodes"). In short: arithmetic computes in the type
// of the destination and converts each source to it (int -> float -> triple broadcast);
// comparisons compute in the wider source type and write an int.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace lobe::ir {

inline constexpr int kVariadic = -1;

enum OpFlags : uint8_t {
  kPropagates = 1u << 0,
  kPure = 1u << 1,
  kEffect = 1u << 2,
  kJump = 1u << 3,
};

struct OpcodeInfo {
  const char* name;
  int8_t min_args;
  int8_t max_args;
  uint32_t written;
  uint32_t derivs;
  uint8_t flags;
  const char* doc;
};

inline constexpr uint8_t kArith = kPropagates | kPure; // value ops that carry derivatives
inline constexpr uint8_t kValue = kPure;               // value ops without derivatives

// clang-format off
inline constexpr OpcodeInfo kOpcodes[] = {
  // ---- core: data movement and arithmetic ----------------------------------------------------
  {"nop",          0, 0,          0, 0, 0,      "does nothing (left by passes)"},
  {"assign",       2, 2,          1, 0, kArith, "a = b, converting int->float->triple, float->matrix diagonal, int 0->null closure"},
  {"add",          3, 3,          1, 0, kArith, "a = b + c (closures: sum of closures)"},
  {"sub",          3, 3,          1, 0, kArith, "a = b - c"},
  {"mul",          3, 3,          1, 0, kArith, "a = b * c (matrix product; closure scaled by float or color)"},
  {"div",          3, 3,          1, 0, kArith, "a = b / c, 0 where c == 0 (matrix: b * inverse(c))"},
  {"mod",          3, 3,          1, 0, kArith, "a = b % c: int remainder / fmod, 0 where c == 0"},
  {"neg",          2, 2,          1, 0, kArith, "a = -b (closure: scaled by -1)"},
  {"eq",           3, 3,          1, 0, kValue, "a = (b == c) as int 0/1; triples/matrices: all components"},
  {"neq",          3, 3,          1, 0, kValue, "a = (b != c) as int 0/1"},
  {"lt",           3, 3,          1, 0, kValue, "a = (b < c); int or float operands only"},
  {"le",           3, 3,          1, 0, kValue, "a = (b <= c)"},
  {"gt",           3, 3,          1, 0, kValue, "a = (b > c)"},
  {"ge",           3, 3,          1, 0, kValue, "a = (b >= c)"},
  {"not",          2, 2,          1, 0, kValue, "a = (b == 0) as int; b int, float or closure (null)"},
  {"compl",        2, 2,          1, 0, kValue, "a = ~b (ints)"},
  {"bitand",       3, 3,          1, 0, kValue, "a = b & c (ints)"},
  {"bitor",        3, 3,          1, 0, kValue, "a = b | c (ints)"},
  {"xor",          3, 3,          1, 0, kValue, "a = b ^ c (ints)"},
  {"shl",          3, 3,          1, 0, kValue, "a = b << c (ints)"},
  {"shr",          3, 3,          1, 0, kValue, "a = b >> c (ints, arithmetic)"},
  // ---- components, matrix elements, arrays ---------------------------------------------------
  {"compref",      3, 3,          1, 0, kArith, "a = triple b[c]; c clamped to 0..2, runtime error if out of range"},
  {"compassign",   3, 3,          1, 0, kArith, "triple a[b] = c; b clamped to 0..2 (a is read and written)"},
  {"mxcompref",    4, 4,          1, 0, kArith, "a = matrix b[c][d]; indices clamped to 0..3"},
  {"mxcompassign", 4, 4,          1, 0, kArith, "matrix a[b][c] = d; indices clamped to 0..3"},
  {"aref",         3, 3,          1, 0, kArith, "a = array b[c]; c clamped to 0..len-1, runtime error if out of range"},
  {"aassign",      3, 3,          1, 0, kArith, "array a[b] = c; b clamped (a is read and written)"},
  {"arraycopy",    2, 2,          1, 0, kArith, "array a = array b, same element type or triple kinds, min(len) elements"},
  {"arraylength",  2, 2,          1, 0, kValue, "int a = number of elements of array b"},
  {"construct",    2, 18,         1, 0, kArith, "a = triple/matrix from components, optional leading space name"},
  // ---- closures ------------------------------------------------------------------------------
  {"closure",      2, kVariadic,  1, 0, kPure,  "a = closure \"key\" positional... \"kw\" value...; weight 1"},
  {"declared_closure", 2, kVariadic, 1, 0, kPure, "a = closure the shader declared [[ builtin = 1 ]]: \"name\", npos, positional... \"kw\" value...; laid out by the operands' types"},
  // ---- control flow and bookkeeping ----------------------------------------------------------
  {"br",           0, 0,          0, 0, kJump,  "jump to jumps[0]"},
  {"cbr",          1, 1,          0, 0, kJump,  "if a != 0 jump to jumps[0] else to jumps[1]"},
  {"exit",         0, 0,          0, 0, kJump,  "end the shader (the layer) now"},
  {"useparam",     1, kVariadic,  0, 0, kEffect, "the params listed are about to be read: run upstream layers"},
  // ---- derivatives ---------------------------------------------------------------------------
  {"Dx",           2, 2,          1, 2, kValue, "a = d b / dx (float or triple); no derivatives of its own"},
  {"Dy",           2, 2,          1, 2, kValue, "a = d b / dy"},
  {"Dz",           2, 2,          1, 2, kValue, "a = d b / dz (0 outside volumes)"},
  {"filterwidth",  2, 2,          1, 2, kValue, "a = sqrt(Dx(b)^2 + Dy(b)^2) per component"},
  {"area",         2, 2,          1, 2, kValue, "a = length(cross(Dx(b), Dy(b))) for point b"},
  {"calculatenormal", 2, 2,       1, 2, kValue, "a = cross(Dx(b), Dy(b)), flipped by flip_handedness"},
  // ---- math library (one float or per-component over triples) --------------------------------
  {"sin", 2, 2, 1, 0, kArith, "a = sin b"}, {"cos", 2, 2, 1, 0, kArith, "a = cos b"},
  {"tan", 2, 2, 1, 0, kArith, "a = tan b"}, {"asin", 2, 2, 1, 0, kArith, "a = asin b"},
  {"acos", 2, 2, 1, 0, kArith, "a = acos b"}, {"atan", 2, 2, 1, 0, kArith, "a = atan b"},
  {"atan2", 3, 3, 1, 0, kArith, "a = atan2(b, c)"}, {"sinh", 2, 2, 1, 0, kArith, "a = sinh b"},
  {"cosh", 2, 2, 1, 0, kArith, "a = cosh b"}, {"tanh", 2, 2, 1, 0, kArith, "a = tanh b"},
  {"sincos", 3, 3, 3, 0, kArith, "a = sin c, b = cos c"},
  {"pow", 3, 3, 1, 0, kArith, "a = pow(b, c); c float or same type as b"},
  {"exp", 2, 2, 1, 0, kArith, "a = e^b"}, {"exp2", 2, 2, 1, 0, kArith, "a = 2^b"},
  {"expm1", 2, 2, 1, 0, kArith, "a = e^b - 1"}, {"log", 2, 3, 1, 0, kArith, "a = ln b, or log base c"},
  {"log2", 2, 2, 1, 0, kArith, "a = log2 b"}, {"log10", 2, 2, 1, 0, kArith, "a = log10 b"},
  {"logb", 2, 2, 1, 0, kArith, "a = exponent of b"}, {"sqrt", 2, 2, 1, 0, kArith, "a = sqrt b (0 for b < 0)"},
  {"inversesqrt", 2, 2, 1, 0, kArith, "a = 1/sqrt b (0 for b <= 0)"}, {"cbrt", 2, 2, 1, 0, kArith, "a = cbrt b"},
  {"hypot", 3, 4, 1, 0, kArith, "a = sqrt(b^2 + c^2 [+ d^2])"},
  {"abs", 2, 2, 1, 0, kArith, "a = |b| (int or float-based)"}, {"fabs", 2, 2, 1, 0, kArith, "a = |b|"},
  {"sign", 2, 2, 1, 0, kArith, "a = -1, 0 or 1"}, {"floor", 2, 2, 1, 0, kArith, "a = floor b"},
  {"ceil", 2, 2, 1, 0, kArith, "a = ceil b"}, {"round", 2, 2, 1, 0, kArith, "a = round b (half away from 0)"},
  {"trunc", 2, 2, 1, 0, kArith, "a = trunc b"}, {"fmod", 3, 3, 1, 0, kArith, "a = fmod(b, c), 0 where c == 0"},
  {"min", 3, 3, 1, 0, kArith, "a = min(b, c)"}, {"max", 3, 3, 1, 0, kArith, "a = max(b, c)"},
  {"clamp", 4, 4, 1, 0, kArith, "a = min(max(b, c), d)"}, {"mix", 4, 4, 1, 0, kArith, "a = b*(1-d) + c*d"},
  {"select", 4, 4, 1, 0, kArith, "a = d != 0 ? c : b (per component if d is a triple)"},
  {"step", 3, 3, 1, 0, kArith, "a = c < b ? 0 : 1"}, {"smoothstep", 4, 4, 1, 0, kArith, "a = smoothstep(b, c, d)"},
  {"erf", 2, 2, 1, 0, kArith, "a = erf b"}, {"erfc", 2, 2, 1, 0, kArith, "a = erfc b"},
  {"isnan", 2, 2, 1, 0, kValue, "int a = isnan b"}, {"isinf", 2, 2, 1, 0, kValue, "int a = isinf b"},
  {"isfinite", 2, 2, 1, 0, kValue, "int a = isfinite b"},
  // ---- geometry, colour, matrices ------------------------------------------------------------
  {"dot", 3, 3, 1, 0, kArith, "a = dot(b, c)"}, {"cross", 3, 3, 1, 0, kArith, "a = cross(b, c)"},
  {"length", 2, 2, 1, 0, kArith, "a = |b|"}, {"distance", 3, 4, 1, 0, kArith, "a = |b - c| (or to segment b-c, point d)"},
  {"normalize", 2, 2, 1, 0, kArith, "a = b / |b| (0 for a zero vector)"},
  {"transform", 3, 4, 1, 0, kArith, "a = b..c transformed by matrix or space name(s); point/vector/normal rules by the last operand's type"},
  {"transformu", 3, 4, 1, 0, kArith, "a = unit conversion (\"from\", \"to\", x)"},
  {"transformc", 3, 4, 1, 0, kArith, "a = colour c (or d) converted from space b (or b to c)"},
  {"luminance", 2, 2, 1, 0, kArith, "float a = luminance of colour b (Rec.709 weights)"},
  {"blackbody", 2, 2, 1, 0, kArith, "colour a = blackbody emission at b kelvin"},
  {"wavelength_color", 2, 2, 1, 0, kArith, "colour a = colour of wavelength b nm"},
  {"determinant", 2, 2, 1, 0, kArith, "float a = det matrix b"}, {"transpose", 2, 2, 1, 0, kArith, "a = transpose b"},
  {"getmatrix", 4, 4, 1, 0, 0, "int a = 1 if matrix b from space c to d is known"},
  // ---- noise, splines, textures --------------------------------------------------------------
  {"noise", 2, kVariadic, 1, 0, kArith, "a = noise(\"type\"?, coords..., [period...]) in [0,1]"},
  {"snoise", 2, 4, 1, 0, kArith, "a = signed Perlin noise in [-1,1]"},
  {"pnoise", 3, kVariadic, 1, 0, kArith, "a = periodic noise (coords..., periods...)"},
  {"psnoise", 3, 5, 1, 0, kArith, "a = periodic signed noise"},
  {"cellnoise", 2, 4, 1, 0, kValue, "a = cell noise (piecewise constant)"},
  {"hashnoise", 2, 4, 1, 0, kValue, "a = hash noise in [0,1]"},
  {"spline", 3, kVariadic, 1, 0, kArith, "a = spline(\"basis\", x, knots... | knot array)"},
  {"splineinverse", 3, kVariadic, 1, 0, kArith, "a = inverse of a monotonic float spline"},
  {"texture", 4, kVariadic, 1, 12, kPropagates, "a = texture(\"file\", s, t, [dsdx dtdx dsdy dtdy], \"kw\" v...)"},
  {"texture3d", 3, kVariadic, 1, 4, kPropagates, "a = texture3d(\"file\", P, \"kw\" v...)"},
  {"environment", 3, kVariadic, 1, 4, kPropagates, "a = environment(\"file\", R, \"kw\" v...)"},
  {"gettextureinfo", 4, 6, 3, 0, kEffect, "int a = query (last) of texture c [at UDIM s t] into b (reports errors)"},
  // ---- strings and messages ------------------------------------------------------------------
  {"printf", 1, kVariadic, 0, 0, kEffect, "print format a with args (OSL format rules)"},
  {"format", 2, kVariadic, 1, 0, kPure, "string a = format b with args"},
  {"error", 1, kVariadic, 0, 0, kEffect, "report a runtime error with format a"},
  {"warning", 1, kVariadic, 0, 0, kEffect, "report a runtime warning with format a"},
  {"fprintf", 2, kVariadic, 0, 0, kEffect, "append formatted text to file a"},
  {"concat", 2, kVariadic, 1, 0, kPure, "string a = b + c + ..."},
  {"strlen", 2, 2, 1, 0, kPure, "int a = length of b"},
  {"startswith", 3, 3, 1, 0, kPure, "int a = b starts with c"},
  {"endswith", 3, 3, 1, 0, kPure, "int a = b ends with c"},
  {"stoi", 2, 2, 1, 0, kPure, "int a = atoi(b)"}, {"stof", 2, 2, 1, 0, kPure, "float a = atof(b)"},
  {"substr", 3, 4, 1, 0, kPure, "string a = b.substr(c [, d])"},
  {"getchar", 3, 3, 1, 0, kPure, "int a = byte c of b"},
  {"hash", 2, 3, 1, 0, kPure, "int a = hash of b"},
  {"regex_search", 3, 4, 1, 0, 0, "int a = regex search (subject, [results,] pattern)"},
  {"regex_match", 3, 4, 1, 0, 0, "int a = regex match"},
  {"split",        3, 5, 3, 0, 0, "int a = pieces of c split at d (\"\": whitespace), at most e, into string array b"},
  {"dict_find",    3, 3, 1, 0, kEffect, "int a = first node matching XPath c in XML document b (text or .xml file) or under node b"},
  {"dict_next",    2, 2, 1, 0, 0, "int a = node after b among the matches of its query (0: none)"},
  {"dict_value",   4, 4, 3, 0, 0, "int a = attribute d (\"\": the node's value) of node c, parsed into b"},
  {"pointcloud_search", 5, kVariadic, 1, 0, kEffect, "int a = points of file b near c (radius d, at most e), \"attr\" dest[] pairs: none (no point clouds)"},
  {"pointcloud_get", 6, 6, 3, 0, kEffect, "int a = attribute f of points d[0..e) of file c into b: none (no point clouds)"},
  {"pointcloud_write", 3, kVariadic, 1, 0, kEffect, "int a = 1 if point c with \"attr\" value pairs was written to file b: 0 (no point clouds)"},
  {"getattribute", 3, 5, 3, 0, kEffect, "int a = renderer attribute into b: (\"obj\"?, \"name\", [index])"},
  {"setmessage", 2, 2, 0, 0, kEffect, "set message a to value b"},
  {"getmessage", 3, 4, 3, 0, kEffect, "int a = message (\"source\"?, \"name\") into b (remembered)"},
  {"trace", 3, kVariadic, 1, 6, kEffect, "int a = trace ray from b along c, \"kw\" v..."},
  // ---- shading-state queries ------------------------------------------------------------------
  {"raytype", 2, 2, 1, 0, 0, "int a = 1 if the ray has type name b"},
  {"backfacing", 1, 1, 1, 0, 0, "int a = ShaderGlobals::backfacing"},
  {"surfacearea", 1, 1, 1, 0, 0, "float a = ShaderGlobals::surfacearea"},
  {"isconnected", 2, 2, 1, 0, 0, "int a = 1 if param b is connected upstream, 2 downstream, 3 both"},
  {"isconstant", 2, 2, 1, 0, 0, "int a = 1 if b is a compile-time constant after specialisation"},
};
// clang-format on

// Looks an opcode up by name; null if unknown.
const OpcodeInfo* find_opcode(std::string_view name);
inline std::span<const OpcodeInfo> opcodes() { return kOpcodes; }

} // namespace lobe::ir

// The Lobe IR opcode table: every opcode the compiler emits and codegen implements, once.
//
// LOBE_OPCODES(X) lists one X(Enum, name, min_args, max_args, written, derivs, flags, doc) per
// opcode; it defines `enum class Opcode` (in table order) and kOpcodes (indexed by Opcode), so
// the two cannot drift. Columns:
//   Enum      the enumerator (Opcode::Add); passes, lowering and codegen compare and switch on it
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

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "library_calls.h"  // runtime/registry
#include "math_functions.h" // runtime/registry

namespace lobe::ir {

inline constexpr int kVariadic = -1;

enum OpFlags : uint8_t {
  kPropagates = 1u << 0,
  kPure = 1u << 1,
  kEffect = 1u << 2,
  kJump = 1u << 3,
};

inline constexpr uint8_t kArith = kPropagates | kPure; // value ops that carry derivatives
inline constexpr uint8_t kValue = kPure;               // value ops without derivatives

// A library call's opcode row: the result, then its OSL arguments; pure, no derivatives read.
#define LOBE_LIBRARY_OPCODE_ROW(X, e, name, R, P, fn, doc)                                         \
  X(e, name, 1 + library::kArity[int(library::Call::e)],                                           \
    1 + library::kArity[int(library::Call::e)], 1, 0, kValue, doc)

// A math function's opcode row: the result, then its arguments (up to max_operands in all);
// derivatives by the chain rule.
#define LOBE_MATH_OPCODE_ROW(X, e, name, arity, max, forms, doc)                                   \
  X(e, #name, 1 + arity, max, 1, 0, kArith, doc)

// clang-format off
#define LOBE_OPCODES(X) \
  /* ---- core: data movement and arithmetic */ \
  X(Nop,              "nop",               0, 0,         0, 0,  0,           "does nothing (left by passes)") \
  X(Assign,           "assign",            2, 2,         1, 0,  kArith,      "a = b, converting int->float->triple, float->matrix diagonal, int 0->null closure") \
  X(Add,              "add",               3, 3,         1, 0,  kArith,      "a = b + c (closures: sum of closures)") \
  X(Sub,              "sub",               3, 3,         1, 0,  kArith,      "a = b - c") \
  X(Mul,              "mul",               3, 3,         1, 0,  kArith,      "a = b * c (matrix product; closure scaled by float or color)") \
  X(Div,              "div",               3, 3,         1, 0,  kArith,      "a = b / c, 0 where c == 0 (matrix: b * inverse(c); matrix / float plainly)") \
  X(Mod,              "mod",               3, 3,         1, 0,  kArith,      "a = b % c: int remainder / fmod, 0 where c == 0") \
  X(Neg,              "neg",               2, 2,         1, 0,  kArith,      "a = -b (closure: scaled by -1)") \
  X(Eq,               "eq",                3, 3,         1, 0,  kValue,      "a = (b == c) as int 0/1; triples/matrices: all components") \
  X(Neq,              "neq",               3, 3,         1, 0,  kValue,      "a = (b != c) as int 0/1") \
  X(Lt,               "lt",                3, 3,         1, 0,  kValue,      "a = (b < c); int or float operands only") \
  X(Le,               "le",                3, 3,         1, 0,  kValue,      "a = (b <= c)") \
  X(Gt,               "gt",                3, 3,         1, 0,  kValue,      "a = (b > c)") \
  X(Ge,               "ge",                3, 3,         1, 0,  kValue,      "a = (b >= c)") \
  X(Not,              "not",               2, 2,         1, 0,  kValue,      "a = (b == 0) as int; b int, float or closure (null)") \
  X(Compl,            "compl",             2, 2,         1, 0,  kValue,      "a = ~b (ints)") \
  X(BitAnd,           "bitand",            3, 3,         1, 0,  kValue,      "a = b & c (ints)") \
  X(BitOr,            "bitor",             3, 3,         1, 0,  kValue,      "a = b | c (ints)") \
  X(Xor,              "xor",               3, 3,         1, 0,  kValue,      "a = b ^ c (ints)") \
  X(Shl,              "shl",               3, 3,         1, 0,  kValue,      "a = b << c (ints)") \
  X(Shr,              "shr",               3, 3,         1, 0,  kValue,      "a = b >> c (ints, arithmetic)") \
  /* ---- components, matrix elements, arrays */ \
  X(CompRef,          "compref",           3, 3,         1, 0,  kArith,      "a = triple b[c]; c clamped to 0..2, runtime error if out of range") \
  X(CompAssign,       "compassign",        3, 3,         1, 0,  kArith,      "triple a[b] = c; b clamped to 0..2 (a is read and written)") \
  X(MxCompRef,        "mxcompref",         4, 4,         1, 0,  kArith,      "a = matrix b[c][d]; indices clamped to 0..3") \
  X(MxCompAssign,     "mxcompassign",      4, 4,         1, 0,  kArith,      "matrix a[b][c] = d; indices clamped to 0..3") \
  X(ARef,             "aref",              3, 3,         1, 0,  kArith,      "a = array b[c]; c clamped to 0..len-1, runtime error if out of range") \
  X(AAssign,          "aassign",           3, 3,         1, 0,  kArith,      "array a[b] = c; b clamped (a is read and written)") \
  X(ArrayCopy,        "arraycopy",         2, 2,         1, 0,  kArith,      "array a = array b, same element type or triple kinds, min(len) elements") \
  X(ArrayLength,      "arraylength",       2, 2,         1, 0,  kValue,      "int a = number of elements of array b") \
  X(Construct,        "construct",         2, 18,        1, 0,  kArith,      "a = triple/matrix from components, optional leading space name") \
  /* ---- closures */ \
  X(Closure,          "closure",           2, kVariadic, 1, 0,  kPure,       "a = closure \"key\" positional... \"kw\" value...; weight 1") \
  X(DeclaredClosure,  "declared_closure",  2, kVariadic, 1, 0,  kPure,       "a = closure the shader declared [[ builtin = 1 ]]: \"name\", npos, positional... \"kw\" value...; laid out by the operands' types") \
  /* ---- control flow and bookkeeping */ \
  X(Br,               "br",                0, 0,         0, 0,  kJump,       "jump to jumps[0]") \
  X(Cbr,              "cbr",               1, 1,         0, 0,  kJump,       "if a != 0 jump to jumps[0] else to jumps[1]") \
  X(Exit,             "exit",              0, 0,         0, 0,  kJump,       "end the shader (the layer) now") \
  X(UseParam,         "useparam",          1, kVariadic, 0, 0,  kEffect,     "the params listed are about to be read: run upstream layers") \
  /* ---- derivatives */ \
  X(Dx,               "Dx",                2, 2,         1, 2,  kValue,      "a = d b / dx (float or triple); no derivatives of its own") \
  X(Dy,               "Dy",                2, 2,         1, 2,  kValue,      "a = d b / dy") \
  X(Dz,               "Dz",                2, 2,         1, 2,  kValue,      "a = d b / dz (0 outside volumes)") \
  X(FilterWidth,      "filterwidth",       2, 2,         1, 2,  kValue,      "a = sqrt(Dx(b)^2 + Dy(b)^2) per component") \
  X(Area,             "area",              2, 2,         1, 2,  kValue,      "a = length(cross(Dx(b), Dy(b))) for point b") \
  X(CalculateNormal,  "calculatenormal",   2, 2,         1, 2,  kValue,      "a = cross(Dx(b), Dy(b)), flipped by flip_handedness") \
  /* ---- math library (one float or per-component over triples) */ \
  X(SinCos,           "sincos",            3, 3,         3, 0,  kArith,      "a = sin c, b = cos c") \
  X(Sqrt,             "sqrt",              2, 2,         1, 0,  kArith,      "a = sqrt b (0 for b < 0)") \
  X(InverseSqrt,      "inversesqrt",       2, 2,         1, 0,  kArith,      "a = 1/sqrt b (0 for b <= 0)") \
  X(Hypot,            "hypot",             3, 4,         1, 0,  kArith,      "a = sqrt(b^2 + c^2 [+ d^2])") \
  X(Abs,              "abs",               2, 2,         1, 0,  kArith,      "a = |b| (int or float-based)") \
  X(Fabs,             "fabs",              2, 2,         1, 0,  kArith,      "a = |b|") \
  X(Sign,             "sign",              2, 2,         1, 0,  kArith,      "a = -1, 0 or 1") \
  X(Floor,            "floor",             2, 2,         1, 0,  kArith,      "a = floor b") \
  X(Ceil,             "ceil",              2, 2,         1, 0,  kArith,      "a = ceil b") \
  X(Round,            "round",             2, 2,         1, 0,  kArith,      "a = round b (half away from 0)") \
  X(Trunc,            "trunc",             2, 2,         1, 0,  kArith,      "a = trunc b") \
  X(Min,              "min",               3, 3,         1, 0,  kArith,      "a = min(b, c)") \
  X(Max,              "max",               3, 3,         1, 0,  kArith,      "a = max(b, c)") \
  X(Clamp,            "clamp",             4, 4,         1, 0,  kArith,      "a = min(max(b, c), d)") \
  X(Mix,              "mix",               4, 4,         1, 0,  kArith,      "a = b*(1-d) + c*d") \
  X(Select,           "select",            4, 4,         1, 0,  kArith,      "a = d != 0 ? c : b (per component if d is a triple)") \
  X(Step,             "step",              3, 3,         1, 0,  kArith,      "a = c < b ? 0 : 1") \
  X(SmoothStep,       "smoothstep",        4, 4,         1, 0,  kArith,      "a = smoothstep(b, c, d)") \
  X(IsNan,            "isnan",             2, 2,         1, 0,  kValue,      "int a = isnan b") \
  X(IsInf,            "isinf",             2, 2,         1, 0,  kValue,      "int a = isinf b") \
  X(IsFinite,         "isfinite",          2, 2,         1, 0,  kValue,      "int a = isfinite b") \
  /* ---- geometry, colour, matrices */ \
  X(Dot,              "dot",               3, 3,         1, 0,  kArith,      "a = dot(b, c)") \
  X(Cross,            "cross",             3, 3,         1, 0,  kArith,      "a = cross(b, c)") \
  X(Length,           "length",            2, 2,         1, 0,  kArith,      "a = |b|") \
  X(Distance,         "distance",          3, 4,         1, 0,  kArith,      "a = |b - c| (or to segment b-c, point d)") \
  X(Normalize,        "normalize",         2, 2,         1, 0,  kArith,      "a = b / |b| (0 for a zero vector)") \
  X(Transform,        "transform",         3, 4,         1, 0,  kArith,      "a = b..c transformed by matrix or space name(s); point/vector/normal rules by the last operand's type") \
  X(TransformU,       "transformu",        3, 4,         1, 0,  kArith,      "a = unit conversion (\"from\", \"to\", x)") \
  X(TransformC,       "transformc",        3, 4,         1, 0,  kArith,      "a = colour c (or d) converted from space b (or b to c)") \
  X(Luminance,        "luminance",         2, 2,         1, 0,  kArith,      "float a = luminance of colour b (Rec.709 weights)") \
  X(Blackbody,        "blackbody",         2, 2,         1, 0,  kArith,      "colour a = blackbody emission at b kelvin") \
  X(WavelengthColor,  "wavelength_color",  2, 2,         1, 0,  kArith,      "colour a = colour of wavelength b nm") \
  X(Determinant,      "determinant",       2, 2,         1, 0,  kArith,      "float a = det matrix b") \
  X(Transpose,        "transpose",         2, 2,         1, 0,  kArith,      "a = transpose b") \
  X(GetMatrix,        "getmatrix",         4, 4,         1, 0,  0,           "int a = 1 if matrix b from space c to d is known") \
  /* ---- noise, splines, textures */ \
  X(Noise,            "noise",             2, kVariadic, 1, 0,  kArith,      "a = noise(\"type\"?, coords..., [period...]) in [0,1]") \
  X(SNoise,           "snoise",            2, 4,         1, 0,  kArith,      "a = signed Perlin noise in [-1,1]") \
  X(PNoise,           "pnoise",            3, kVariadic, 1, 0,  kArith,      "a = periodic noise (coords..., periods...)") \
  X(PSNoise,          "psnoise",           3, 5,         1, 0,  kArith,      "a = periodic signed noise") \
  X(CellNoise,        "cellnoise",         2, 4,         1, 0,  kValue,      "a = cell noise (piecewise constant)") \
  X(HashNoise,        "hashnoise",         2, 4,         1, 0,  kValue,      "a = hash noise in [0,1]") \
  X(Spline,           "spline",            3, kVariadic, 1, 0,  kArith,      "a = spline(\"basis\", x, knots... | knot array)") \
  X(SplineInverse,    "splineinverse",     3, kVariadic, 1, 0,  kArith,      "a = inverse of a monotonic float spline") \
  X(Texture,          "texture",           4, kVariadic, 1, 12, kPropagates, "a = texture(\"file\", s, t, [dsdx dtdx dsdy dtdy], \"kw\" v...)") \
  X(Texture3d,        "texture3d",         3, kVariadic, 1, 4,  kPropagates, "a = texture3d(\"file\", P, \"kw\" v...)") \
  X(Environment,      "environment",       3, kVariadic, 1, 4,  kPropagates, "a = environment(\"file\", R, \"kw\" v...)") \
  X(GetTextureInfo,   "gettextureinfo",    4, 6,         3, 0,  kEffect,     "int a = query (last) of texture c [at UDIM s t] into b (reports errors)") \
  /* ---- strings and messages */ \
  X(Printf,           "printf",            1, kVariadic, 0, 0,  kEffect,     "print format a with args (OSL format rules)") \
  X(Format,           "format",            2, kVariadic, 1, 0,  kPure,       "string a = format b with args") \
  X(Error,            "error",             1, kVariadic, 0, 0,  kEffect,     "report a runtime error with format a") \
  X(Warning,          "warning",           1, kVariadic, 0, 0,  kEffect,     "report a runtime warning with format a") \
  X(Fprintf,          "fprintf",           2, kVariadic, 0, 0,  kEffect,     "append formatted text to file a") \
  X(Concat,           "concat",            2, kVariadic, 1, 0,  kPure,       "string a = b + c + ...") \
  X(Substr,           "substr",            3, 4,         1, 0,  kPure,       "string a = b.substr(c [, d])") \
  X(Hash,             "hash",              2, 3,         1, 0,  kPure,       "int a = hash of b") \
  X(RegexSearch,      "regex_search",      3, 4,         1, 0,  0,           "int a = regex search (subject, [results,] pattern)") \
  X(RegexMatch,       "regex_match",       3, 4,         1, 0,  0,           "int a = regex match") \
  X(Split,            "split",             3, 5,         3, 0,  0,           "int a = pieces of c split at d (\"\": whitespace), at most e, into string array b") \
  X(DictFind,         "dict_find",         3, 3,         1, 0,  kEffect,     "int a = first node matching XPath c in XML document b (text or .xml file) or under node b") \
  X(DictNext,         "dict_next",         2, 2,         1, 0,  0,           "int a = node after b among the matches of its query (0: none)") \
  X(DictValue,        "dict_value",        4, 4,         3, 0,  0,           "int a = attribute d (\"\": the node's value) of node c, parsed into b") \
  X(PointcloudSearch, "pointcloud_search", 5, kVariadic, 1, 0,  kEffect,     "int a = points of file b near c (radius d, at most e), \"attr\" dest[] pairs: none (no point clouds)") \
  X(PointcloudGet,    "pointcloud_get",    6, 6,         3, 0,  kEffect,     "int a = attribute f of points d[0..e) of file c into b: none (no point clouds)") \
  X(PointcloudWrite,  "pointcloud_write",  3, kVariadic, 1, 0,  kEffect,     "int a = 1 if point c with \"attr\" value pairs was written to file b: 0 (no point clouds)") \
  X(GetAttribute,     "getattribute",      3, 5,         3, 0,  kEffect,     "int a = renderer attribute into b: (\"obj\"?, \"name\", [index])") \
  X(SetMessage,       "setmessage",        2, 2,         0, 0,  kEffect,     "set message a to value b") \
  X(GetMessage,       "getmessage",        3, 4,         3, 0,  kEffect,     "int a = message (\"source\"?, \"name\") into b (remembered)") \
  X(Trace,            "trace",             3, kVariadic, 1, 6,  kEffect,     "int a = trace ray from b along c, \"kw\" v...") \
  /* ---- shading-state queries */ \
  X(RayType,          "raytype",           2, 2,         1, 0,  0,           "int a = 1 if the ray has type name b") \
  X(Backfacing,       "backfacing",        1, 1,         1, 0,  0,           "int a = ShaderGlobals::backfacing") \
  X(SurfaceArea,      "surfacearea",       1, 1,         1, 0,  0,           "float a = ShaderGlobals::surfacearea") \
  X(IsConnected,      "isconnected",       2, 2,         1, 0,  0,           "int a = 1 if param b is connected upstream, 2 downstream, 3 both") \
  X(IsConstant,       "isconstant",        2, 2,         1, 0,  0,           "int a = 1 if b is a compile-time constant after specialisation") \
  /* ---- math functions: one row each in math_functions.h */ \
  LOBE_MATH_FUNCTIONS(LOBE_MATH_OPCODE_ROW, X) \
  /* ---- library calls: one row each in library_calls.h */ \
  LOBE_LIBRARY_CALLS(LOBE_LIBRARY_OPCODE_ROW, X)
// clang-format on

enum class Opcode : uint16_t {
#define LOBE_OPCODE_ENUM(e, ...) e,
  LOBE_OPCODES(LOBE_OPCODE_ENUM)
#undef LOBE_OPCODE_ENUM
};

struct OpcodeInfo {
  Opcode op;
  const char* name;
  int8_t min_args;
  int8_t max_args;
  uint32_t written;
  uint32_t derivs;
  uint8_t flags;
  const char* doc;
};

inline constexpr OpcodeInfo kOpcodes[] = {
#define LOBE_OPCODE_ROW(e, name, min, max, written, derivs, flags, doc)                            \
  {Opcode::e, name, min, max, written, derivs, flags, doc},
    LOBE_OPCODES(LOBE_OPCODE_ROW)
#undef LOBE_OPCODE_ROW
};
inline constexpr size_t kOpcodeCount = std::size(kOpcodes);

// The row of an opcode (every enumerator has one: the table defines the enum).
constexpr const OpcodeInfo& info(Opcode op) { return kOpcodes[size_t(op)]; }
constexpr const char* to_string(Opcode op) { return info(op).name; }
constexpr bool is_jump(Opcode op) { return info(op).flags & kJump; }

// The opcode printed as `name`; nullopt if no opcode has that name.
std::optional<Opcode> opcode_from_name(std::string_view name);
inline std::span<const OpcodeInfo> opcodes() { return kOpcodes; }

} // namespace lobe::ir

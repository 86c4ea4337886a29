// Lobe IR: the compiler's output and the runtime's input.
//
// A shader is a flat list of typed symbols and a list of operations over them, in the spirit of
// OSL's .oso: every value lives in a named symbol (no SSA; codegen turns symbols into allocas
// and LLVM's mem2reg makes SSA), user functions are inlined by the front end, structs are
// flattened into one symbol per field ("s.a", "s.b"; arrays of structs into arrays per field),
// and control flow is explicit jumps between op indices. This keeps the IR easy to print, parse,
// hash, specialise (an instance value is a Param turned Const) and lower to LLVM.
//
// The text form (printed by `lobe compile --emit=ir`, parsed back by ir_parse) is described in
// docs/ir.md. print(parse(print(ir))) == print(ir) is a tested invariant.
#pragma once

#include "ir/opcodes.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lobe::ir {

// Base types of symbols. Point/Vector/Normal/Color are all three floats but transform
// differently; Matrix is 16 floats, row-major (OSL's convention: points are row vectors).
enum class BaseType : uint8_t { Int, Float, Color, Point, Vector, Normal, Matrix, String, Closure };

const char* to_string(BaseType t);
std::optional<BaseType> base_type_from_string(const std::string& s);

struct Type {
  BaseType base = BaseType::Float;
  int arraylen = 0; // 0: not an array; > 0: fixed length; -1: unsized array parameter

  bool is_array() const { return arraylen != 0; }
  bool is_triple() const {
    return base == BaseType::Color || base == BaseType::Point || base == BaseType::Vector ||
           base == BaseType::Normal;
  }
  int components() const; // floats/ints per element: 1, 3, 16; strings and closures: 1
  friend bool operator==(const Type&, const Type&) = default;
};
std::string to_string(const Type& t);    // "float", "color[3]", "float[]"
std::string array_suffix(const Type& t); // "", "[3]", "[]"

enum class SymKind : uint8_t {
  Param,       // shader parameter (instance value, connection or default)
  OutputParam, // `output` shader parameter
  Global,      // shading global (P, N, Ci, u, ...): name is the global's name
  Local,       // named local variable (possibly a flattened struct field, "s.a")
  Temp,        // compiler temporary ("$t12")
  Const,       // literal constant ("$c3"), value in `init`
};
const char* to_string(SymKind k);

// A constant element: ints and floats are stored in `f`/`i` by the symbol's base type, strings
// in `s`. A triple/matrix/array constant has one ConstValue per scalar component, in order.
struct ConstValue {
  int32_t i = 0;
  float f = 0.0f;
  std::string s;
  static ConstValue of_int(int32_t v) {
    ConstValue c;
    c.i = v;
    return c;
  }
  static ConstValue of_float(float v) {
    ConstValue c;
    c.f = v;
    return c;
  }
  static ConstValue of_string(std::string v) {
    ConstValue c;
    c.s = std::move(v);
    return c;
  }
  friend bool operator==(const ConstValue&, const ConstValue&) = default;
};

// One metadata item: `[[ string help = "text", float min = 0 ]]`, values kept as given.
struct Metadata {
  Type type;
  std::string name;
  std::vector<ConstValue> value;
  friend bool operator==(const Metadata&, const Metadata&) = default;
};

struct SourceLoc {
  std::string file; // empty: unknown
  int line = 0;
  int column = 0;
  friend bool operator==(const SourceLoc&, const SourceLoc&) = default;
};

struct Symbol {
  std::string name;
  Type type;
  SymKind kind = SymKind::Temp;
  bool derivs = false;          // carries d/dx and d/dy (set by the derivative analysis)
  std::vector<ConstValue> init; // Const: the value. Param/OutputParam: the constant default,
                                // when the default is a constant expression.
  // Params whose default is not a constant: ops [init_begin, init_end) of Shader::ops compute
  // it; they run only when the parameter gets neither a connection nor an instance value.
  int init_begin = -1, init_end = -1;
  // An unsized array param (`float[]`) with a computed default: the default's length (a
  // constant default tells it by its value count). The runtime sizes the array per instance:
  // the instance value's length, else this (see docs/ir.md).
  int default_len = 0;
  std::vector<Metadata> metadata;
  std::string
      struct_name; // the flattened struct's type name for a struct-field param ("" otherwise)
  // A param whose constant `init` Lobe folded from an expression that oslc keeps as code
  // (`float(3)`, `2 * 3.5`, `S(1, c)`, an array field of a struct): OSL's tools report such a
  // default as unknown, and so does `lobe info` (the value still serves as the default).
  bool folded = false;
  // An output parameter nothing reads: no connection takes it downstream and the group's
  // renderer outputs do not name it. The group builder marks it at -O2 (OSL's elision of
  // unconnected outputs) so that dead-code elimination drops what only computes it.
  bool unread = false;
  SourceLoc loc;
};

// The value of a constant string symbol (not an array), or null for any other symbol.
inline const std::string* string_value(const Symbol& s) {
  bool string = s.kind == SymKind::Const && s.type.base == BaseType::String && !s.type.is_array();
  return string && !s.init.empty() ? &s.init[0].s : nullptr;
}

// A struct type of a struct parameter, for the interface listing (`lobe info`): the params are
// flattened into one symbol per leaf field, and this keeps the fields' order, types and nesting.
struct StructField {
  std::string name;
  Type type;               // for a struct-typed field only `arraylen` counts
  std::string struct_name; // the field's struct type, "" for a field of a base type
  friend bool operator==(const StructField&, const StructField&) = default;
};
struct StructType {
  std::string name;
  std::vector<StructField> fields;
  friend bool operator==(const StructType&, const StructType&) = default;
};

// An operation: `opcode dst src...`. The opcode is one of the table in ir/opcodes.h: the core
// ops listed in docs/ir.md (assign, add, ..., br, cbr, exit, nop) or a standard-library
// function (sin, noise, printf, ...) resolved by codegen from the argument types.
struct Op {
  Opcode opcode = Opcode::Nop;
  std::vector<int> args;     // symbol indices; by convention written args come first
  uint32_t written_mask = 0; // bit i set: args[i] is written by this op
  std::vector<int> jumps;    // op indices (br: {target}; cbr: {if_true, if_false})
  SourceLoc loc;
  // An `assign` the optimiser made of an arithmetic identity (x * 1, x + 0 become x), not a copy
  // as written: OSL's layer elision does not take it for a copy of a global (group_build.cpp).
  // Not part of the IR text.
  bool identity_copy = false;
  // Emitted inside the body of an inlined user function, or the store of a call's result into
  // the variable it is assigned to (`o = g()`: oslc returns into `o` from inside the body). OSL's
  // runtime optimiser counts such an op as conditional (a function body lies between its
  // `functioncall` op and that op's jump target), so an output written there is not known to it
  // (in_conditional). Printed as `%infn`.
  bool in_function = false;
  // How many inlined user function calls have their body begin at this op: OSL numbers a
  // `functioncall` op before each (debug_uninit's op numbers). Not part of the IR text.
  int calls_begin = 0;
  // A `br` for a `return` before the end of an inlined function's body: OSL numbers it as its
  // `return` op (the last statement's return falls through, with no op). Not part of the IR text.
  bool osl_return = false;

  bool writes(int argi) const { return (written_mask >> argi) & 1u; }
};

enum class ShaderType : uint8_t { Surface, Displacement, Volume, Shader };
const char* to_string(ShaderType t);

struct Shader {
  ShaderType type = ShaderType::Surface;
  std::string name;
  std::vector<Metadata> metadata; // shader-level metadata
  // The struct types of struct parameters, each after the structs its fields use.
  std::vector<StructType> structs;
  std::vector<Symbol> symbols;
  // The main body starts at op `main_begin` and runs to the end; ops before it are the
  // parameter default initialisers referenced by Symbol::init_begin/init_end.
  std::vector<Op> ops;
  int main_begin = 0;
  // Reads of connected params are announced by `useparam` ops (lowering writes them; the text
  // parser sets this when it reads one). Without, codegen fetches the connections a layer reads
  // when it starts. Specialisation may remove every useparam op and keeps this set.
  bool useparams = false;

  int find_symbol(const std::string& name) const;               // -1 if absent
  const StructType* find_struct(const std::string& name) const; // null if absent
};

// The optional `"keyword", value` arguments of texture(), texture3d() and environment(), and of
// noise("gabor", ...) (OSL's NoiseParams), with the type each takes (OSL's): a float one takes
// an int too, a colour or vector one any triple (no number); `output` ones are written by the
// lookup (an lvalue of that type); `or_string` ("subimage") takes a name too. Null for a name
// they do not take. The type checker accepts any pair, as oslc does, converting only values
// that fit; the group builder drops a pair that does not, with OSL's message (builtin_option).
struct KeywordOption {
  const char* name;
  BaseType type;
  bool output = false;
  bool or_string = false;
};
const KeywordOption* texture_option(std::string_view name);
const KeywordOption* gabor_option(std::string_view name);
// Whether a value of type `t` (`written`: the op writes that operand) fits option `o`.
bool option_fits(const KeywordOption& o, const Type& t, bool written);
// The operand index of the first "keyword" of a texture, texture3d or environment op (after the
// explicit derivatives, when given).
size_t first_texture_option(const Shader& sh, const Op& op);

// Whether op `at` of the main code lies inside a conditional construct (an if or else branch, a
// loop's body), as OSL's runtime optimiser counts it: between a `cbr` and the join its branches
// reach (a branch's jumps forward past the join widen it), or between a loop's back edge and its
// target; or in an inlined function's body (Op::in_function). An early exit() or return before the
// op does not make it conditional.
bool in_conditional(const Shader& shader, int at);

} // namespace lobe::ir

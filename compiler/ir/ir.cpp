// Small helpers of the IR data structures: names of enums, type strings, symbol look-up, and
// the opcode table look-up (the table itself is in opcodes.h).
#include "ir/ir.h"
#include "ir/opcodes.h"

#include <algorithm>
#include <string_view>
#include <unordered_map>

namespace lobe::ir {

namespace {
const KeywordOption kTextureOptions[] = {
    {"blur", BaseType::Float},
    {"sblur", BaseType::Float},
    {"tblur", BaseType::Float},
    {"rblur", BaseType::Float},
    {"width", BaseType::Float},
    {"swidth", BaseType::Float},
    {"twidth", BaseType::Float},
    {"rwidth", BaseType::Float},
    {"wrap", BaseType::String},
    {"swrap", BaseType::String},
    {"twrap", BaseType::String},
    {"rwrap", BaseType::String},
    {"fill", BaseType::Float},
    {"firstchannel", BaseType::Int},
    {"subimage", BaseType::Int, false, true},
    {"interp", BaseType::String},
    {"missingcolor", BaseType::Color},
    {"missingalpha", BaseType::Float},
    {"time", BaseType::Float},
    {"alpha", BaseType::Float, true},
    {"errormessage", BaseType::String, true},
};
const KeywordOption kGaborOptions[] = {
    {"anisotropic", BaseType::Int}, {"do_filter", BaseType::Int},  {"direction", BaseType::Vector},
    {"bandwidth", BaseType::Float}, {"impulses", BaseType::Float},
};

template <size_t N>
const KeywordOption* find_option(const KeywordOption (&table)[N], std::string_view name) {
  for (const KeywordOption& o : table)
    if (name == o.name) return &o;
  return nullptr;
}
} // namespace

const KeywordOption* texture_option(std::string_view name) {
  return find_option(kTextureOptions, name);
}
const KeywordOption* gabor_option(std::string_view name) {
  return find_option(kGaborOptions, name);
}

bool option_fits(const KeywordOption& o, const Type& t, bool written) {
  if (t.is_array()) return false;
  if (o.output) return written && t.base == o.type;
  if (o.or_string && t.base == BaseType::String) return true;
  switch (o.type) {
  case BaseType::Float:
    return t.base == BaseType::Float || t.base == BaseType::Int;
  case BaseType::Color:
  case BaseType::Vector:
    return t.is_triple();
  default:
    return t.base == o.type;
  }
}

size_t first_texture_option(const Shader& sh, const Op& op) {
  // Operands: result, file, then s t [dsdx dtdx dsdy dtdy] (texture), P [dPdx dPdy dPdz]
  // (texture3d) or R [dRdx dRdy] (environment); derivatives are given when the operand after
  // the coordinates is not a keyword string.
  size_t coords = op.opcode == Opcode::Texture ? 4 : 3;
  size_t derivs = op.opcode == Opcode::Texture ? 4 : op.opcode == Opcode::Texture3d ? 3 : 2;
  bool given = op.args.size() >= coords + derivs &&
               sh.symbols[size_t(op.args[coords])].type.base != BaseType::String;
  return given ? coords + derivs : coords;
}

const char* to_string(BaseType t) {
  switch (t) {
  case BaseType::Int:
    return "int";
  case BaseType::Float:
    return "float";
  case BaseType::Color:
    return "color";
  case BaseType::Point:
    return "point";
  case BaseType::Vector:
    return "vector";
  case BaseType::Normal:
    return "normal";
  case BaseType::Matrix:
    return "matrix";
  case BaseType::String:
    return "string";
  case BaseType::Closure:
    return "closure";
  }
  return "?";
}

std::optional<BaseType> base_type_from_string(const std::string& s) {
  static constexpr BaseType kAll[] = {BaseType::Int,    BaseType::Float,  BaseType::Color,
                                      BaseType::Point,  BaseType::Vector, BaseType::Normal,
                                      BaseType::Matrix, BaseType::String, BaseType::Closure};
  for (BaseType t : kAll)
    if (s == to_string(t)) return t;
  return std::nullopt;
}

int Type::components() const {
  if (is_triple()) return 3;
  if (base == BaseType::Matrix) return 16;
  return 1;
}

std::string array_suffix(const Type& t) {
  if (t.arraylen == 0) return "";
  return "[" + (t.arraylen > 0 ? std::to_string(t.arraylen) : std::string()) + "]";
}

std::string to_string(const Type& t) { return to_string(t.base) + array_suffix(t); }

const char* to_string(SymKind k) {
  switch (k) {
  case SymKind::Param:
    return "param";
  case SymKind::OutputParam:
    return "oparam";
  case SymKind::Global:
    return "global";
  case SymKind::Local:
    return "local";
  case SymKind::Temp:
    return "temp";
  case SymKind::Const:
    return "const";
  }
  return "?";
}

const char* to_string(ShaderType t) {
  switch (t) {
  case ShaderType::Surface:
    return "surface";
  case ShaderType::Displacement:
    return "displacement";
  case ShaderType::Volume:
    return "volume";
  case ShaderType::Shader:
    return "shader";
  }
  return "?";
}

bool in_conditional(const Shader& sh, int at) {
  if (at >= 0 && size_t(at) < sh.ops.size() && sh.ops[size_t(at)].in_function) return true;
  // A loop body: between a back edge's target and the back edge (a do-while's body comes before
  // its cbr, and for(;;) has none).
  for (size_t k = size_t(std::max(at, sh.main_begin)); k < sh.ops.size(); ++k)
    if (is_jump(sh.ops[k].opcode))
      for (int j : sh.ops[k].jumps)
        if (j <= at) return true;
  for (int c = sh.main_begin; c < at; ++c) {
    const Op& op = sh.ops[size_t(c)];
    if (op.opcode != Opcode::Cbr) continue;
    int end = c;
    for (int j : op.jumps) end = std::max(end, j);
    for (bool grew = true; grew;) {
      grew = false;
      for (int k = c + 1; k < end; ++k)
        if (is_jump(sh.ops[size_t(k)].opcode))
          for (int j : sh.ops[size_t(k)].jumps)
            if (j > end) end = j, grew = true;
    }
    if (at < end) return true;
  }
  return false;
}

int Shader::find_symbol(const std::string& n) const {
  for (size_t i = 0; i < symbols.size(); ++i)
    if (symbols[i].name == n) return static_cast<int>(i);
  return -1;
}

const StructType* Shader::find_struct(const std::string& n) const {
  for (const StructType& st : structs)
    if (st.name == n) return &st;
  return nullptr;
}

// By name, for the text parser and lowering (builtins named as opcodes); everything past them
// compares the enum.
std::optional<Opcode> opcode_from_name(std::string_view name) {
  static const std::unordered_map<std::string_view, Opcode> index = [] {
    std::unordered_map<std::string_view, Opcode> m;
    for (const OpcodeInfo& o : kOpcodes) m.emplace(o.name, o.op);
    return m;
  }();
  auto it = index.find(name);
  if (it == index.end()) return std::nullopt;
  return it->second;
}

// The table defines the enum, so row i is opcode i.
static_assert([] {
  for (size_t i = 0; i < kOpcodeCount; ++i)
    if (size_t(kOpcodes[i].op) != i) return false;
  return true;
}());

} // namespace lobe::ir

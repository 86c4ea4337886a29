// Names of AST enums and types, for diagnostics and dumps.
#include "ast/ast.h"

namespace lobe::ast {

const char* to_string(BaseType b) {
  switch (b) {
  case BaseType::Error:
    return "<error>";
  case BaseType::Void:
    return "void";
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
    return "closure color";
  case BaseType::Struct:
    return "struct";
  }
  return "?";
}

std::string to_string(const Type& t) {
  std::string s = t.base == BaseType::Struct && t.strct ? t.strct->name : to_string(t.base);
  if (t.arraylen > 0) s += "[" + std::to_string(t.arraylen) + "]";
  if (t.arraylen < 0) s += "[]";
  return s;
}

const char* to_string(BinaryOp op) {
  static const char* const kNames[] = {"+", "-", "*",  "/", "%",  "<<", ">>", "&",  "|",
                                       "^", "<", "<=", ">", ">=", "==", "!=", "&&", "||"};
  return kNames[int(op)];
}

const char* operator_name(BinaryOp op) {
  static const char* const kNames[] = {"add", "sub",    "mul",   "div", "mod", "shl",
                                       "shr", "bitand", "bitor", "xor", "lt",  "le",
                                       "gt",  "ge",     "eq",    "neq", "",    ""};
  return kNames[int(op)];
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

} // namespace lobe::ast

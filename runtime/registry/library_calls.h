// Library calls: the builtins that are one C function of plain values, each declared once, here.
//
// LOBE_LIBRARY_CALLS(M, x) lists one M(x, Enum, name, Result, (Params...), shadeop, doc) per
// function. Everything else about the function is derived from its row:
//   - its opcode: ir::Opcode::Enum, printed `name`, operands the result and then the
//     arguments, pure (LOBE_OPCODES includes these rows, opcodes.h);
//   - the type checker's signature `Result name(Params...)` (compiler/sema/builtins.cpp), so a
//     call resolves, type-checks and lowers to the opcode with no more code;
//   - the shadeop's C prototype (runtime/shadeops/shadeop_decls.h: the definition must match
//     it or the build fails), its row in the JIT's symbol table and its signature string
//     (runtime/shadeops/table.cpp);
//   - the code generator's call: each argument loaded as its C type, the shadeop called, the
//     result stored (runtime/codegen/ops_library.cpp, op_library_call);
//   - its line in the generated list of docs/language.md (`closure_docs --update
//     docs/language.md`; a test fails while the committed list differs).
// Adding one is its row plus the shadeop's definition, extern "C", in runtime/shadeops/.
//
// Parameter and result types, as OSL sees them and as the C function receives them:
//   Int     int              Float   float            String  const char* (interned)
//   Color, Point, Vector, Normal     const float* (the 3 components; parameters only)
//   Env     lobe::shadeops::RuntimeEnv* — the shading environment, for a function that makes
//           strings (env->strings.intern); first parameter only, and not an argument in OSL.
// Results are Int, Float or String and carry no derivatives. A function with outputs, arrays,
// keyword arguments, derivatives or several overloads has its own emitter instead
// (docs/architecture.md, "Adding things").
#pragma once

#include <cstddef>
#include <tuple>
#include <type_traits>

// clang-format off
#define LOBE_LIBRARY_CALLS(M, x) \
  M(x, Strlen,     "strlen",     Int,   (String),         lobe_strlen,     "the length of the string in bytes") \
  M(x, StartsWith, "startswith", Int,   (String, String), lobe_startswith, "1 if the string begins with the second, else 0") \
  M(x, EndsWith,   "endswith",   Int,   (String, String), lobe_endswith,   "1 if the string ends with the second, else 0") \
  M(x, Stoi,       "stoi",       Int,   (String),         lobe_stoi,       "the integer the string begins with (base 10, saturating to the int range; 0 if none)") \
  M(x, Stof,       "stof",       Float, (String),         lobe_stof,       "the number the string begins with (C's strtod; 0 if none)") \
  M(x, GetChar,    "getchar",    Int,   (String, Int),    lobe_getchar,    "the byte at an index of the string, 0 outside it")
// clang-format on

namespace lobe::ir::library {

// The type tags of the rows (unqualified in LOBE_LIBRARY_CALLS; expand it where these are
// visible, e.g. inside this namespace or after `using namespace lobe::ir::library`).
// Each names its OSL type (kName; none for Env).
#define LOBE_LIBRARY_TAG(T, name)                                                                  \
  struct T {                                                                                       \
    static constexpr const char* kName = name;                                                     \
  };
LOBE_LIBRARY_TAG(Int, "int")
LOBE_LIBRARY_TAG(Float, "float")
LOBE_LIBRARY_TAG(String, "string")
LOBE_LIBRARY_TAG(Color, "color")
LOBE_LIBRARY_TAG(Point, "point")
LOBE_LIBRARY_TAG(Vector, "vector")
LOBE_LIBRARY_TAG(Normal, "normal")
LOBE_LIBRARY_TAG(Env, nullptr)
#undef LOBE_LIBRARY_TAG

// The library calls in table order.
enum class Call : int {
#define LOBE_LIBRARY_ENUM_ROW(x, e, name, R, P, fn, doc) e,
  LOBE_LIBRARY_CALLS(LOBE_LIBRARY_ENUM_ROW, _)
#undef LOBE_LIBRARY_ENUM_ROW
};

template <class... P> constexpr bool first_is_env() {
  if constexpr (sizeof...(P) == 0)
    return false;
  else
    return std::is_same_v<std::tuple_element_t<0, std::tuple<P...>>, Env>;
}

// A parameter list (a function type `void (Params...)`): how many OSL arguments it has (Env is
// not one, and may only come first).
template <class F> struct ParamList;
template <class... P> struct ParamList<void(P...)> {
  static constexpr int kArity = (0 + ... + (std::is_same_v<P, Env> ? 0 : 1));
  static constexpr bool kEnv = first_is_env<P...>();
  static_assert(kArity + int(kEnv) == int(sizeof...(P)), "Env is only the first parameter");
};

inline constexpr int kArity[] = {
#define LOBE_LIBRARY_ARITY_ROW(x, e, name, R, P, fn, doc) ParamList<void P>::kArity,
    LOBE_LIBRARY_CALLS(LOBE_LIBRARY_ARITY_ROW, _)
#undef LOBE_LIBRARY_ARITY_ROW
};
inline constexpr size_t kCount = sizeof(kArity) / sizeof(kArity[0]);

// OSL's name of a tag type ("" for Env).
template <class T> constexpr const char* type_name() { return T::kName ? T::kName : ""; }

} // namespace lobe::ir::library

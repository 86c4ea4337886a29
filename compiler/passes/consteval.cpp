// Implements evaluate(): operands are first converted to the type the op computes in (the
// destination's for arithmetic, the wider source's for comparisons), then the op is applied
// per component.
#include "passes/consteval.h"
#include "hashword.h"
#include "mathops.h"

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <functional>

namespace lobe::passes {

using namespace ir;
using Values = std::vector<ConstValue>;

namespace {

bool is_num(const Type& t) {
  return !t.is_array() && (t.base == BaseType::Int || t.base == BaseType::Float);
}

// The wider of two comparable types (int < float < triple), or nullopt.
std::optional<Type> wider(const Type& a, const Type& b) {
  if (a.is_array() || b.is_array()) return std::nullopt;
  if (a == b) return a;
  auto rank = [](const Type& t) {
    return t.base == BaseType::Int ? 0 : t.base == BaseType::Float ? 1 : t.is_triple() ? 2 : -1;
  };
  int ra = rank(a), rb = rank(b);
  if (ra < 0 || rb < 0) return std::nullopt;
  if (ra == 2 && rb == 2) return a; // two different triples: compare as floats
  return ra >= rb ? a : b;
}

int32_t int_binop(const std::string& op, int32_t a, int32_t b, bool& ok) {
  int64_t x = a, y = b;
  if (op == "add") return int32_t(uint32_t(a) + uint32_t(b));
  if (op == "sub") return int32_t(uint32_t(a) - uint32_t(b));
  if (op == "mul") return int32_t(uint32_t(a) * uint32_t(b));
  if (op == "div") return b == 0 ? 0 : int32_t(x / y);
  if (op == "mod") return b == 0 ? 0 : int32_t(x % y);
  if (op == "bitand") return a & b;
  if (op == "bitor") return a | b;
  if (op == "xor") return a ^ b;
  if (op == "shl") return (b < 0 || b > 31) ? (ok = false, 0) : int32_t(uint32_t(a) << b);
  if (op == "shr") return (b < 0 || b > 31) ? (ok = false, 0) : (a >> b);
  if (op == "min") return std::min(a, b);
  if (op == "max") return std::max(a, b);
  ok = false;
  return 0;
}

// Float functions of one operand (math builtins as runtime/mathlib/mathops.h defines them).
std::function<float(float)> float_unop(const std::string& op, math::MathMode mode) {
  if (const math::FnInfo* f = math::find_fn(op, 1))
    return [fn = f->fn, mode](float a) { return math::value1(fn, mode, a); };
  if (op == "neg") return [](float a) { return -a; };
  if (op == "sqrt") return [](float a) { return math::sqrt(a); };
  if (op == "inversesqrt") return [](float a) { return math::inversesqrt(a); };
  if (op == "abs" || op == "fabs") return [](float a) { return std::fabs(a); };
  if (op == "sign") return [](float a) { return math::sign(a); };
  if (op == "floor") return [](float a) { return std::floor(a); };
  if (op == "ceil") return [](float a) { return std::ceil(a); };
  if (op == "round") return [](float a) { return std::round(a); };
  if (op == "trunc") return [](float a) { return std::trunc(a); };
  return nullptr;
}

std::function<float(float, float)> float_binop(const std::string& op, math::MathMode mode) {
  if (const math::FnInfo* f = math::find_fn(op, 2))
    return [fn = f->fn, mode](float a, float b) { return math::value2(fn, mode, a, b); };
  if (op == "add") return [](float a, float b) { return a + b; };
  if (op == "sub") return [](float a, float b) { return a - b; };
  if (op == "mul") return [](float a, float b) { return a * b; };
  if (op == "div") return [](float a, float b) { return math::div(a, b); };
  if (op == "mod") return [](float a, float b) { return math::fmod(a, b); };
  if (op == "min") return [](float a, float b) { return math::min(a, b); };
  if (op == "max") return [](float a, float b) { return math::max(a, b); };
  if (op == "step") return [](float a, float b) { return math::step(a, b); };
  if (op == "hypot") return [](float a, float b) { return math::sqrt(a * a + b * b); };
  if (op == "log") // log(a, base) = log(a) / log(base)
    return [mode](float a, float b) {
      return math::div(math::value1(math::Fn::Log, mode, a), math::value1(math::Fn::Log, mode, b));
    };
  return nullptr;
}

// Three operands, as codegen computes them (ops_math.cpp).
std::function<float(float, float, float)> float_ternop(const std::string& op) {
  if (op == "clamp") // the IR's clamp: min(max(x, lo), hi)
    return [](float x, float lo, float hi) { return math::min(math::max(x, lo), hi); };
  if (op == "mix") return [](float x, float y, float t) { return x * (1 - t) + y * t; };
  if (op == "select") return [](float x, float y, float c) { return c != 0 ? y : x; };
  if (op == "smoothstep")
    return [](float e0, float e1, float x) { return math::smoothstep(e0, e1, x); };
  if (op == "hypot")
    return [](float a, float b, float c) {
      float s = a * a + b * b;
      return math::sqrt(s + c * c);
    };
  return nullptr;
}

// Comparisons with codegen's rules: ints and strings exactly; floats unordered (a NaN makes
// every comparison true), triples by all components (==) or any (!=).
std::optional<Values> compare(const std::string& op, const std::vector<ConstArg>& s) {
  bool strings = s[0].type == Type{BaseType::String} && s[1].type == s[0].type;
  if (strings) { // compared by content: strings have no numeric value to widen
    if (op != "eq" && op != "neq") return std::nullopt;
    bool same = (*s[0].value)[0].s == (*s[1].value)[0].s;
    return Values{ConstValue::of_int(op == "eq" ? same : !same)};
  }
  auto t = wider(s[0].type, s[1].type);
  if (!t) return std::nullopt;
  auto a = convert_const(s[0].type, *s[0].value, *t);
  auto b = convert_const(s[1].type, *s[1].value, *t);
  if (!a || !b) return std::nullopt;
  if (t->base == BaseType::Int) {
    int32_t x = (*a)[0].i, y = (*b)[0].i;
    bool r = op == "eq"    ? x == y
             : op == "neq" ? x != y
             : op == "lt"  ? x < y
             : op == "le"  ? x <= y
             : op == "gt"  ? x > y
                           : x >= y;
    return Values{ConstValue::of_int(r)};
  }
  if (op == "eq" || op == "neq") {
    bool all_eq = true, any_ne = false;
    for (size_t i = 0; i < a->size(); ++i) {
      all_eq &= math::eq((*a)[i].f, (*b)[i].f);
      any_ne |= math::ne((*a)[i].f, (*b)[i].f);
    }
    return Values{ConstValue::of_int(op == "eq" ? all_eq : any_ne)};
  }
  if (t->is_triple()) return std::nullopt;
  float x = (*a)[0].f, y = (*b)[0].f;
  bool r = op == "lt"   ? math::lt(x, y)
           : op == "le" ? math::le(x, y)
           : op == "gt" ? math::gt(x, y)
                        : math::ge(x, y);
  return Values{ConstValue::of_int(r)};
}

// hash() of numbers: lookup3 over the bits of every component (runtime/mathlib/hashword.h).
std::optional<Values> hash(const std::vector<ConstArg>& s) {
  std::vector<uint32_t> words;
  for (const ConstArg& a : s) {
    if (a.type.is_array()) return std::nullopt;
    if (a.type.base == BaseType::Int)
      words.push_back(uint32_t((*a.value)[0].i));
    else if (a.type.base == BaseType::Float || a.type.is_triple())
      for (const ConstValue& c : *a.value) words.push_back(math::word_of(c.f));
    else
      return std::nullopt; // strings hash by OIIO's string hash, at run time
  }
  if (words.empty() || words.size() > 4) return std::nullopt;
  return Values{ConstValue::of_int(math::osl_hash(words.data(), int(words.size())))};
}

// Arithmetic in the destination type, sources converted to it.
std::optional<Values> arith(const std::string& op, const Type& dst, const std::vector<ConstArg>& s,
                            math::MathMode mode) {
  if (!(is_num(dst) || (dst.is_triple() && !dst.is_array()))) return std::nullopt;
  std::vector<Values> args;
  for (const ConstArg& a : s) {
    auto v = convert_const(a.type, *a.value, dst);
    if (!v) return std::nullopt;
    args.push_back(std::move(*v));
  }
  Values out(size_t(dst.components()));
  bool ok = true;
  for (size_t c = 0; c < out.size(); ++c) {
    if (dst.base == BaseType::Int) {
      if (args.size() == 1 && op == "neg")
        out[c] = ConstValue::of_int(int32_t(0u - uint32_t(args[0][c].i)));
      else if (args.size() == 1 && (op == "abs" || op == "fabs"))
        out[c] = ConstValue::of_int(args[0][c].i < 0 ? int32_t(0u - uint32_t(args[0][c].i))
                                                     : args[0][c].i);
      else if (args.size() == 1 && op == "compl")
        out[c] = ConstValue::of_int(~args[0][c].i);
      else if (args.size() == 1 && op == "sign")
        out[c] = ConstValue::of_int(args[0][c].i < 0 ? -1 : args[0][c].i > 0 ? 1 : 0);
      else if (args.size() == 2)
        out[c] = ConstValue::of_int(int_binop(op, args[0][c].i, args[1][c].i, ok));
      else
        return std::nullopt;
    } else if (args.size() == 1) {
      auto f = float_unop(op, mode);
      if (!f) return std::nullopt;
      out[c] = ConstValue::of_float(f(args[0][c].f));
    } else if (args.size() == 2) {
      auto f = float_binop(op, mode);
      if (!f) return std::nullopt;
      out[c] = ConstValue::of_float(f(args[0][c].f, args[1][c].f));
    } else if (args.size() == 3) {
      auto f = float_ternop(op);
      if (!f) return std::nullopt;
      out[c] = ConstValue::of_float(f(args[0][c].f, args[1][c].f, args[2][c].f));
    } else {
      return std::nullopt;
    }
  }
  if (!ok) return std::nullopt;
  return out;
}

} // namespace

std::optional<Values> convert_const(const Type& from, const Values& v, const Type& to) {
  if (from == to) return v;
  if (from.is_array() || to.is_array()) return std::nullopt;
  if (from.base == BaseType::Int && to.base == BaseType::Float)
    return Values{ConstValue::of_float(float(v[0].i))};
  if (from.base == BaseType::Float && to.base == BaseType::Int) {
    float f = v[0].f;
    if (!(std::fabs(f) < 2147483648.0f)) return std::nullopt; // undefined in C++: leave it
    return Values{ConstValue::of_int(int32_t(f))};
  }
  if (to.is_triple()) {
    if (from.is_triple()) return v;
    if (from.base == BaseType::Int) return Values(3, ConstValue::of_float(float(v[0].i)));
    if (from.base == BaseType::Float) return Values(3, ConstValue::of_float(v[0].f));
  }
  return std::nullopt;
}

std::optional<Values> evaluate(const std::string& op, const Type& dst,
                               const std::vector<ConstArg>& s, const EvalOptions& options) {
  if (op == "assign" && s.size() == 1) return convert_const(s[0].type, *s[0].value, dst);
  if ((op == "eq" || op == "neq" || op == "lt" || op == "le" || op == "gt" || op == "ge") &&
      s.size() == 2)
    return compare(op, s);
  if (op == "not" && s.size() == 1 && is_num(s[0].type)) {
    const ConstValue& c = (*s[0].value)[0];
    return Values{ConstValue::of_int(s[0].type.base == BaseType::Int ? c.i == 0 : c.f == 0)};
  }
  if (op == "compref" && s.size() == 2 && s[0].type.is_triple() && !s[0].type.is_array()) {
    int i = (*s[1].value)[0].i;
    if (i < 0 || i > 2) return std::nullopt; // keep the run-time range error
    return Values{(*s[0].value)[size_t(i)]};
  }
  if (op == "construct" && s.size() == 3 && dst.is_triple() && !dst.is_array()) {
    Values out;
    for (const ConstArg& a : s) {
      auto v = convert_const(a.type, *a.value, Type{BaseType::Float});
      if (!v) return std::nullopt;
      out.push_back((*v)[0]);
    }
    return out;
  }
  if (op == "strlen" && s.size() == 1 && s[0].type == Type{BaseType::String})
    return Values{ConstValue::of_int(int32_t((*s[0].value)[0].s.size()))};
  if (op == "concat" && dst == Type{BaseType::String}) {
    ConstValue c;
    for (const ConstArg& a : s) {
      if (!(a.type == Type{BaseType::String})) return std::nullopt;
      c.s += (*a.value)[0].s;
    }
    return Values{c};
  }
  if (op == "hash" && dst == Type{BaseType::Int}) return hash(s);
  if ((op == "isnan" || op == "isinf" || op == "isfinite") && s.size() == 1 &&
      s[0].type == Type{BaseType::Float}) {
    float x = (*s[0].value)[0].f;
    bool r = op == "isnan" ? std::isnan(x) : op == "isinf" ? std::isinf(x) : std::isfinite(x);
    return Values{ConstValue::of_int(r)};
  }
  // Operators and the math library (per component, in the destination type).
  static const char* kArith[] = {
      "add",   "sub",    "mul",  "div",        "mod",         "neg",  "compl", "bitand", "bitor",
      "xor",   "shl",    "shr",  "sin",        "cos",         "tan",  "asin",  "acos",   "atan",
      "atan2", "sinh",   "cosh", "tanh",       "pow",         "exp",  "exp2",  "expm1",  "log",
      "log2",  "log10",  "logb", "sqrt",       "inversesqrt", "cbrt", "hypot", "abs",    "fabs",
      "sign",  "floor",  "ceil", "round",      "trunc",       "fmod", "min",   "max",    "clamp",
      "mix",   "select", "step", "smoothstep", "erf",         "erfc"};
  for (const char* a : kArith)
    if (op == a)
      return arith(op, dst, s, options.fast_math ? math::MathMode::Fast : math::MathMode::Exact);
  return std::nullopt;
}

} // namespace lobe::passes

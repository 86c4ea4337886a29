// Implements evaluate(): operands are first converted to the type the op computes in (the
// destination's for arithmetic, the wider source's for comparisons), then the op is applied
// per component.
#include "passes/consteval.h"
#include "hashword.h"
#include "mathops.h"
#include "passes/math_opcode.h"

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>

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

int32_t int_binop(Opcode op, int32_t a, int32_t b, bool& ok) {
  int64_t x = a, y = b;
  if (op == Opcode::Add) return int32_t(uint32_t(a) + uint32_t(b));
  if (op == Opcode::Sub) return int32_t(uint32_t(a) - uint32_t(b));
  if (op == Opcode::Mul) return int32_t(uint32_t(a) * uint32_t(b));
  if (op == Opcode::Div) return b == 0 ? 0 : int32_t(x / y);
  if (op == Opcode::Mod) return b == 0 ? 0 : int32_t(x % y);
  if (op == Opcode::BitAnd) return a & b;
  if (op == Opcode::BitOr) return a | b;
  if (op == Opcode::Xor) return a ^ b;
  if (op == Opcode::Shl) return (b < 0 || b > 31) ? (ok = false, 0) : int32_t(uint32_t(a) << b);
  if (op == Opcode::Shr) return (b < 0 || b > 31) ? (ok = false, 0) : (a >> b);
  if (op == Opcode::Min) return std::min(a, b);
  if (op == Opcode::Max) return std::max(a, b);
  ok = false;
  return 0;
}

// Float functions of one operand (math builtins as runtime/mathlib/mathops.h defines them).
std::function<float(float)> float_unop(Opcode op, math::MathMode mode) {
  if (const math::FnInfo* f = math_fn(op, 1))
    return [fn = f->fn, mode](float a) { return math::value1(fn, mode, a); };
  if (op == Opcode::Neg) return [](float a) { return -a; };
  if (op == Opcode::Sqrt) return [](float a) { return math::sqrt(a); };
  if (op == Opcode::InverseSqrt) return [](float a) { return math::inversesqrt(a); };
  if (op == Opcode::Abs || op == Opcode::Fabs) return [](float a) { return std::fabs(a); };
  if (op == Opcode::Sign) return [](float a) { return math::sign(a); };
  if (op == Opcode::Floor) return [](float a) { return std::floor(a); };
  if (op == Opcode::Ceil) return [](float a) { return std::ceil(a); };
  if (op == Opcode::Round) return [](float a) { return std::round(a); };
  if (op == Opcode::Trunc) return [](float a) { return std::trunc(a); };
  return nullptr;
}

std::function<float(float, float)> float_binop(Opcode op, math::MathMode mode) {
  if (const math::FnInfo* f = math_fn(op, 2))
    return [fn = f->fn, mode](float a, float b) { return math::value2(fn, mode, a, b); };
  if (op == Opcode::Add) return [](float a, float b) { return a + b; };
  if (op == Opcode::Sub) return [](float a, float b) { return a - b; };
  if (op == Opcode::Mul) return [](float a, float b) { return a * b; };
  if (op == Opcode::Div) return [](float a, float b) { return math::div(a, b); };
  if (op == Opcode::Mod) return [](float a, float b) { return math::fmod(a, b); };
  if (op == Opcode::Min) return [](float a, float b) { return math::min(a, b); };
  if (op == Opcode::Max) return [](float a, float b) { return math::max(a, b); };
  if (op == Opcode::Step) return [](float a, float b) { return math::step(a, b); };
  if (op == Opcode::Hypot) return [](float a, float b) { return math::sqrt(a * a + b * b); };
  if (op == Opcode::Log) // log(a, base) = log(a) / log(base)
    return [mode](float a, float b) {
      return math::div(math::value1(math::Fn::Log, mode, a), math::value1(math::Fn::Log, mode, b));
    };
  return nullptr;
}

// Three operands, as codegen computes them (ops_math.cpp).
std::function<float(float, float, float)> float_ternop(Opcode op) {
  if (op == Opcode::Clamp) // the IR's clamp: min(max(x, lo), hi)
    return [](float x, float lo, float hi) { return math::min(math::max(x, lo), hi); };
  if (op == Opcode::Mix) return [](float x, float y, float t) { return x * (1 - t) + y * t; };
  if (op == Opcode::Select) return [](float x, float y, float c) { return c != 0 ? y : x; };
  if (op == Opcode::SmoothStep)
    return [](float e0, float e1, float x) { return math::smoothstep(e0, e1, x); };
  if (op == Opcode::Hypot)
    return [](float a, float b, float c) {
      float s = a * a + b * b;
      return math::sqrt(s + c * c);
    };
  return nullptr;
}

// Comparisons with codegen's rules: ints and strings exactly; floats unordered (a NaN makes
// every comparison true), or as C with `c_compares`; triples by all components (==) or any (!=).
std::optional<Values> compare(Opcode op, const std::vector<ConstArg>& s, bool c_compares) {
  bool strings = s[0].type == Type{BaseType::String} && s[1].type == s[0].type;
  if (strings) { // compared by content: strings have no numeric value to widen
    if (op != Opcode::Eq && op != Opcode::Neq) return std::nullopt;
    bool same = (*s[0].value)[0].s == (*s[1].value)[0].s;
    return Values{ConstValue::of_int(op == Opcode::Eq ? same : !same)};
  }
  auto t = wider(s[0].type, s[1].type);
  if (!t) return std::nullopt;
  auto a = convert_const(s[0].type, *s[0].value, *t);
  auto b = convert_const(s[1].type, *s[1].value, *t);
  if (!a || !b) return std::nullopt;
  if (t->base == BaseType::Int) {
    int32_t x = (*a)[0].i, y = (*b)[0].i;
    bool r = op == Opcode::Eq    ? x == y
             : op == Opcode::Neq ? x != y
             : op == Opcode::Lt  ? x < y
             : op == Opcode::Le  ? x <= y
             : op == Opcode::Gt  ? x > y
                                 : x >= y;
    return Values{ConstValue::of_int(r)};
  }
  if (op == Opcode::Eq || op == Opcode::Neq) {
    // OSL's folder takes two constants of the same bits as equal before comparing (so a NaN
    // equals itself there).
    bool same_bits = c_compares && a->size() == b->size();
    for (size_t i = 0; same_bits && i < a->size(); ++i)
      same_bits = std::bit_cast<uint32_t>((*a)[i].f) == std::bit_cast<uint32_t>((*b)[i].f);
    if (same_bits) return Values{ConstValue::of_int(op == Opcode::Eq)};
    bool all_eq = true, any_ne = false;
    for (size_t i = 0; i < a->size(); ++i) {
      float x = (*a)[i].f, y = (*b)[i].f;
      all_eq &= c_compares ? x == y : math::eq(x, y);
      any_ne |= c_compares ? x != y : math::ne(x, y);
    }
    return Values{ConstValue::of_int(op == Opcode::Eq ? all_eq : any_ne)};
  }
  if (t->is_triple()) return std::nullopt;
  float x = (*a)[0].f, y = (*b)[0].f;
  bool r = c_compares ? (op == Opcode::Lt   ? x < y
                         : op == Opcode::Le ? x <= y
                         : op == Opcode::Gt ? x > y
                                            : x >= y)
                      : (op == Opcode::Lt   ? math::lt(x, y)
                         : op == Opcode::Le ? math::le(x, y)
                         : op == Opcode::Gt ? math::gt(x, y)
                                            : math::ge(x, y));
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
std::optional<Values> arith(Opcode op, const Type& dst, const std::vector<ConstArg>& s,
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
  // Division by a constant that is not all zero divides plainly, a zero component giving inf,
  // as the generated code divides (and OSL: vector(4) / vector(0, 1, 2) is "inf 4 2" in OSL
  // 1.13.12, folded or not); an all-zero divisor gives 0.
  bool divisor_nonzero = false; // a float divisor (second operand) that is not all zero
  if (args.size() == 2 && dst.base != BaseType::Int)
    for (const ConstValue& b : args[1]) divisor_nonzero = divisor_nonzero || b.f != 0.0f;
  const bool plain_div = op == Opcode::Div && divisor_nonzero;
  // OSL folds fmod of triples with C's fmod once the divisor is not all zero (an all-zero one,
  // or a float 0, gives 0): a zero component of it gives NaN there (a float's fold gives 0, as
  // math::fmod; at run time both give 0).
  const math::FnInfo* fi = math_fn(op, 2);
  const bool c_fmod = fi && fi->fn == math::Fn::Fmod && dst.is_triple() && divisor_nonzero;
  for (size_t c = 0; c < out.size(); ++c) {
    if (plain_div) {
      out[c] = ConstValue::of_float(args[0][c].f / args[1][c].f);
      continue;
    }
    if (dst.base == BaseType::Int) {
      if (args.size() == 1 && op == Opcode::Neg)
        out[c] = ConstValue::of_int(int32_t(0u - uint32_t(args[0][c].i)));
      else if (args.size() == 1 && (op == Opcode::Abs || op == Opcode::Fabs))
        out[c] = ConstValue::of_int(args[0][c].i < 0 ? int32_t(0u - uint32_t(args[0][c].i))
                                                     : args[0][c].i);
      else if (args.size() == 1 && op == Opcode::Compl)
        out[c] = ConstValue::of_int(~args[0][c].i);
      else if (args.size() == 1 && op == Opcode::Sign)
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
      if (c_fmod && args[1][c].f == 0.0f)
        out[c] = ConstValue::of_float(std::numeric_limits<float>::quiet_NaN());
      else
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
    // NaN and out of range: INT_MIN, as at run time (math::cvtt, x86's cvttss2si, OSL's).
    return Values{ConstValue::of_int(math::cvtt(v[0].f))};
  }
  if (to.is_triple()) {
    if (from.is_triple()) return v;
    if (from.base == BaseType::Int) return Values(3, ConstValue::of_float(float(v[0].i)));
    if (from.base == BaseType::Float) return Values(3, ConstValue::of_float(v[0].f));
  }
  return std::nullopt;
}

std::optional<Values> evaluate(Opcode op, const Type& dst, const std::vector<ConstArg>& s,
                               const EvalOptions& options) {
  if (op == Opcode::Assign && s.size() == 1) return convert_const(s[0].type, *s[0].value, dst);
  if ((op == Opcode::Eq || op == Opcode::Neq || op == Opcode::Lt || op == Opcode::Le ||
       op == Opcode::Gt || op == Opcode::Ge) &&
      s.size() == 2)
    return compare(op, s, options.c_compares);
  if (op == Opcode::Not && s.size() == 1 && is_num(s[0].type)) {
    const ConstValue& c = (*s[0].value)[0];
    bool zero = options.c_compares ? c.f == 0 : math::eq(c.f, 0); // !nan: 0 in C, else 1
    return Values{ConstValue::of_int(s[0].type.base == BaseType::Int ? c.i == 0 : zero)};
  }
  if (op == Opcode::CompRef && s.size() == 2 && s[0].type.is_triple() && !s[0].type.is_array()) {
    int i = (*s[1].value)[0].i;
    if (i < 0 || i > 2) return std::nullopt; // keep the run-time range error
    return Values{(*s[0].value)[size_t(i)]};
  }
  if (op == Opcode::Construct && s.size() == 3 && dst.is_triple() && !dst.is_array()) {
    Values out;
    for (const ConstArg& a : s) {
      auto v = convert_const(a.type, *a.value, Type{BaseType::Float});
      if (!v) return std::nullopt;
      out.push_back((*v)[0]);
    }
    return out;
  }
  if (op == Opcode::Strlen && s.size() == 1 && s[0].type == Type{BaseType::String})
    return Values{ConstValue::of_int(int32_t((*s[0].value)[0].s.size()))};
  if (op == Opcode::Concat && dst == Type{BaseType::String}) {
    ConstValue c;
    for (const ConstArg& a : s) {
      if (!(a.type == Type{BaseType::String})) return std::nullopt;
      c.s += (*a.value)[0].s;
    }
    return Values{c};
  }
  if (op == Opcode::Hash && dst == Type{BaseType::Int}) return hash(s);
  if ((op == Opcode::IsNan || op == Opcode::IsInf || op == Opcode::IsFinite) && s.size() == 1 &&
      s[0].type == Type{BaseType::Float}) {
    float x = (*s[0].value)[0].f;
    bool r = op == Opcode::IsNan   ? std::isnan(x)
             : op == Opcode::IsInf ? std::isinf(x)
                                   : std::isfinite(x);
    return Values{ConstValue::of_int(r)};
  }
  // Operators and the math library (per component, in the destination type).
  switch (op) {
  case Opcode::Add:
  case Opcode::Sub:
  case Opcode::Mul:
  case Opcode::Div:
  case Opcode::Mod:
  case Opcode::Neg:
  case Opcode::Compl:
  case Opcode::BitAnd:
  case Opcode::BitOr:
  case Opcode::Xor:
  case Opcode::Shl:
  case Opcode::Shr:
  case Opcode::Sqrt:
  case Opcode::InverseSqrt:
  case Opcode::Hypot:
  case Opcode::Abs:
  case Opcode::Fabs:
  case Opcode::Sign:
  case Opcode::Floor:
  case Opcode::Ceil:
  case Opcode::Round:
  case Opcode::Trunc:
#define LOBE_MATH_FOLD_CASE(x, e, name, arity, max, forms, doc) case Opcode::e:
    LOBE_MATH_FUNCTIONS(LOBE_MATH_FOLD_CASE, _)
#undef LOBE_MATH_FOLD_CASE
  case Opcode::Min:
  case Opcode::Max:
  case Opcode::Clamp:
  case Opcode::Mix:
  case Opcode::Select:
  case Opcode::Step:
  case Opcode::SmoothStep:
    return arith(op, dst, s, options.fast_math ? math::MathMode::Fast : math::MathMode::Exact);
  default:
    break;
  }
  return std::nullopt;
}

} // namespace lobe::passes

// Implements evaluate(): operands are first converted to the type the op computes in (the
// destination's for arithmetic, the wider source's for comparisons), then the op is applied
// per component.
#include "passes/consteval.h"

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

std::function<float(float)> float_unop(const std::string& op) {
  if (op == "neg") return [](float a) { return -a; };
  if (op == "sin") return [](float a) { return std::sin(a); };
  if (op == "cos") return [](float a) { return std::cos(a); };
  if (op == "tan") return [](float a) { return std::tan(a); };
  if (op == "sqrt") return [](float a) { return a > 0 ? std::sqrt(a) : 0.0f; };
  if (op == "abs" || op == "fabs") return [](float a) { return std::fabs(a); };
  if (op == "floor") return [](float a) { return std::floor(a); };
  if (op == "ceil") return [](float a) { return std::ceil(a); };
  if (op == "exp") return [](float a) { return std::exp(a); };
  if (op == "radians") return [](float a) { return a * float(M_PI / 180.0); };
  return nullptr;
}

std::function<float(float, float)> float_binop(const std::string& op) {
  if (op == "add") return [](float a, float b) { return a + b; };
  if (op == "sub") return [](float a, float b) { return a - b; };
  if (op == "mul") return [](float a, float b) { return a * b; };
  if (op == "div") return [](float a, float b) { return b == 0 ? 0.0f : a / b; };
  if (op == "mod" || op == "fmod")
    return [](float a, float b) { return b == 0 ? 0.0f : std::fmod(a, b); };
  if (op == "min") return [](float a, float b) { return std::fmin(a, b); };
  if (op == "max") return [](float a, float b) { return std::fmax(a, b); };
  if (op == "pow") // OSL's safe_pow, as runtime/codegen/ops_math.cpp computes it
    return [](float a, float b) {
      if (b == 0) return 1.0f;
      if (a == 0 || (a < 0 && b != std::floor(b))) return 0.0f;
      float p = std::pow(a, b);
      return p > FLT_MAX ? FLT_MAX : p < -FLT_MAX ? -FLT_MAX : p;
    };
  return nullptr;
}

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
  bool isint = t->base == BaseType::Int;
  auto num = [&](const ConstValue& c) { return isint ? double(c.i) : double(c.f); };
  if (op == "eq" || op == "neq") {
    bool same = true;
    for (size_t i = 0; i < a->size(); ++i) same &= num((*a)[i]) == num((*b)[i]);
    return Values{ConstValue::of_int(op == "eq" ? same : !same)};
  }
  if (t->is_triple()) return std::nullopt;
  double x = num((*a)[0]), y = num((*b)[0]);
  bool r = op == "lt" ? x < y : op == "le" ? x <= y : op == "gt" ? x > y : x >= y;
  return Values{ConstValue::of_int(r)};
}

// Arithmetic in the destination type, sources converted to it.
std::optional<Values> arith(const std::string& op, const Type& dst,
                            const std::vector<ConstArg>& s) {
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
      else if (args.size() == 1 && op == "abs")
        out[c] = ConstValue::of_int(args[0][c].i < 0 ? int32_t(0u - uint32_t(args[0][c].i))
                                                     : args[0][c].i);
      else if (args.size() == 1 && op == "compl")
        out[c] = ConstValue::of_int(~args[0][c].i);
      else if (args.size() == 2)
        out[c] = ConstValue::of_int(int_binop(op, args[0][c].i, args[1][c].i, ok));
      else
        return std::nullopt;
    } else if (args.size() == 1) {
      auto f = float_unop(op);
      if (!f) return std::nullopt;
      out[c] = ConstValue::of_float(f(args[0][c].f));
    } else if (args.size() == 2) {
      auto f = float_binop(op);
      if (!f) return std::nullopt;
      out[c] = ConstValue::of_float(f(args[0][c].f, args[1][c].f));
    } else if (args.size() == 3 && op == "clamp") {
      out[c] = ConstValue::of_float(std::fmin(std::fmax(args[0][c].f, args[1][c].f), args[2][c].f));
    } else if (args.size() == 3 && op == "mix") {
      float t = args[2][c].f;
      out[c] = ConstValue::of_float(args[0][c].f * (1 - t) + args[1][c].f * t);
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
                               const std::vector<ConstArg>& s) {
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
  static const char* kArith[] = {"add",    "sub",   "mul", "div",  "mod",   "neg",  "compl",
                                 "bitand", "bitor", "xor", "shl",  "shr",   "sin",  "cos",
                                 "tan",    "sqrt",  "abs", "fabs", "floor", "ceil", "exp",
                                 "fmod",   "min",   "max", "pow",  "clamp", "mix",  "radians"};
  for (const char* a : kArith)
    if (op == a) return arith(op, dst, s);
  return std::nullopt;
}

} // namespace lobe::passes

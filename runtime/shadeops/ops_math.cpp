// The math builtins JIT code calls out of line: one C-ABI function per math::Fn and form, each
// a thin wrapper of runtime/mathlib/mathops.h (the constant folder calls the same code), with
// the mode (math::MathMode, from CompileOptions::fast_math) as the last argument.
//   lobe_math_<f>(float x, int mode) -> float                  value of a unary f
//   lobe_math_<f>_slope(float x, int mode) -> float            its derivative factor
//   lobe_math_<f>(float a, float b, int mode) -> float         value of atan2, pow, fmod
//   lobe_math_<f>_dual(float* out, const float* a, const float* b, int mode)
//                                                              value, d/dx, d/dy of those
// and lobe_hash, hash() of numbers.
// (Plain C++ over the header, so it can be compiled to bitcode for inlining as it is.)
#include "shadeop_decls.h"
#include "shadeop_sig.h"
#include "shadeops.h"

#include "hashword.h"
#include "mathops.h"

#include <array>
#include <deque>
#include <string>
#include <utility>
#include <vector>

namespace lobe::shadeops {
namespace {

using math::Fn;
using math::MathMode;

template <Fn f> float unary_value(float x, int32_t mode) {
  return math::value1(f, MathMode(mode), x);
}
template <Fn f> float unary_slope(float x, int32_t mode) {
  return math::slope1(f, MathMode(mode), x);
}
template <Fn f> float binary_value(float a, float b, int32_t mode) {
  return math::value2(f, MathMode(mode), a, b);
}
template <Fn f> void binary_dual(float* out, const float* a, const float* b, int32_t mode) {
  math::Dual r = math::dual2(f, MathMode(mode), {a[0], a[1], a[2]}, {b[0], b[1], b[2]});
  out[0] = r.v, out[1] = r.dx, out[2] = r.dy;
}

template <class F> void* addr(F* f) { return reinterpret_cast<void*>(f); }

// Names live as long as the process (the table hands out const char*).
const char* keep(std::string s) {
  static std::deque<std::string> names;
  return names.emplace_back(std::move(s)).c_str();
}

template <Fn f> void add_entries(std::vector<ShadeOpSymbol>& out) {
  constexpr const math::FnInfo& info = math::kFns[size_t(f)];
  static_assert(info.fn == f, "kFns is in enum order");
  if constexpr (info.arity == 1) {
    out.push_back({math_shadeop(f, MathForm::Value), addr(&unary_value<f>),
                   shadeop_sig<decltype(&unary_value<f>)>});
    out.push_back({math_shadeop(f, MathForm::Slope), addr(&unary_slope<f>),
                   shadeop_sig<decltype(&unary_slope<f>)>});
  } else {
    out.push_back({math_shadeop(f, MathForm::Value), addr(&binary_value<f>),
                   shadeop_sig<decltype(&binary_value<f>)>});
    out.push_back({math_shadeop(f, MathForm::Dual), addr(&binary_dual<f>),
                   shadeop_sig<decltype(&binary_dual<f>)>});
  }
}

template <size_t... I> std::vector<ShadeOpSymbol> make_entries(std::index_sequence<I...>) {
  std::vector<ShadeOpSymbol> out;
  (add_entries<Fn(I)>(out), ...);
  return out;
}

} // namespace

const char* math_shadeop(math::Fn f, MathForm form) {
  constexpr size_t n = std::size(math::kFns);
  static const auto names = [] {
    std::array<std::array<const char*, 3>, n> t{};
    for (size_t i = 0; i < n; ++i) {
      std::string base = std::string("lobe_math_") + math::kFns[i].name;
      t[i] = {keep(base), keep(base + "_slope"), keep(base + "_dual")};
    }
    return t;
  }();
  return names[size_t(f)][size_t(form)];
}

std::span<const ShadeOpSymbol> math_shadeop_symbols() {
  static const std::vector<ShadeOpSymbol> table =
      make_entries(std::make_index_sequence<std::size(math::kFns)>());
  return table;
}

} // namespace lobe::shadeops

// hash() of numbers: OSL's lookup3 over `n` 32-bit words (1 to 4).
extern "C" int32_t lobe_hash(const uint32_t* words, int32_t n) {
  return lobe::math::osl_hash(words, n);
}

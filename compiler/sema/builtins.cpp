// The builtin table, grouped by family. Shorthands: I int, F float, C color, P point,
// V vector, N normal, M matrix, S string; "generic" means float and every triple (OSL's
// functions that work per component).
#include "sema/builtins.h"

#include "sema/types.h"

#include "library_calls.h"
#include "math_functions.h"

#include <algorithm>
#include <map>
#include <type_traits>

namespace lobe::sema {

namespace {

using Sig = BuiltinSig;

class Builder {
public:
  std::vector<Sig> sigs;

  Sig& add(const char* name, Type ret, std::vector<Type> params) {
    Sig s;
    s.name = name;
    s.ret = ret;
    for (auto& p : params) s.params.push_back({p, false});
    sigs.push_back(std::move(s));
    return sigs.back();
  }
  // T f(T...) for T = float, color, point, vector, normal (arity 1..3)
  void generic(const char* name, int arity) {
    for (Type t : kGeneric) add(name, t, std::vector<Type>(size_t(arity), t));
  }
  static inline const Type kGeneric[] = {t_float(), t_color(), t_point(), t_vector(), t_normal()};
  static inline const Type kTriples[] = {t_color(), t_point(), t_vector(), t_normal()};
};

// A math_functions.h row's signatures: Generic, float and every triple (all arguments of the
// result's type); Float, float only.
enum class MathForms { Generic, Float };
void math_function(Builder& b, const char* name, int arity, MathForms forms) {
  if (forms == MathForms::Generic)
    b.generic(name, arity);
  else
    b.add(name, t_float(), std::vector<Type>(size_t(arity), t_float()));
}

void math(Builder& b) {
  // The functions computed by formula (runtime/registry/math_functions.h), then the rest.
#define LOBE_MATH_SIG_ROW(x, e, name, arity, max, forms, doc)                                      \
  math_function(b, #name, arity, MathForms::forms);
  LOBE_MATH_FUNCTIONS(LOBE_MATH_SIG_ROW, _)
#undef LOBE_MATH_SIG_ROW
  for (const char* f :
       {"sqrt", "inversesqrt", "fabs", "floor", "ceil", "round", "trunc", "radians", "degrees"})
    b.generic(f, 1);
  b.add("abs", t_int(), {t_int()});
  b.generic("abs", 1);
  b.add("fabs", t_int(), {t_int()}); // OSL's fabs is abs: fabs(int) is an int
  b.generic("sign", 1);              // no int form, as stdosl.h: sign(-3) is the float -1
  for (const char* f : {"mod", "min", "max", "step"}) {
    if (std::string(f) == "min" || std::string(f) == "max" || std::string(f) == "mod")
      b.add(f, t_int(), {t_int(), t_int()});
    b.generic(f, 2);
  }
  for (Type t : Builder::kTriples) {
    b.add("pow", t, {t, t_float()});
    b.add("fmod", t, {t, t_float()});
    b.add("mod", t, {t, t_float()});
    b.add("log", t, {t, t_float()});
    b.add("step", t, {t_float(), t});
  }
  b.add("log", t_float(), {t_float(), t_float()});
  b.generic("smoothstep", 3);
  for (Type t : Builder::kTriples) b.add("smoothstep", t, {t_float(), t_float(), t});
  // As stdosl.h declares them: no int form (select(1, 2, c) is a float), an int or float
  // condition for every type, a triple condition per component for triples.
  b.add("select", t_float(), {t_float(), t_float(), t_float()});
  b.add("select", t_float(), {t_float(), t_float(), t_int()});
  for (Type t : Builder::kTriples) {
    b.add("select", t, {t, t, t_float()});
    b.add("select", t, {t, t, t_int()});
    b.add("select", t, {t, t, t});
  }
  for (const char* f : {"isnan", "isinf", "isfinite"}) b.add(f, t_int(), {t_float()});
  for (Type t : Builder::kGeneric) {
    Sig& s = b.add("sincos", t_void(), {t, t, t});
    s.params[1].output = s.params[2].output = true;
  }
}

void geometry(Builder& b) {
  b.add("dot", t_float(), {t_vector(), t_vector()});
  b.add("cross", t_vector(), {t_vector(), t_vector()});
  b.add("length", t_float(), {t_vector()});
  b.add("distance", t_float(), {t_point(), t_point()});
  b.add("distance", t_float(), {t_point(), t_point(), t_point()});
  b.add("normalize", t_normal(), {t_normal()});
  b.add("normalize", t_vector(), {t_vector()});
  for (Type t : {t_point(), t_vector(), t_normal()}) {
    b.add("transform", t, {t_string(), t});
    b.add("transform", t, {t_string(), t_string(), t});
    b.add("transform", t, {t_matrix(), t});
  }
  b.add("transformu", t_float(), {t_string(), t_float()});
  b.add("transformu", t_float(), {t_string(), t_string(), t_float()});
  Sig& g1 = b.add("getmatrix", t_int(), {t_string(), t_string(), t_matrix()});
  g1.params[2].output = true;
  b.add("determinant", t_float(), {t_matrix()});
  b.add("transpose", t_matrix(), {t_matrix()});
  b.add("area", t_float(), {t_point()});
  b.add("calculatenormal", t_normal(), {t_point()});
  b.add("surfacearea", t_float(), {});
  b.add("backfacing", t_int(), {});
  b.add("raytype", t_int(), {t_string()});
}

void derivatives(Builder& b) {
  for (const char* f : {"Dx", "Dy", "Dz"}) b.generic(f, 1);
  b.add("filterwidth", t_float(), {t_float()});
  b.add("filterwidth", t_vector(), {t_vector()});
}

void color(Builder& b) {
  b.add("luminance", t_float(), {t_color()});
  b.add("blackbody", t_color(), {t_float()});
  b.add("wavelength_color", t_color(), {t_float()});
  b.add("transformc", t_color(), {t_string(), t_color()});
  b.add("transformc", t_color(), {t_string(), t_string(), t_color()});
}

// noise-like functions: float, color and vector results (as OSL's; `point p = noise(P)` takes
// the vector one) over 1-4 D domains.
void patterns(Builder& b) {
  const Type results[] = {t_float(), t_color(), t_vector()};
  for (const char* f : {"noise", "snoise", "cellnoise", "hashnoise"}) {
    for (Type r : results) {
      b.add(f, r, {t_float()});
      b.add(f, r, {t_float(), t_float()});
      b.add(f, r, {t_point()});
      b.add(f, r, {t_point(), t_float()});
    }
  }
  for (const char* f : {"pnoise", "psnoise"}) {
    for (Type r : results) {
      b.add(f, r, {t_float(), t_float()});
      b.add(f, r, {t_float(), t_float(), t_float(), t_float()});
      b.add(f, r, {t_point(), t_point()});
      b.add(f, r, {t_point(), t_float(), t_point(), t_float()});
    }
  }
  // Generic noise("perlin" | "uperlin" | "cell" | "hash" | "simplex" | "gabor" ..., ...), 1-4 D,
  // and pnoise(name, ...) in the same 4 domains; trailing `"name", value` keyword pairs are the
  // gabor options ("anisotropic", "direction", "bandwidth", "impulses", "do_filter"; ignored by
  // the other kinds, as in OSL).
  for (const char* f : {"noise", "pnoise"}) {
    bool periodic = std::string(f) == "pnoise";
    for (Type r : results) {
      if (periodic) {
        b.add(f, r, {t_string(), t_float(), t_float()}).extra = Sig::Extra::Keywords;
        b.add(f, r, {t_string(), t_float(), t_float(), t_float(), t_float()}).extra =
            Sig::Extra::Keywords;
        b.add(f, r, {t_string(), t_point(), t_point()}).extra = Sig::Extra::Keywords;
        b.add(f, r, {t_string(), t_point(), t_float(), t_point(), t_float()}).extra =
            Sig::Extra::Keywords;
      } else {
        b.add(f, r, {t_string(), t_float()}).extra = Sig::Extra::Keywords;
        b.add(f, r, {t_string(), t_float(), t_float()}).extra = Sig::Extra::Keywords;
        b.add(f, r, {t_string(), t_point()}).extra = Sig::Extra::Keywords;
        b.add(f, r, {t_string(), t_point(), t_float()}).extra = Sig::Extra::Keywords;
      }
    }
  }
  b.add("hash", t_int(), {t_int()});
  b.add("hash", t_int(), {t_float()});
  b.add("hash", t_int(), {t_float(), t_float()});
  b.add("hash", t_int(), {t_point()});
  b.add("hash", t_int(), {t_point(), t_float()});
  b.add("hash", t_int(), {t_string()});
}

void strings(Builder& b) {
  b.add("printf", t_void(), {t_string()}).extra = Sig::Extra::Any;
  b.add("format", t_string(), {t_string()}).extra = Sig::Extra::Any;
  b.add("error", t_void(), {t_string()}).extra = Sig::Extra::Any;
  b.add("warning", t_void(), {t_string()}).extra = Sig::Extra::Any;
  // concat of 2 to 6 strings, as OSL's (its builtin takes two, its stdosl.h the longer forms).
  const Type str = t_string();
  b.add("concat", str, {str, str});
  b.add("concat", str, {str, str, str});
  b.add("concat", str, {str, str, str, str});
  b.add("concat", str, {str, str, str, str, str});
  b.add("concat", str, {str, str, str, str, str, str});
  b.add("substr", t_string(), {t_string(), t_int(), t_int()});
  b.add("substr", t_string(), {t_string(), t_int()});
  // split(str, results[], sep = "" (whitespace), maxsplit = arraylength(results)): the count.
  const Type strings_out(BaseType::String, -1);
  b.add("split", t_int(), {t_string(), strings_out, t_string(), t_int()}).params[1].output = true;
  b.add("split", t_int(), {t_string(), strings_out, t_string()}).params[1].output = true;
  b.add("split", t_int(), {t_string(), strings_out}).params[1].output = true;
  b.add("regex_search", t_int(), {t_string(), t_string()});
  b.add("regex_match", t_int(), {t_string(), t_string()});
  // (subject, int results[], pattern): results receives (begin, end) offset pairs.
  b.add("regex_search", t_int(), {t_string(), Type(BaseType::Int, -1), t_string()})
      .params[1]
      .output = true;
  b.add("regex_match", t_int(), {t_string(), Type(BaseType::Int, -1), t_string()})
      .params[1]
      .output = true;
}

// spline(basis, x, knots...) / (basis, x, knots[]) / (basis, x, nknots, knots[]) per value type;
// splineinverse is float only. The variadic form takes at least four knots (a cubic segment).
void splines(Builder& b) {
  for (Type t : Builder::kGeneric) {
    b.add("spline", t, {t_string(), t_float(), t, t, t, t}).extra = Sig::Extra::Any;
    b.add("spline", t, {t_string(), t_float(), Type(t.base, -1)});
    b.add("spline", t, {t_string(), t_float(), t_int(), Type(t.base, -1)});
  }
  b.add("splineinverse", t_float(),
        {t_string(), t_float(), t_float(), t_float(), t_float(), t_float()})
      .extra = Sig::Extra::Any;
  b.add("splineinverse", t_float(), {t_string(), t_float(), Type(BaseType::Float, -1)});
  b.add("splineinverse", t_float(), {t_string(), t_float(), t_int(), Type(BaseType::Float, -1)});
}

// Renderer services: attributes, messages, texture queries, rays, files.
void services(Builder& b) {
  const BaseType values[] = {BaseType::Int,   BaseType::Float,  BaseType::String, BaseType::Color,
                             BaseType::Point, BaseType::Vector, BaseType::Normal, BaseType::Matrix};
  for (BaseType v : values) {
    for (int len : {0, -1}) {
      Type t(v, len);
      b.add("getattribute", t_int(), {t_string(), t}).params[1].output = true;
      b.add("getattribute", t_int(), {t_string(), t_string(), t}).params[2].output = true;
      b.add("getattribute", t_int(), {t_string(), t_int(), t}).params[2].output = true;
      b.add("getattribute", t_int(), {t_string(), t_string(), t_int(), t}).params[3].output = true;
      b.add("getmessage", t_int(), {t_string(), t}).params[1].output = true;
      b.add("getmessage", t_int(), {t_string(), t_string(), t}).params[2].output = true;
      b.add("setmessage", t_void(), {t_string(), t});
      b.add("gettextureinfo", t_int(), {t_string(), t_string(), t}).params[2].output = true;
    }
  }
  // Messages carry closures too (a closure color or an array of them), as OSL's do.
  for (int len : {0, -1}) {
    Type c(BaseType::Closure, len);
    b.add("getmessage", t_int(), {t_string(), c}).params[1].output = true;
    b.add("getmessage", t_int(), {t_string(), t_string(), c}).params[2].output = true;
    b.add("setmessage", t_void(), {t_string(), c});
  }
  for (BaseType v : values) {
    // gettextureinfo(file, s, t, query, dest): the UDIM tile at (s, t) of a UDIM file name.
    for (int len : {0, -1})
      b.add("gettextureinfo", t_int(), {t_string(), t_float(), t_float(), t_string(), Type(v, len)})
          .params[4]
          .output = true;
    // XML dictionaries: dict_value(node, attribute, dest) for any non-array type.
    b.add("dict_value", t_int(), {t_int(), t_string(), Type(v, 0)}).params[2].output = true;
    // pointcloud_get(file, indices[], count, attribute, dest[])
    b.add("pointcloud_get", t_int(),
          {t_string(), Type(BaseType::Int, -1), t_int(), t_string(), Type(v, -1)})
        .params[4]
        .output = true;
  }
  b.add("dict_find", t_int(), {t_string(), t_string()});
  b.add("dict_find", t_int(), {t_int(), t_string()});
  b.add("dict_next", t_int(), {t_int()});
  // pointcloud_search(file, P, radius, maxpoints, [sort,] "attribute", dest[], ...) and
  // pointcloud_write(file, P, "attribute", value, ...).
  for (bool sort : {false, true}) {
    std::vector<Type> ps = {t_string(), t_point(), t_float(), t_int()};
    if (sort) ps.push_back(t_int());
    Sig& s = b.add("pointcloud_search", t_int(), ps);
    s.extra = Sig::Extra::Pairs;
    s.pairs_written = true;
  }
  b.add("pointcloud_write", t_int(), {t_string(), t_point()}).extra = Sig::Extra::Pairs;
  b.add("trace", t_int(), {t_point(), t_vector()}).extra = Sig::Extra::Keywords;
  b.add("fprintf", t_void(), {t_string(), t_string()}).extra = Sig::Extra::Any;
}

void textures(Builder& b) {
  // texture(filename, s, t, "keyword", value, ...) and friends: float, color or vector (the
  // first channels), each also with explicit derivatives.
  for (Type r : {t_float(), t_color(), t_vector()}) {
    auto add = [&](const char* name, std::vector<Type> ps) {
      b.add(name, r, std::move(ps)).extra = Sig::Extra::Keywords;
    };
    const Type f = t_float(), v = t_vector();
    add("texture", {t_string(), f, f});
    add("texture", {t_string(), f, f, f, f, f, f}); // dsdx dtdx dsdy dtdy
    add("texture3d", {t_string(), t_point()});
    add("texture3d", {t_string(), t_point(), v, v, v}); // dPdx dPdy dPdz
    add("environment", {t_string(), v});
    add("environment", {t_string(), v, v, v}); // dRdx dRdy
  }
}

// The library calls (ir/library_calls.h): one signature each, from the table's row.
namespace lib = ir::library;
template <class T> Type lib_type() {
  if constexpr (std::is_same_v<T, lib::Int>)
    return t_int();
  else if constexpr (std::is_same_v<T, lib::Float>)
    return t_float();
  else if constexpr (std::is_same_v<T, lib::String>)
    return t_string();
  else if constexpr (std::is_same_v<T, lib::Color>)
    return t_color();
  else if constexpr (std::is_same_v<T, lib::Point>)
    return t_point();
  else if constexpr (std::is_same_v<T, lib::Vector>)
    return t_vector();
  else
    return t_normal();
}
template <class F> struct LibParams;
template <class... P> struct LibParams<void(P...)> {
  static std::vector<Type> types() {
    std::vector<Type> out;
    ((std::is_same_v<P, lib::Env> ? void() : out.push_back(lib_type<P>())), ...);
    return out;
  }
};

void library_calls(Builder& b) {
  using namespace ir::library;
#define LOBE_LIBRARY_SIG_ROW(x, e, name, R, P, fn, doc)                                            \
  b.add(name, lib_type<R>(), LibParams<void P>::types());
  LOBE_LIBRARY_CALLS(LOBE_LIBRARY_SIG_ROW, _)
#undef LOBE_LIBRARY_SIG_ROW
}

void misc(Builder& b) {
  b.add("exit", t_void(), {});
  b.add("arraylength", t_int(), {t_float()}).array_param = true;
  b.add("isconnected", t_int(), {t_float()}).any_param = true;
  b.add("isconstant", t_int(), {t_float()}).any_param = true;
}

} // namespace

std::string BuiltinSig::signature() const {
  std::string s = ast::to_string(ret) + " " + name + "(";
  for (size_t i = 0; i < params.size(); ++i) {
    if (i) s += ", ";
    if (params[i].output) s += "output ";
    s += any_param ? "any" : array_param ? "T[]" : ast::to_string(params[i].type);
  }
  if (extra != Extra::None) s += params.empty() ? "..." : ", ...";
  return s + ")";
}

BuiltinTable::BuiltinTable() {
  Builder b;
  math(b);
  geometry(b);
  derivatives(b);
  color(b);
  patterns(b);
  strings(b);
  splines(b);
  services(b);
  textures(b);
  library_calls(b);
  misc(b);
  // Group by name, keeping each name's declaration order (the preference order).
  std::stable_sort(b.sigs.begin(), b.sigs.end(),
                   [](const Sig& x, const Sig& y) { return x.name < y.name; });
  sigs_ = std::move(b.sigs);
}

std::span<const BuiltinSig> BuiltinTable::lookup(std::string_view name) const {
  auto lo = std::lower_bound(sigs_.begin(), sigs_.end(), name,
                             [](const Sig& s, std::string_view n) { return s.name < n; });
  auto hi = lo;
  while (hi != sigs_.end() && hi->name == name) ++hi;
  return {lo, hi};
}

const BuiltinTable& builtins() {
  static const BuiltinTable table;
  return table;
}

} // namespace lobe::sema

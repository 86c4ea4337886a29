// Instance values: the text or words of a `param` turned into constants of a parameter's type,
// with OSL's rules when the value says its type (see InstanceValue in lobe/shadingsys.h).
#include "instance_values.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <sstream>

namespace lobe::group {
namespace {

// Words of a value: the given ones, else the text split at spaces (and at commas when `commas`).
std::vector<std::string> value_words(const InstanceValue& v, bool commas) {
  if (!v.words.empty()) return v.words;
  std::vector<std::string> out;
  std::string w;
  for (char c : v.value) {
    if (c == ' ' || c == '\t' || c == '\n' || (commas && c == ',')) {
      if (!w.empty()) out.push_back(w);
      w.clear();
    } else {
      w += c;
    }
  }
  if (!w.empty()) out.push_back(w);
  return out;
}

// The declared type of a typed instance value, as IR; nullopt for an unknown name. "T[]" has
// arraylen -1: as many elements as the value gives.
std::optional<ir::Type> declared_type(const std::string& name) {
  bool unsized = name.size() > 2 && name.compare(name.size() - 2, 2, "[]") == 0;
  std::optional<DataType> d = DataType::parse(unsized ? name.substr(0, name.size() - 2) : name);
  if (!d) return std::nullopt;
  static const ir::BaseType kBase[] = {
      ir::BaseType::Int,    ir::BaseType::Float,  ir::BaseType::Color,  ir::BaseType::Point,
      ir::BaseType::Vector, ir::BaseType::Normal, ir::BaseType::Matrix, ir::BaseType::String};
  if (unsized && d->arraylen) return std::nullopt;
  return ir::Type{kBase[size_t(d->base)], unsized ? -1 : d->arraylen};
}

// OSL's typed value: `t`'s elements x components values read from the words as C's atof and
// atoi read them (junk after a number is ignored, no number is 0); missing values are 0 and
// extra ones ignored. A scalar string is the whole text. An unsized `t` takes its length from
// the words. Words that hold no number at all are listed in `junk` (Lobe warns; OSL is silent).
std::vector<ir::ConstValue> read_typed(const InstanceValue& v, ir::Type& t,
                                       std::vector<std::string>& junk) {
  if (t.base == ir::BaseType::String && !t.is_array())
    return {ir::ConstValue{0, 0, v.words.empty() ? v.value : v.words[0]}};
  std::vector<std::string> w = value_words(v, t.base != ir::BaseType::String);
  if (t.arraylen < 0)
    t.arraylen = std::max(1, int(w.size() + size_t(t.components()) - 1) / t.components());
  size_t n = size_t(t.components()) * size_t(std::max(1, t.arraylen));
  std::vector<ir::ConstValue> out(n);
  for (size_t k = 0; k < n && k < w.size(); ++k) {
    char* end = nullptr;
    if (t.base == ir::BaseType::String)
      out[k].s = w[k];
    else if (t.base == ir::BaseType::Int)
      out[k].i = read_int(w[k].c_str(), &end);
    else
      out[k].f = std::strtof(w[k].c_str(), &end);
    if (end == w[k].c_str()) junk.push_back(w[k]);
  }
  return out;
}

// Lobe's untyped value: the words must be numbers (or strings) that fill the type exactly, or
// one value that broadcasts to every component.
bool fit_untyped(const InstanceValue& v, const ir::Type& t, std::vector<ir::ConstValue>& out,
                 int& arraylen) {
  out.clear();
  int comps = t.components();
  if (t.base == ir::BaseType::String && !t.is_array()) {
    out.push_back({0, 0, v.words.empty() ? v.value : v.words[0]});
    arraylen = 0;
    return true;
  }
  if (t.base == ir::BaseType::Closure) return false;
  for (const std::string& w : value_words(v, false)) {
    ir::ConstValue c;
    if (t.base == ir::BaseType::String) {
      c.s = w;
    } else {
      char* end = nullptr;
      if (t.base == ir::BaseType::Int) {
        c.i = read_int(w.c_str(), &end);
        if (*end == '.' || *end == 'e') { // a float's digits: truncated, then the nearest int
          float f = std::strtof(w.c_str(), &end);
          c.i = f != f ? 0 : int32_t(std::clamp(f, -2147483648.0f, 2147483520.0f));
        }
      } else {
        c.f = std::strtof(w.c_str(), &end);
      }
      if (end == w.c_str() || *end) return false;
    }
    out.push_back(c);
  }
  if (out.empty()) return false;
  if (t.arraylen < 0) { // unsized: the value decides the length
    if (out.size() % size_t(comps)) return false;
    arraylen = int(out.size()) / comps;
    return true;
  }
  arraylen = t.arraylen;
  size_t want = size_t(std::max(1, t.arraylen) * comps);
  if (out.size() == 1 && want > 1) out.assign(want, out[0]);
  return out.size() == want;
}

} // namespace

ValueFit fit_instance_value(const InstanceValue& v, const ir::Type& param) {
  ValueFit r;
  if (!v.osl_rules) {
    r.ok = fit_untyped(v, param, r.values, r.arraylen);
    if (!r.ok)
      r.error = "value '" + v.value + "' does not fit parameter '" + v.name + "' of type " +
                ir::to_string(param);
    return r;
  }
  std::optional<ir::Type> t = declared_type(v.type);
  if (!t) {
    r.error = "unknown type '" + v.type + "' for parameter '" + v.name + "'";
    return r;
  }
  std::vector<std::string> junk;
  std::vector<ir::ConstValue> vals = read_typed(v, *t, junk);
  if (!junk.empty())
    r.note =
        "value '" + junk[0] + "' for parameter '" + v.name + "' is not a number; it reads as 0";
  // OSL's matching: the same type (any triple for a triple, an unsized array takes any
  // length), or a float broadcast to a triple; anything else keeps the default, with OSL's
  // warning.
  bool arrays_fit = param.arraylen == t->arraylen || (param.arraylen < 0 && t->arraylen > 0);
  if (param.base == ir::BaseType::Closure) { // no value sets a closure: OSL skips it so
    r.warning = "skipping assignment of closure: " + v.name;
  } else if (same_kind(*t, param) && arrays_fit) {
    r.ok = true;
    r.values = std::move(vals);
    r.arraylen = t->arraylen;
  } else if (t->base == ir::BaseType::Float && !t->is_array() && param.is_triple() &&
             !param.is_array()) {
    r.ok = true;
    r.values.assign(3, vals[0]);
  } else {
    r.warning = "attempting to set parameter with wrong type: " + v.name + " (expected '" +
                ir::to_string(param) + "', received '" + ir::to_string(*t) + "')";
  }
  return r;
}

bool same_kind(const ir::Type& a, const ir::Type& b) {
  return a.base == b.base || (a.is_triple() && b.is_triple());
}

std::string nonexistent_param_note(const std::string& layer, const std::string& shader,
                                   const std::string& param,
                                   const std::vector<std::string>& params) {
  std::string names;
  for (const std::string& n : params) names.append(names.empty() ? "" : ", ").append(n);
  return "layer '" + layer + "': shader '" + shader + "' has no parameter '" + param +
         "' (its parameters: " + names + ")";
}

int metadata_lockgeom(const ir::Symbol& s) {
  int lockgeom = -1;
  for (const ir::Metadata& m : s.metadata) {
    if (m.type != ir::Type{ir::BaseType::Int, 0} || m.value.empty()) continue;
    if (m.name == "lockgeom") lockgeom = m.value[0].i;
    if (m.name == "interpolated") lockgeom = m.value[0].i ? 0 : 1;
  }
  return lockgeom;
}

bool interactive_param(const ShaderGroup::Layer& l, const ir::Symbol& s) {
  const InstanceValue* given = nullptr;
  for (const InstanceValue& v : l.values)
    if (v.name == s.name) given = &v;
  if (given) return given->interactive;
  for (const ir::Metadata& m : s.metadata)
    if (m.name == "interactive" && m.type.base == ir::BaseType::Int && !m.value.empty() &&
        m.value[0].i != 0)
      return true;
  return false;
}

// OpenImageIO's stoi saturates: the nearest int.
int32_t read_int(const char* text, char** end) {
  long v = std::strtol(text, end, 10);
  return int32_t(std::clamp<long>(v, INT32_MIN, INT32_MAX));
}

} // namespace lobe::group

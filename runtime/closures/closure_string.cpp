// closure_to_string (bsdf.h): a closure tree in OSL's print format,
//   (w0, w1, w2) * name ((Nx, Ny, Nz), arg, "kw", value)
// one term per component with the product of the weights above it, terms joined by "\n\t+ ".
// Keyword arguments are printed when they differ from their registry default or are marked
// always_printed (the ones OSL's reference renderer registers), so that `diffuse(N)` prints
// `diffuse ((0, 0, 1), "label", "")` as OSL prints it. A layer prints its two sub-closures in
// parentheses.
#include "closure_registry.h"
#include "closures.h"
#include "lobe/bsdf.h"

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace lobe {
namespace {

using registry::ArgType;

std::string fmt_float(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v));
  return buf;
}

std::string fmt_triple(const Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", static_cast<double>(v.x), static_cast<double>(v.y),
                static_cast<double>(v.z));
  return buf;
}

std::string fmt_value(ArgType t, const unsigned char* p) {
  switch (t) {
  case ArgType::Int: {
    int v;
    std::memcpy(&v, p, 4);
    return std::to_string(v);
  }
  case ArgType::Float: {
    float v;
    std::memcpy(&v, p, 4);
    return fmt_float(v);
  }
  case ArgType::Color:
  case ArgType::Vector: {
    Vec3 v;
    std::memcpy(&v, p, 12);
    return fmt_triple(v);
  }
  case ArgType::String: {
    const char* s;
    std::memcpy(&s, p, sizeof s);
    std::string r = "\"";
    r.append(s ? s : "");
    r.push_back('"');
    return r;
  }
  case ArgType::Closure: {
    const ClosureNode* c;
    std::memcpy(&c, p, sizeof c);
    std::string r = "("; // not "(" + ...: GCC 12 warns falsely (-Wrestrict) on that form
    r += closure_to_string(c);
    r += ')';
    return r;
  }
  }
  return "";
}

// One argument of a shader-declared closure: arrays as [a, b, ...].
std::string fmt_declared(const DeclaredClosureArg& a, const unsigned char* values) {
  using B = DeclaredClosureArg::Base;
  ArgType t = a.base == B::Int       ? ArgType::Int
              : a.base == B::Float   ? ArgType::Float
              : a.base == B::String  ? ArgType::String
              : a.base == B::Closure ? ArgType::Closure
                                     : ArgType::Vector;
  size_t stride = a.base == B::Matrix                               ? 64
                  : a.base == B::Triple                             ? 12
                  : (t == ArgType::String || t == ArgType::Closure) ? 8
                                                                    : 4;
  auto one = [&](const unsigned char* p) {
    if (a.base != B::Matrix) return fmt_value(t, p);
    std::string s = "(";
    for (int k = 0; k < 16; ++k) {
      float v;
      std::memcpy(&v, p + 4 * k, 4);
      if (k) s += ", ";
      s += fmt_float(v);
    }
    return s + ")";
  };
  const unsigned char* p = values + a.offset;
  if (a.arraylen == 0) return one(p);
  std::string s = "[";
  for (int k = 0; k < a.arraylen; ++k) {
    if (k) s += ", ";
    s += one(p + size_t(k) * stride);
  }
  return s + "]";
}

std::string declared(const ClosureDeclared& c, const Color3& w) {
  const DeclaredClosureInfo& info = *c.info;
  std::string s = fmt_triple(w) + " * " + info.name + " (";
  for (uint32_t i = 0; i < info.nargs; ++i) {
    const DeclaredClosureArg& a = info.args[i];
    if (i) s += ", ";
    if (a.keyword) {
      s.push_back('"');
      s.append(a.keyword);
      s.append("\", ");
    }
    s += fmt_declared(a, c.values());
  }
  return s + ")";
}

bool is_default(const registry::ClosureEntry& e, size_t i, const unsigned char* p) {
  closures::Params d(e.key);
  size_t off = registry::param_offset(e.params, i);
  if (e.params[i].type == ArgType::String) {
    const char *a, *b;
    std::memcpy(&a, p + off, sizeof a);
    std::memcpy(&b, d.data() + off, sizeof b);
    return std::strcmp(a ? a : "", b ? b : "") == 0;
  }
  return std::memcmp(p + off, d.data() + off, registry::arg_size(e.params[i].type)) == 0;
}

std::string component(int id, const unsigned char* p, const Color3& w) {
  const registry::ClosureEntry& e = registry::closures()[id];
  std::string s = fmt_triple(w) + " * " + e.name + " (";
  bool first = true;
  for (size_t i = 0; i < e.params.size(); ++i) {
    const registry::ClosureParam& q = e.params[i];
    if (q.keyword && !q.always_printed && is_default(e, i, p)) continue;
    if (!first) s += ", ";
    first = false;
    if (q.keyword) {
      s.push_back('"');
      s.append(q.name);
      s.append("\", ");
    }
    s += fmt_value(q.type, p + registry::param_offset(e.params, i));
  }
  return s + ")";
}

void collect(const ClosureNode* node, const Color3& w, std::vector<std::string>& out, int depth) {
  if (!node || depth > 64) return;
  if (node->id == kClosureAdd) {
    const auto* a = static_cast<const ClosureAdd*>(node);
    collect(a->a, w, out, depth + 1);
    collect(a->b, w, out, depth + 1);
  } else if (node->id == kClosureMul) {
    const auto* m = static_cast<const ClosureMul*>(node);
    collect(m->closure, w * m->weight, out, depth + 1);
  } else if (node->id == kClosureDeclared) {
    const auto* c = static_cast<const ClosureDeclared*>(node);
    out.push_back(declared(*c, w * c->weight));
  } else if (node->id >= 0 && node->id < static_cast<int>(registry::closures().size())) {
    const auto* c = static_cast<const ClosureComponent*>(node);
    out.push_back(component(c->id, c->params(), w * c->weight));
  }
}

} // namespace

std::string closure_to_string(const ClosureNode* closure) {
  std::vector<std::string> terms;
  collect(closure, Color3{1, 1, 1}, terms, 0);
  std::string s;
  for (size_t i = 0; i < terms.size(); ++i) {
    if (i) s.append("\n\t+ ");
    s.append(terms[i]);
  }
  return s;
}

} // namespace lobe

// Registering a renderer's closures (lobe/closure_plugin.h): validation, the registry entry
// (closure_registry.h, add_closure) and the table of their functions (plugin.h).
#include "plugin.h"

#include "closure_registry.h"
#include "closures.h"
#include "common.h"
#include "params.h"

#include <cctype>
#include <deque>

namespace lobe {
namespace closures {
namespace {

// Registered closures, kept for the process (a deque: entries never move), and by id.
struct Plugins {
  std::deque<CustomClosure> list;
  const CustomClosure* by_id[registry::kMaxClosures] = {};
};
Plugins& plugins() {
  static Plugins p;
  return p;
}

bool valid_name(const std::string& s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  for (char ch : s)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_')) return false;
  return true;
}

registry::ArgType arg_type(ClosureParamType t) {
  switch (t) {
  case ClosureParamType::Int:
    return registry::ArgType::Int;
  case ClosureParamType::Float:
    return registry::ArgType::Float;
  case ClosureParamType::Color:
    return registry::ArgType::Color;
  case ClosureParamType::Vector:
    return registry::ArgType::Vector;
  case ClosureParamType::String:
    return registry::ArgType::String;
  case ClosureParamType::Closure:
    return registry::ArgType::Closure;
  }
  return registry::ArgType::Float;
}

// Why `c` cannot be registered, or null.
const char* invalid(const CustomClosure& c) {
  if (!valid_name(c.name))
    return "the name must be letters, digits and '_', not starting with a digit";
  if (!c.eval || !c.pdf || !c.sample) return "eval, pdf and sample are required";
  if (!(c.lobe_flags & (kLobeReflect | kLobeTransmit)))
    return "lobe_flags must include kLobeReflect or kLobeTransmit";
  if (c.lobe_flags & kLobeSpecular) return "delta lobes (kLobeSpecular) cannot be registered";
  bool keywords = false;
  for (const ClosureParamDecl& p : c.params) {
    if (!valid_name(p.name)) return "a parameter name must be letters, digits and '_'";
    if (keywords && !p.keyword) return "a positional parameter follows a keyword parameter";
    keywords |= p.keyword;
  }
  return nullptr;
}

} // namespace

const CustomClosure* plugin(int id) {
  if (id < registry::closure_id::kCount || id >= int(registry::kMaxClosures)) return nullptr;
  return plugins().by_id[id];
}

BsdfEval plugin_eval(const CustomClosure& c, const unsigned char* p, const Vec3& wo, const Vec3& wi,
                     Transport mode) {
  BsdfEval e = c.eval(p, wo, wi, mode, c.user);
  e.value = sanitize(e.value);
  if (!finite_positive(e.pdf)) e.pdf = 0.0f;
  return e;
}

float plugin_pdf(const CustomClosure& c, const unsigned char* p, const Vec3& wo, const Vec3& wi) {
  float pdf = c.pdf(p, wo, wi, c.user);
  return finite_positive(pdf) ? pdf : 0.0f;
}

BsdfSample plugin_sample(const CustomClosure& c, const unsigned char* p, const Vec3& wo,
                         const Vec3& u, Transport mode) {
  Vec3 uc = {clampf(u.x, 0.0f, kOneMinusEpsilon), clampf(u.y, 0.0f, kOneMinusEpsilon),
             clampf(u.z, 0.0f, kOneMinusEpsilon)};
  BsdfSample s = c.sample(p, wo, uc, mode, c.user);
  if (!finite_positive(s.pdf) || !is_finite(s.wi)) return {};
  if (!(std::fabs(dot(s.wi, s.wi) - 1.0f) <= 1e-6f)) s.wi = normalize(s.wi);
  if (is_zero(s.wi)) return {};
  s.weight = sanitize(s.weight);
  if (s.flags == 0) s.flags = c.lobe_flags;
  if (!(s.eta > 0.0f && s.eta < INFINITY)) s.eta = 1.0f;
  return s;
}

Color3 plugin_albedo(const CustomClosure& c, const unsigned char* p, const Vec3& wo) {
  return c.albedo ? sanitize(c.albedo(p, wo, c.user)) : splat(1.0f);
}

} // namespace closures

int register_closure(const CustomClosure& c, std::string* error) {
  auto fail = [&](const char* why) {
    if (error) *error = "register_closure '" + c.name + "': " + why;
    return -1;
  };
  if (const char* why = closures::invalid(c)) return fail(why);
  std::vector<registry::ClosureParam> params;
  for (const ClosureParamDecl& p : c.params) {
    const char* def =
        p.keyword ? (p.default_value.empty() ? "0" : p.default_value.c_str()) : nullptr;
    params.push_back({p.name.c_str(), closures::arg_type(p.type), p.keyword, def, p.doc.c_str()});
  }
  if (registry::param_block_size(params) > closures::Params::kMaxBytes)
    return fail("the parameters take more than 256 bytes");
  uint32_t flags = ((c.lobe_flags & kLobeReflect) ? registry::kReflect : 0u) |
                   ((c.lobe_flags & kLobeTransmit) ? registry::kTransmit : 0u);
  const char* why = nullptr;
  int id =
      registry::add_closure({c.name.c_str(), c.name.c_str(), params, flags, c.doc.c_str()}, &why);
  if (id < 0) return fail(why);
  auto& p = closures::plugins();
  p.by_id[id] = &p.list.emplace_back(c);
  return id;
}

long closure_param_offset(std::string_view closure, std::string_view param) {
  const registry::ClosureEntry* e = registry::find_by_key(closure);
  if (!e) return -1;
  for (size_t i = 0; i < e->params.size(); ++i)
    if (param == e->params[i].name) return long(registry::param_offset(e->params, i));
  return -1;
}

} // namespace lobe

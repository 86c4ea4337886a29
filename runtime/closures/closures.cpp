// The per-lobe API (closures.h): Params blocks built from the registry, and dispatch of
// eval/pdf/sample/albedo to the lobe families through with_lobe (dispatch.h).
#include "closures.h"

#include "closure_registry.h"
#include "dispatch.h"
#include "plugin.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

namespace lobe::closures {
namespace {

using registry::ArgType;

// A Params block asked for what the registry does not have: a programming error in the caller
// (the closure library's own native materials and tests), reported as an exception the caller
// sees rather than printed (the library never prints).
[[noreturn]] void check_failed(const std::string& what) {
  throw std::logic_error("closure parameters: " + what);
}

// Writes a keyword's registry default (literal text) into its slot.
void write_default(const registry::ClosureParam& p, unsigned char* dst) {
  const char* text = p.default_value ? p.default_value : "0";
  switch (p.type) {
  case ArgType::Int: {
    int v = std::atoi(text);
    std::memcpy(dst, &v, 4);
    break;
  }
  case ArgType::Float: {
    float v = std::strtof(text, nullptr);
    std::memcpy(dst, &v, 4);
    break;
  }
  case ArgType::Color:
  case ArgType::Vector: {
    Vec3 v;
    char* end = nullptr;
    v.x = std::strtof(text, &end);
    v.y = *end ? std::strtof(end, &end) : v.x;
    v.z = *end ? std::strtof(end, &end) : v.x;
    std::memcpy(dst, &v, 12);
    break;
  }
  case ArgType::String: {
    const char* v = ""; // only empty-string defaults exist in the table
    std::memcpy(dst, &v, sizeof v);
    break;
  }
  case ArgType::Closure:
    break;
  }
}

// Neutral starting values for positional parameters (see Params).
void write_positional(const registry::ClosureParam& p, unsigned char* dst) {
  std::string_view name = p.name;
  if (p.type == ArgType::Vector) {
    Vec3 v = name == "N" ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
    std::memcpy(dst, &v, 12);
  } else if (p.type == ArgType::Color) {
    Vec3 v{1, 1, 1};
    std::memcpy(dst, &v, 12);
  } else if (p.type == ArgType::String) {
    const char* v = name == "distribution" ? "ggx" : "";
    std::memcpy(dst, &v, sizeof v);
  }
}

} // namespace

Params::Params(std::string_view key) {
  const registry::ClosureEntry* e = registry::find_by_key(key);
  if (!e) check_failed("unknown closure key '" + std::string(key) + "'");
  id_ = registry::id_of(key);
  size_ = registry::param_block_size(e->params);
  if (size_ > kMaxBytes) check_failed("parameter block too large");
  for (size_t i = 0; i < e->params.size(); ++i) {
    unsigned char* dst = data_ + registry::param_offset(e->params, i);
    if (e->params[i].keyword)
      write_default(e->params[i], dst);
    else
      write_positional(e->params[i], dst);
  }
}

unsigned char* Params::slot(std::string_view name, int expected_type) {
  const registry::ClosureEntry& e = registry::closures()[id_];
  for (size_t i = 0; i < e.params.size(); ++i) {
    if (name != e.params[i].name) continue;
    if (expected_type >= 0 && static_cast<int>(e.params[i].type) != expected_type)
      check_failed(std::string(e.key) + "." + std::string(name) + ": wrong type");
    return data_ + registry::param_offset(e.params, i);
  }
  check_failed(std::string(e.key) + " has no parameter '" + std::string(name) + "'");
}

Params& Params::set(std::string_view name, float v) {
  const registry::ClosureEntry& e = registry::closures()[id_];
  for (const registry::ClosureParam& p : e.params) {
    if (name != p.name) continue;
    if (p.type == ArgType::Int) return set(name, static_cast<int>(v));
    if (p.type == ArgType::Color || p.type == ArgType::Vector) return set(name, Vec3{v, v, v});
  }
  std::memcpy(slot(name, static_cast<int>(ArgType::Float)), &v, 4);
  return *this;
}

Params& Params::set(std::string_view name, int v) {
  const registry::ClosureEntry& e = registry::closures()[id_];
  for (const registry::ClosureParam& p : e.params)
    if (name == p.name && p.type == ArgType::Float) return set(name, static_cast<float>(v));
  std::memcpy(slot(name, static_cast<int>(ArgType::Int)), &v, 4);
  return *this;
}

Params& Params::set(std::string_view name, const Vec3& v) {
  std::memcpy(slot(name, -1), &v, 12);
  return *this;
}

Params& Params::set(std::string_view name, const char* v) {
  std::memcpy(slot(name, static_cast<int>(ArgType::String)), &v, sizeof v);
  return *this;
}

Params& Params::set_closure(std::string_view name, const ClosureNode* v) {
  std::memcpy(slot(name, static_cast<int>(ArgType::Closure)), &v, sizeof v);
  return *this;
}

BsdfEval eval(int id, const unsigned char* params, const Vec3& wo, const Vec3& wi, Transport mode) {
  if (const CustomClosure* c = plugin(id)) return plugin_eval(*c, params, wo, wi, mode);
  BsdfEval r;
  with_lobe(id, params, [&](const auto& l, const Frame& f) {
    BsdfEval e = eval_lobe(l, f, wo, wi, mode);
    r.value = e.value;
    r.pdf = e.pdf;
  });
  return r;
}

float pdf(int id, const unsigned char* params, const Vec3& wo, const Vec3& wi) {
  if (const CustomClosure* c = plugin(id)) return plugin_pdf(*c, params, wo, wi);
  return eval(id, params, wo, wi, Transport::Radiance).pdf;
}

std::optional<BsdfSample> sample(int id, const unsigned char* params, const Vec3& wo, const Vec3& u,
                                 Transport mode) {
  std::optional<BsdfSample> r;
  if (const CustomClosure* c = plugin(id)) {
    BsdfSample s = plugin_sample(*c, params, wo, u, mode);
    if (s.pdf > 0.0f) r = s;
    return r;
  }
  with_lobe(id, params, [&](const auto& l, const Frame& f) {
    BsdfSample s = sample_lobe(l, f, wo, u, mode);
    if (s.pdf > 0.0f) r = s;
  });
  return r;
}

Color3 albedo(int id, const unsigned char* params, const Vec3& wo) {
  if (const CustomClosure* c = plugin(id)) return plugin_albedo(*c, params, wo);
  Color3 r;
  with_lobe(id, params, [&](const auto& l, const Frame& f) { r = albedo_lobe(l, f, wo); });
  return r;
}

uint32_t lobe_flags(int id, const unsigned char* params) {
  if (const CustomClosure* c = plugin(id)) return c->lobe_flags;
  uint32_t r = 0;
  with_lobe(id, params, [&](const auto& l, const Frame&) { r = l.flags(); });
  return r;
}

// A registered closure's state is its parameter block's address: its functions take the
// block.
const unsigned char* plugin_params(const void* state) {
  return *static_cast<const unsigned char* const*>(state);
}

uint32_t setup(int id, const unsigned char* params, void* state) {
  if (const CustomClosure* c = plugin(id)) {
    *static_cast<const unsigned char**>(state) = params;
    return c->lobe_flags;
  }
  return setup_lobe(id, params, state);
}

BsdfEval eval_prepared(int id, const void* state, const Vec3& wo, const Vec3& wi, Transport mode) {
  if (const CustomClosure* c = plugin(id))
    return plugin_eval(*c, plugin_params(state), wo, wi, mode);
  BsdfEval r;
  with_prepared(id, state,
                [&](const auto& l, const Frame& f) { r = eval_lobe(l, f, wo, wi, mode); });
  return r;
}

std::optional<BsdfSample> sample_prepared(int id, const void* state, const Vec3& wo, const Vec3& u,
                                          Transport mode) {
  std::optional<BsdfSample> r;
  if (const CustomClosure* c = plugin(id)) {
    BsdfSample s = plugin_sample(*c, plugin_params(state), wo, u, mode);
    if (s.pdf > 0.0f) r = s;
    return r;
  }
  with_prepared(id, state, [&](const auto& l, const Frame& f) {
    BsdfSample s = sample_lobe(l, f, wo, u, mode);
    if (s.pdf > 0.0f) r = s;
  });
  return r;
}

Color3 albedo_prepared(int id, const void* state, const Vec3& wo) {
  if (const CustomClosure* c = plugin(id)) return plugin_albedo(*c, plugin_params(state), wo);
  Color3 r;
  with_prepared(id, state, [&](const auto& l, const Frame& f) { r = albedo_lobe(l, f, wo); });
  return r;
}

bool has_implementation(int id) {
  if (id < 0 || id >= static_cast<int>(registry::closures().size())) return false;
  if (plugin(id)) return true;
  uint32_t fl = registry::closures()[id].flags;
  if (!(fl & (registry::kReflect | registry::kTransmit))) return true; // handled by Bsdf::build
  if (id == closure_id::measured_bsdf)
    return true; // its default block names no file, so it cannot be probed
  Params p(registry::closures()[id].key);
  return with_lobe(id, p.data(), [](const auto&, const Frame&) {});
}

const char* param_warning(int id, const unsigned char* params) {
  float thickness = 0.0f;
  if (id == closure_id::conductor_bsdf) thickness = as<ConductorParams>(params).thinfilm_thickness;
  if (id == closure_id::dielectric_bsdf)
    thickness = as<DielectricParams>(params).thinfilm_thickness;
  if (id == closure_id::generalized_schlick_bsdf)
    thickness = as<GeneralizedSchlickParams>(params).thinfilm_thickness;
  return thickness < 0.0f || thickness != thickness
             ? "thinfilm_thickness is negative or NaN: no thin film"
             : nullptr;
}

} // namespace lobe::closures

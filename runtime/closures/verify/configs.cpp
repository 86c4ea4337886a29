// Parameter grids for the property suites, derived from parameter names in the registry.
#include "configs.h"

#include "closure_registry.h"

#include <cmath>
#include <functional>
#include <string_view>

namespace lobe::verify {
namespace {

using registry::ArgType;
using registry::ClosureEntry;

const registry::ClosureParam* find_param(const ClosureEntry& e, std::string_view name) {
  for (const registry::ClosureParam& p : e.params)
    if (name == p.name) return &p;
  return nullptr;
}
bool has(const ClosureEntry& e, std::string_view name, ArgType t) {
  const registry::ClosureParam* p = find_param(e, name);
  return p && p->type == t;
}

// One value of one axis: a name suffix and how it changes the configuration.
struct Value {
  std::string suffix;
  std::function<void(ClosureConfig&)> apply;
};
using Axis = std::vector<Value>;

// Neutral, physically plausible starting values (Params starts floats at 0, colours at 1).
void set_defaults(const ClosureEntry& e, ClosureConfig& c) {
  static constexpr const char* kAlphas[] = {"roughness_x", "roughness_y", "xalpha", "yalpha",
                                            "ax",          "ay",          "alpha"};
  for (const char* a : kAlphas)
    if (has(e, a, ArgType::Float)) c.params.set(a, 0.3f);
  for (const char* r : {"roughness", "sigma"})
    if (has(e, r, ArgType::Float)) c.params.set(r, 0.5f);
  if (has(e, "exponent", ArgType::Float))
    c.params.set("exponent", find_param(e, "f0") ? 5.0f : 20.0f);
  if (has(e, "shininess", ArgType::Float)) c.params.set("shininess", 20.0f);
  bool transmits = e.flags & registry::kTransmit;
  for (const char* eta : {"eta", "ior"})
    if (has(e, eta, ArgType::Float)) {
      c.params.set(eta, 1.5f);
      if (transmits) c.eta_below = 1.5;
    }
  if (has(e, "ior", ArgType::Color)) c.params.set("ior", Vec3{0.2f, 0.9f, 1.1f});
  if (has(e, "extinction", ArgType::Color)) c.params.set("extinction", Vec3{3.9f, 2.4f, 2.2f});
  if (has(e, "f0", ArgType::Color)) {
    c.params.set("f0", Vec3{0.9f, 0.5f, 0.04f});
    // generalized_schlick_bsdf refracts with the IOR whose normal-incidence reflectance is the
    // mean of f0 (docs/closures.md): eta = (1 + sqrt f0)/(1 - sqrt f0), 5.51 here.
    double s = std::sqrt((0.9 + 0.5 + 0.04) / 3.0);
    if (transmits) c.eta_below = (1.0 + s) / (1.0 - s);
  }
  if (has(e, "refract", ArgType::Int)) c.params.set("refract", 2);
}

Axis roughness_pair_axis(const ClosureEntry& e, Level level) {
  static constexpr const char* kPairs[][2] = {
      {"roughness_x", "roughness_y"}, {"xalpha", "yalpha"}, {"ax", "ay"}};
  for (const auto& pr : kPairs) {
    if (!has(e, pr[0], ArgType::Float) || !has(e, pr[1], ArgType::Float)) continue;
    std::string x = pr[0], y = pr[1];
    auto pair = [x, y](float ax, float ay, std::string s) {
      return Value{s, [=](ClosureConfig& c) { c.params.set(x, ax).set(y, ay); }};
    };
    Axis a{pair(0.05f, 0.05f, "a=0.05"), pair(0.5f, 0.5f, "a=0.5"),
           pair(0.2f, 0.05f, "a=(0.2,0.05)")};
    if (level == Level::Full) a.push_back(pair(0.125f, 0.125f, "a=0.125"));
    return a;
  }
  return {};
}

Axis float_axis(const ClosureEntry& e, const char* name, std::vector<float> quick,
                std::vector<float> full, Level level) {
  if (!has(e, name, ArgType::Float)) return {};
  Axis a;
  std::string n = name;
  for (float v : (level == Level::Quick ? quick : full)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s=%g", name, v);
    a.push_back({buf, [n, v](ClosureConfig& c) { c.params.set(n, v); }});
  }
  return a;
}

Axis eta_axis(const ClosureEntry& e, Level level) {
  bool transmits = e.flags & registry::kTransmit;
  for (const char* name : {"eta", "ior"}) {
    if (!has(e, name, ArgType::Float)) continue;
    std::string n = name;
    auto val = [n, transmits](float v, const char* s) {
      return Value{s, [=](ClosureConfig& c) {
                     c.params.set(n, v);
                     c.eta_below = transmits ? v : 1.0;
                   }};
    };
    Axis a{val(1.5f, "eta=1.5")};
    if (level == Level::Full) a.push_back(val(1.0f / 1.5f, "eta=0.667"));
    return a;
  }
  return {};
}

Axis distribution_axis(const ClosureEntry& e) {
  if (!has(e, "distribution", ArgType::String)) return {};
  return {{"ggx", [](ClosureConfig& c) { c.params.set("distribution", "ggx"); }},
          {"beckmann", [](ClosureConfig& c) { c.params.set("distribution", "beckmann"); }}};
}

Axis refract_axis(const ClosureEntry& e, Level level) {
  if (!has(e, "refract", ArgType::Int)) return {};
  Axis a;
  for (int v : (level == Level::Quick ? std::vector<int>{2} : std::vector<int>{0, 1, 2}))
    a.push_back(
        {"refract=" + std::to_string(v), [v](ClosureConfig& c) { c.params.set("refract", v); }});
  return a;
}

std::vector<Axis> axes_for(const ClosureEntry& e, Level level) {
  std::vector<Axis> axes{
      distribution_axis(e),
      roughness_pair_axis(e, level),
      float_axis(e, "alpha", {0.05f, 0.5f}, {0.05f, 0.125f, 0.5f}, level),
      float_axis(e, "roughness", {0.5f}, {0.0f, 0.5f, 1.0f}, level),
      float_axis(e, "sigma", {0.5f}, {0.0f, 0.5f, 1.0f}, level),
      eta_axis(e, level),
      refract_axis(e, level),
  };
  if (!find_param(e, "f0")) axes.push_back(float_axis(e, "exponent", {20}, {1, 20, 200}, level));
  std::erase_if(axes, [](const Axis& a) { return a.empty(); });
  return axes;
}

Vec3 at_angle(double deg, bool inside) {
  double t = deg * M_PI / 180.0;
  return {static_cast<float>(std::sin(t)), 0.0f,
          static_cast<float>(inside ? -std::cos(t) : std::cos(t))};
}

} // namespace

std::vector<Incident> incident_set(Level level, bool inside) {
  std::vector<Incident> v;
  Vec3 grazing = normalize(Vec3{0.5f, 0.5f, 0.001f});
  if (level == Level::Quick) {
    v = {{"30deg", at_angle(30, false)}, {"grazing", grazing}};
    if (inside) v.push_back({"inside60", at_angle(60, true)});
    return v;
  }
  for (double d : {0.0, 30.0, 60.0, 85.0})
    v.push_back({std::to_string(static_cast<int>(d)) + "deg", at_angle(d, false)});
  v.push_back({"grazing", grazing});
  if (inside)
    for (double d : {30.0, 60.0})
      v.push_back({"inside" + std::to_string(static_cast<int>(d)), at_angle(d, true)});
  return v;
}

bool is_testable(int id) {
  auto all = registry::closures();
  if (id < 0 || id >= static_cast<int>(all.size())) return false;
  const ClosureEntry& e = all[id];
  if (!(e.flags & (registry::kReflect | registry::kTransmit))) return false;
  if (find_param(e, "filename")) return false; // measured data: needs a file, tested apart
  for (const registry::ClosureParam& p : e.params)
    if (p.type == ArgType::Closure) return false;
  return closures::has_implementation(id);
}

std::vector<ClosureConfig> configs_for(int id, Level level) {
  if (!is_testable(id)) return {};
  const ClosureEntry& e = registry::closures()[id];
  ClosureConfig base{e.key, closures::Params(e.key), 1.0, false, {}};
  set_defaults(e, base);
  base.incident = incident_set(level, e.flags & registry::kTransmit);
  std::vector<ClosureConfig> out{base};
  for (const Axis& axis : axes_for(e, level)) {
    std::vector<ClosureConfig> next;
    for (const ClosureConfig& c : out)
      for (const Value& v : axis) {
        ClosureConfig n = c;
        n.name += " " + v.suffix;
        v.apply(n);
        next.push_back(n);
      }
    out = std::move(next);
  }
  return out;
}

std::vector<ClosureConfig> lossless_configs(Level level) {
  std::vector<ClosureConfig> out;
  std::vector<float> alphas = level == Level::Quick ? std::vector<float>{0.125f, 1.0f}
                                                    : std::vector<float>{0.05f, 0.125f, 0.5f, 1.0f};
  std::vector<Incident> inc;
  for (double d : {0.0, 30.0, 60.0, 85.0})
    inc.push_back({std::to_string(static_cast<int>(d)) + "deg", at_angle(d, false)});
  for (const char* dist : {"ggx", "beckmann"})
    for (float a : alphas) {
      char suffix[48];
      std::snprintf(suffix, sizeof suffix, " %s a=%g lossless", dist, a);
      int cid = registry::id_of("conductor_bsdf");
      if (cid >= 0 && closures::has_implementation(cid)) {
        closures::Params p("conductor_bsdf");
        p.set("roughness_x", a).set("roughness_y", a).set("distribution", dist);
        p.set("ior", Vec3{1, 1, 1}).set("extinction", Vec3{1000, 1000, 1000});
        p.set("energy_compensation", 1);
        out.push_back({std::string("conductor_bsdf") + suffix, p, 1.0, true, inc});
      }
      int gid = registry::id_of("generalized_schlick_bsdf");
      if (gid >= 0 && closures::has_implementation(gid)) {
        closures::Params p("generalized_schlick_bsdf");
        p.set("roughness_x", a).set("roughness_y", a).set("distribution", dist);
        p.set("f0", Vec3{1, 1, 1}).set("f90", Vec3{1, 1, 1}).set("exponent", 5.0f);
        p.set("transmission_tint", Vec3{0, 0, 0}).set("energy_compensation", 1);
        out.push_back({std::string("generalized_schlick_bsdf") + suffix, p, 1.0, true, inc});
      }
    }
  return out;
}

} // namespace lobe::verify

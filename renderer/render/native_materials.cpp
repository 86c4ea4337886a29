// Native stdlib materials (see native_materials.h). Each mirrors its .osl file line by line.
#include "native_materials.h"

#include "closures.h"

#include "lobe/context.h"

#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <new>
#include <sstream>
#include <vector>

namespace lobe::render {

uint64_t global_bit(const char* name) {
  for (size_t i = 0; i < std::size(kGlobalFields); ++i)
    if (std::strcmp(kGlobalFields[i].name, name) == 0) return uint64_t(1) << i;
  return 0;
}

namespace {

// The parameters of each native shader, as declared in its .osl file.
enum class PType { Float, Color, String };
struct ParamSpec {
  const char* name;
  PType type;
};

const std::vector<ParamSpec>* params_of(const std::string& shader) {
  using P = PType;
  static const std::map<std::string, std::vector<ParamSpec>> kParams = {
      {"matte", {{"Cs", P::Color}, {"Kd", P::Float}, {"roughness", P::Float}}},
      {"plastic",
       {{"Cs", P::Color},
        {"Kd", P::Float},
        {"Ks", P::Float},
        {"roughness", P::Float},
        {"ior", P::Float}}},
      {"metal",
       {{"preset", P::String},
        {"ior", P::Color},
        {"extinction", P::Color},
        {"roughness", P::Float},
        {"tint", P::Color}}},
      {"brushed_metal",
       {{"preset", P::String},
        {"roughness_along", P::Float},
        {"roughness_across", P::Float},
        {"tint", P::Color}}},
      {"glass",
       {{"transmission_color", P::Color},
        {"reflection_color", P::Color},
        {"ior", P::Float},
        {"roughness", P::Float}}},
      {"emitter", {{"Cs", P::Color}, {"power", P::Float}}},
      {"mirror", {{"Cs", P::Color}}},
      {"constant_background", {{"Cs", P::Color}}},
  };
  auto it = kParams.find(shader);
  return it == kParams.end() ? nullptr : &it->second;
}

// Instance values by name, checked against the shader's parameters as the JIT checks them
// (runtime/group/instance_values.cpp): a string parameter takes the text; a float exactly one
// number; a color one number (grey) or three. Messages match the JIT's.
class ParamValues {
public:
  bool parse(const ShaderGroup::Layer& layer, const std::vector<ParamSpec>& specs,
             std::string& error) {
    for (const InstanceValue& iv : layer.values) {
      const ParamSpec* spec = nullptr;
      for (const ParamSpec& ps : specs)
        if (iv.name == ps.name) spec = &ps;
      if (!spec) { // as the renderer reports the JIT's warning for it
        std::string names;
        for (const ParamSpec& ps : specs)
          names += (names.empty() ? "" : ", ") + std::string(ps.name);
        error = "layer '" + layer.name + "': shader '" + layer.shader + "' has no parameter '" +
                iv.name + "' (its parameters: " + names + ")";
        return false;
      }
      if (spec->type == PType::String) {
        strings_[iv.name] = iv.value;
        continue;
      }
      std::istringstream in(iv.value);
      std::vector<float> v;
      bool ok = true;
      for (std::string w; in >> w;) {
        char* end = nullptr;
        float x = std::strtof(w.c_str(), &end);
        ok &= end != w.c_str() && !*end;
        v.push_back(x);
      }
      ok &= spec->type == PType::Float ? v.size() == 1 : (v.size() == 1 || v.size() == 3);
      if (!ok) {
        error = "layer '" + layer.name + "': value '" + iv.value + "' does not fit parameter '" +
                iv.name + "' of type " + (spec->type == PType::Float ? "float" : "color");
        return false;
      }
      nums_[iv.name] = v;
    }
    return true;
  }
  float f(const char* name, float def) const {
    auto it = nums_.find(name);
    return it == nums_.end() ? def : it->second[0];
  }
  Color3 c(const char* name, Color3 def) const {
    auto it = nums_.find(name);
    if (it == nums_.end()) return def;
    const auto& v = it->second;
    return v.size() >= 3 ? Color3{v[0], v[1], v[2]} : Color3{v[0], v[0], v[0]};
  }
  std::string s(const char* name, const char* def) const {
    auto it = strings_.find(name);
    return it == strings_.end() ? def : it->second;
  }

private:
  std::map<std::string, std::vector<float>> nums_;
  std::map<std::string, std::string> strings_;
};

// Closure-tree construction in the context arena.
ClosureNode* component(ShadingContext& ctx, const closures::Params& p, const Color3& w) {
  void* mem = ctx.allocate(sizeof(ClosureComponent) + p.size());
  if (!mem) return nullptr;
  auto* c = new (mem) ClosureComponent;
  c->id = p.id();
  c->weight = w;
  std::memcpy(c->params(), p.data(), p.size());
  return c;
}

ClosureNode* layer(ShadingContext& ctx, const ClosureNode* top, const ClosureNode* base) {
  closures::Params p("layer");
  p.set_closure("top", top).set_closure("base", base);
  return component(ctx, p, {1, 1, 1});
}

struct MetalIor {
  Color3 n, k;
};
MetalIor metal_preset(const std::string& name, const MetalIor& custom) {
  if (name == "gold") return {{0.18299f, 0.42108f, 1.37340f}, {3.42420f, 2.34590f, 1.77040f}};
  if (name == "silver") return {{0.15943f, 0.14512f, 0.13547f}, {3.92910f, 3.19000f, 2.38080f}};
  if (name == "copper") return {{0.27105f, 0.67693f, 1.31640f}, {3.60920f, 2.62480f, 2.29210f}};
  if (name == "aluminium") return {{1.65740f, 0.88037f, 0.52123f}, {9.22380f, 6.26950f, 4.83700f}};
  return custom;
}

using ShadeFn = std::function<const ClosureNode*(ShaderGlobals&, ShadingContext&)>;

class NativeMaterial final : public Material {
public:
  NativeMaterial(ShadeFn fn, uint64_t reads) : fn_(std::move(fn)), reads_(reads) {}
  void shade(ShaderGlobals& sg) const override { sg.Ci = fn_(sg, *sg.context); }
  uint64_t globals_read() const override { return reads_; }
  bool read_output(const ShadingContext&, const std::string&, const std::string&,
                   std::vector<float>&) const override {
    return false;
  }
  const CompileStats& stats() const override { return stats_; }

private:
  ShadeFn fn_;
  uint64_t reads_;
  CompileStats stats_;
};

// The stdlib shaders, as closures over their parameter values.
ShadeFn make_shader(const std::string& name, const ParamValues& p) {
  if (name == "matte") {
    Color3 albedo = p.c("Cs", {0.8f, 0.8f, 0.8f}) * p.f("Kd", 1);
    float rough = p.f("roughness", 0);
    return [=](ShaderGlobals& sg, ShadingContext& ctx) -> const ClosureNode* {
      if (rough > 0) {
        closures::Params q("oren_nayar_diffuse_bsdf");
        q.set("N", sg.N)
            .set("albedo", albedo)
            .set("roughness", rough)
            .set("energy_compensation", 1);
        return component(ctx, q, {1, 1, 1});
      }
      closures::Params q("diffuse");
      q.set("N", sg.N);
      return component(ctx, q, albedo);
    };
  }
  if (name == "plastic") {
    Color3 base = p.c("Cs", {0.8f, 0.8f, 0.8f}) * p.f("Kd", 1);
    float ks = p.f("Ks", 1), r = p.f("roughness", 0.2f), ior = p.f("ior", 1.5f);
    return [=](ShaderGlobals& sg, ShadingContext& ctx) -> const ClosureNode* {
      closures::Params coat("dielectric_bsdf");
      coat.set("N", sg.N)
          .set("U", normalize(sg.dPdu))
          .set("reflection_tint", Color3{ks, ks, ks})
          .set("transmission_tint", Color3{0, 0, 0})
          .set("roughness_x", r * r)
          .set("roughness_y", r * r)
          .set("ior", ior)
          .set("distribution", "ggx");
      closures::Params diff("diffuse");
      diff.set("N", sg.N);
      return layer(ctx, component(ctx, coat, {1, 1, 1}), component(ctx, diff, base));
    };
  }
  if (name == "metal" || name == "brushed_metal") {
    bool brushed = name == "brushed_metal";
    // brushed_metal has no ior/extinction: an unknown preset is aluminium, as in its .osl.
    MetalIor custom = brushed ? metal_preset("aluminium", {})
                              : MetalIor{p.c("ior", {0.18299f, 0.42108f, 1.37340f}),
                                         p.c("extinction", {3.42420f, 2.34590f, 1.77040f})};
    MetalIor m = metal_preset(p.s("preset", brushed ? "aluminium" : "gold"), custom);
    float rx = brushed ? p.f("roughness_along", 0.15f) : p.f("roughness", 0.3f);
    float ry = brushed ? p.f("roughness_across", 0.6f) : rx;
    Color3 tint = p.c("tint", {1, 1, 1});
    return [=](ShaderGlobals& sg, ShadingContext& ctx) -> const ClosureNode* {
      closures::Params q("conductor_bsdf");
      q.set("N", sg.N)
          .set("U", normalize(sg.dPdu))
          .set("roughness_x", rx * rx)
          .set("roughness_y", ry * ry)
          .set("ior", m.n)
          .set("extinction", m.k)
          .set("distribution", "ggx");
      return component(ctx, q, tint);
    };
  }
  if (name == "glass") {
    Color3 tt = p.c("transmission_color", {1, 1, 1}), rt = p.c("reflection_color", {1, 1, 1});
    float ior = p.f("ior", 1.5f), r = p.f("roughness", 0);
    return [=](ShaderGlobals& sg, ShadingContext& ctx) -> const ClosureNode* {
      closures::Params q("dielectric_bsdf");
      q.set("N", sg.N)
          .set("U", normalize(sg.dPdu))
          .set("reflection_tint", rt)
          .set("transmission_tint", tt)
          .set("roughness_x", r * r)
          .set("roughness_y", r * r)
          .set("ior", ior)
          .set("distribution", "ggx");
      return component(ctx, q, {1, 1, 1});
    };
  }
  if (name == "emitter") {
    Color3 e = p.c("Cs", {1, 1, 1}) * p.f("power", 1);
    return [=](ShaderGlobals&, ShadingContext& ctx) -> const ClosureNode* {
      return component(ctx, closures::Params("emission"), e);
    };
  }
  if (name == "mirror") {
    Color3 cs = p.c("Cs", {1, 1, 1});
    return [=](ShaderGlobals& sg, ShadingContext& ctx) -> const ClosureNode* {
      closures::Params q("reflection");
      q.set("N", sg.N);
      return component(ctx, q, cs);
    };
  }
  if (name == "constant_background") {
    Color3 cs = p.c("Cs", {1, 1, 1});
    return [=](ShaderGlobals&, ShadingContext& ctx) -> const ClosureNode* {
      return component(ctx, closures::Params("background"), cs);
    };
  }
  return nullptr;
}

uint64_t reads_of(const std::string& name) {
  if (name == "emitter" || name == "constant_background") return 0;
  if (name == "matte" || name == "mirror") return global_bit("N");
  return global_bit("N") | global_bit("dPdu");
}

} // namespace

bool has_native_material(const std::string& shader) {
  static const char* kNames[] = {"matte",         "plastic", "metal",  "glass",
                                 "brushed_metal", "emitter", "mirror", "constant_background"};
  for (const char* n : kNames)
    if (shader == n) return true;
  return false;
}

std::shared_ptr<const Material> make_native_material(const ShaderGroup& group, std::string& error) {
  if (group.layers.size() != 1 || !group.connections.empty()) {
    error = "native materials take a single layer without connections";
    return nullptr;
  }
  const ShaderGroup::Layer& l = group.layers[0];
  if (!has_native_material(l.shader)) {
    error = "no native version of shader '" + l.shader + "'";
    return nullptr;
  }
  ParamValues p;
  if (!p.parse(l, *params_of(l.shader), error)) return nullptr;
  return std::make_shared<NativeMaterial>(make_shader(l.shader, p), reads_of(l.shader));
}

} // namespace lobe::render

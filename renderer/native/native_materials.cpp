// Native stdlib materials (see native_materials.h). Each mirrors its .osl file line by line;
// the parameters and their defaults are read from the .osl file itself.
#include "native_materials.h"

#include "closures.h"
#include "driver/driver.h"
#include "instance_values.h"

#include "lobe/context.h"
#include "lobe/install.h"

#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <new>
#include <vector>

namespace lobe::render {

MaterialCompiler native_compiler() {
  return [](const scene::MaterialDesc& m, std::string& error) {
    return make_native_material(m.group, error, m.unknown_params_warn);
  };
}

namespace {

// The parameters of a native shader: those its .osl file declares (name, type, constant
// default, in declaration order), read from the stdlib shader compiled by the front end, so the
// twins cannot drift from the shaders' interfaces. Only float, color and string parameters.
enum class PType { Float, Color, String };
struct ParamSpec {
  std::string name;
  PType type;
  std::vector<float> def; // Float: 1 value, Color: 3
  std::string def_s;      // String
  ir::Type ir_type;       // as declared (instance values are read for it)
};
struct DeclaredParams {
  std::vector<ParamSpec> params;
  std::string error; // why the .osl could not be read
};

DeclaredParams read_declared_params(const std::string& shader) {
  DeclaredParams out;
  std::string path = stdlib_shader_dir() + "/" + shader + ".osl";
  // Through the one compile driver, as the JIT's materials load their shaders (it reads the
  // file once; whether it exists is asked only when that fails).
  driver::Loaded r = driver::load_file(path, driver::Options{});
  if (!r.ok || !r.shader) {
    out.error = !std::filesystem::exists(path)
                    ? "cannot read stdlib shader " + path
                    : "stdlib shader " + path + " does not compile:\n" + r.rendered();
    return out;
  }
  for (const ir::Symbol& sym : r.shader->symbols) {
    if (sym.kind != ir::SymKind::Param) continue;
    ParamSpec ps{sym.name, PType::Float, {}, {}, sym.type};
    if (sym.type.is_array() || sym.init.empty() ||
        !(sym.type.base == ir::BaseType::Float || sym.type.is_triple() ||
          sym.type.base == ir::BaseType::String)) {
      out.error = path + ": parameter '" + sym.name + "' is not a float, color or string with " +
                  "a constant default (the native twins take no other)";
      return out;
    }
    if (sym.type.base == ir::BaseType::String) {
      ps.type = PType::String;
      ps.def_s = sym.init[0].s;
    } else {
      ps.type = sym.type.is_triple() ? PType::Color : PType::Float;
      for (const ir::ConstValue& v : sym.init) ps.def.push_back(v.f);
    }
    out.params.push_back(std::move(ps));
  }
  return out;
}

// Read once per shader, from any thread.
const DeclaredParams& declared_params(const std::string& shader) {
  static std::mutex mu;
  static std::map<std::string, DeclaredParams> cache;
  std::lock_guard<std::mutex> lock(mu);
  auto it = cache.find(shader);
  if (it == cache.end()) it = cache.emplace(shader, read_declared_params(shader)).first;
  return it->second;
}

// Instance values by name, read for the shader's parameters by the JIT's own rules
// (group::fit_instance_value, runtime/group/instance_values.cpp), so both backends take and
// refuse the same values with the same words. A value OSL ignores with a warning (a type that
// does not fit, group text's rules) leaves the default, as in the JIT. A parameter without an
// instance value has its declared default.
class ParamValues {
public:
  bool parse(const ShaderGroup::Layer& layer, const std::vector<ParamSpec>& specs,
             bool unknown_params_ignored, std::string& error) {
    specs_ = &specs;
    for (const InstanceValue& iv : layer.values) {
      const ParamSpec* spec = find(iv.name);
      if (!spec) { // the JIT's note for it (the renderer makes it an error in JSON scenes)
        if (unknown_params_ignored) continue; // testrender XML: ignored, as the JIT ignores it
        std::vector<std::string> names;
        for (const ParamSpec& ps : specs) names.push_back(ps.name);
        error = group::nonexistent_param_note(layer.name, layer.shader, iv.name, names);
        return false;
      }
      group::ValueFit fit = group::fit_instance_value(iv, spec->ir_type);
      if (!fit.error.empty()) {
        error = "layer '" + layer.name + "': " + fit.error;
        return false;
      }
      if (!fit.ok || fit.values.empty()) continue;
      if (spec->type == PType::String) {
        strings_[iv.name] = fit.values[0].s;
        continue;
      }
      std::vector<float>& v = nums_[iv.name];
      for (const ir::ConstValue& c : fit.values) v.push_back(c.f);
    }
    return true;
  }
  float f(const char* name) const { return numbers(name)[0]; }
  Color3 c(const char* name) const {
    const std::vector<float>& v = numbers(name);
    return v.size() >= 3 ? Color3{v[0], v[1], v[2]} : Color3{v[0], v[0], v[0]};
  }
  std::string s(const char* name) const {
    auto it = strings_.find(name);
    if (it != strings_.end()) return it->second;
    const ParamSpec* spec = find(name);
    return spec ? spec->def_s : "";
  }

private:
  const ParamSpec* find(const std::string& name) const {
    for (const ParamSpec& ps : *specs_)
      if (ps.name == name) return &ps;
    return nullptr;
  }
  // The instance value, else the default (make_shader asks only for declared parameters).
  const std::vector<float>& numbers(const char* name) const {
    static const std::vector<float> kZero{0};
    auto it = nums_.find(name);
    if (it != nums_.end()) return it->second;
    const ParamSpec* spec = find(name);
    return spec && !spec->def.empty() ? spec->def : kZero;
  }

  const std::vector<ParamSpec>* specs_ = nullptr;
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
    Color3 albedo = p.c("Cs") * p.f("Kd");
    float rough = p.f("roughness");
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
    Color3 base = p.c("Cs") * p.f("Kd");
    float ks = p.f("Ks"), r = p.f("roughness"), ior = p.f("ior");
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
    MetalIor custom =
        brushed ? metal_preset("aluminium", {}) : MetalIor{p.c("ior"), p.c("extinction")};
    MetalIor m = metal_preset(p.s("preset"), custom);
    float rx = brushed ? p.f("roughness_along") : p.f("roughness");
    float ry = brushed ? p.f("roughness_across") : rx;
    Color3 tint = p.c("tint");
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
    Color3 tt = p.c("transmission_color"), rt = p.c("reflection_color");
    float ior = p.f("ior"), r = p.f("roughness");
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
    Color3 e = p.c("Cs") * p.f("power");
    return [=](ShaderGlobals&, ShadingContext& ctx) -> const ClosureNode* {
      return component(ctx, closures::Params("emission"), e);
    };
  }
  if (name == "mirror") {
    Color3 cs = p.c("Cs");
    return [=](ShaderGlobals& sg, ShadingContext& ctx) -> const ClosureNode* {
      closures::Params q("reflection");
      q.set("N", sg.N);
      return component(ctx, q, cs);
    };
  }
  if (name == "constant_background") {
    Color3 cs = p.c("Cs");
    return [=](ShaderGlobals&, ShadingContext& ctx) -> const ClosureNode* {
      return component(ctx, closures::Params("background"), cs);
    };
  }
  return nullptr;
}

uint64_t reads_of(const std::string& name) {
  // Closures of constant weights: the same everywhere (Material::kUniform).
  if (name == "emitter" || name == "constant_background") return Material::kUniform;
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

std::shared_ptr<const Material> make_native_material(const ShaderGroup& group, std::string& error,
                                                     bool unknown_params_ignored) {
  if (group.layers.size() != 1 || !group.connections.empty()) {
    error = "native materials take a single layer without connections";
    return nullptr;
  }
  const ShaderGroup::Layer& l = group.layers[0];
  if (!has_native_material(l.shader)) {
    error = "no native version of shader '" + l.shader + "'";
    return nullptr;
  }
  const DeclaredParams& declared = declared_params(l.shader);
  if (!declared.error.empty()) {
    error = declared.error;
    return nullptr;
  }
  ParamValues p;
  if (!p.parse(l, declared.params, unknown_params_ignored, error)) return nullptr;
  return std::make_shared<NativeMaterial>(make_shader(l.shader, p), reads_of(l.shader));
}

} // namespace lobe::render

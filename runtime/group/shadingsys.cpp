// ShadingSystem (shadingsys.h): group parsing, the compile pipeline (load layers -> cache
// look-up -> specialise -> LLVM IR -> optimise -> JIT) and the material cache.
#include "lobe/shadingsys.h"

#include "closure_registry.h"
#include "codegen.h"
#include "color_system.h"
#include "disk_cache.h"
#include "group_build.h"
#include "group_text.h"
#include "ir/printer.h"
#include "jit.h"
#include "lobe/bsdf.h"
#include "material.h"
#include "shadeop_bitcode.h"
#include "shader_source.h"

#include <llvm/Bitcode/BitcodeWriter.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>
#include <llvm/Support/raw_ostream.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <mutex>
#include <unordered_map>

namespace lobe {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
} // namespace

struct ShadingSystem::Impl {
  CompileOptions options;
  std::shared_ptr<shadeops::RuntimeEnv> env = std::make_shared<shadeops::RuntimeEnv>();
  std::shared_ptr<jit::Jit> jit;
  std::string jit_error;
  std::mutex mutex; // guards the maps below
  std::map<std::string, ir::Shader> registered;
  std::unordered_map<std::string, std::shared_ptr<const Material>> cache;

  std::optional<ir::Shader> load(const std::string& name, DiagnosticList& diags, CompileStats& st);
  std::string cache_key(const ShaderGroup& g, const std::vector<const ir::Shader*>& layers) const;
  // The colour system options.colorspace names (Rec709 when it names none).
  const shadeops::ColorSystem* colors() const {
    const shadeops::ColorSystem* cs = shadeops::ColorSystem::find(options.colorspace);
    return cs ? cs : &shadeops::ColorSystem::rec709();
  }
  std::shared_ptr<const Material> build(const ShaderGroup& g,
                                        const std::vector<const ir::Shader*>& layers,
                                        CompileStats stats, DiagnosticList& diags);
  bool compile_to_code(llvm::Module& mod, const std::string& entry,
                       const codegen::HostSymbols& host, jit::CompiledGroup& code,
                       jit::JitTimes& times, std::string& err);
};

const std::vector<std::string>& colorspace_names() { return shadeops::ColorSystem::names(); }

std::string colorspace_error(const std::string& name) {
  if (name.empty() || shadeops::ColorSystem::find(name)) return ""; // "": the default
  return "Unknown color space \"" + name + "\"";
}

ShadingSystem::ShadingSystem() : impl_(std::make_unique<Impl>()) {
  impl_->env->closure_printer = &closure_to_string;
  std::unique_ptr<jit::Jit> j = jit::Jit::create(impl_->jit_error);
  impl_->jit = std::move(j);
}

ShadingSystem::~ShadingSystem() = default;

CompileOptions& ShadingSystem::options() { return impl_->options; }

std::unique_ptr<ShaderGroup> ShadingSystem::parse_group(const std::string& text,
                                                        const std::string& where,
                                                        DiagnosticList& diags) const {
  return group::parse_group_text(text, where, diags);
}

bool ShadingSystem::add_shader_ir(const std::string& name, const std::string& ir_text,
                                  DiagnosticList& diags) {
  auto sh = group::parse_ir_text(ir_text, name, diags);
  if (!sh) return false;
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->registered[name] = std::move(*sh);
  return true;
}

bool ShadingSystem::add_shader_source(const std::string& name, const std::string& source,
                                      const std::string& where, DiagnosticList& diags) {
  CompileStats st;
  auto sh = group::compile_osl_source(where, source, impl_->options, diags, st);
  if (!sh) return false;
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->registered[name] = std::move(*sh);
  return true;
}

std::optional<ir::Shader> ShadingSystem::Impl::load(const std::string& name, DiagnosticList& diags,
                                                    CompileStats& st) {
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = registered.find(name);
    if (it != registered.end()) return it->second;
  }
  std::string path = group::find_shader_file(name, options);
  if (path.empty()) {
    diags.push_back(
        group::to_public(diag::file_report(diag::DiagId::err_shader_not_found, "", {name})));
    return std::nullopt;
  }
  return group::compile_shader_file(path, options, diags, st);
}

// The printed IR of every layer, the layer names and values, the connections and the options.
std::string ShadingSystem::Impl::cache_key(const ShaderGroup& g,
                                           const std::vector<const ir::Shader*>& layers) const {
  std::string key = "O"; // appended piecewise: "O" + to_string(...) trips GCC 12's -Wrestrict
  key += std::to_string(options.opt_level);
  key += options.specialize ? "s" : "n";
  key += options.lockgeom_default ? "" : "u";
  key += options.userdata_isconnected ? "c" : "";
  key += options.range_checking ? "" : "r";
  key += options.lazy_layers ? "" : "e";
  key += options.lazy_globals ? "" : "g";
  key += options.lazy_unconnected ? "" : "k";
  key += options.lazy_error ? "" : "q";
  key += options.merge_instances ? "" : "m";
  key += options.debug_nan ? "N" : "";
  key += options.debug_uninit ? "U" : "";
  key += options.fast_math ? "" : "x";
  key += "L"; // the loop limit is baked into the code
  key += std::to_string(options.max_loop_iterations);
  key += "\n";
  key += "colorspace "; // every colour function depends on it
  key += colors()->name();
  key += "\n";

  key += "group "; // getattribute("shader:groupname") reads it
  key += g.name;
  key += "\n";
  for (size_t i = 0; i < layers.size(); ++i) {
    key += "layer " + g.layers[i].name + "\n" + ir::print(*layers[i]);
    for (const InstanceValue& v : g.layers[i].values) {
      key += "value " + v.type + " " + v.name + " " + v.value + " ";
      key += std::to_string(v.lockgeom);
      key += v.osl_rules ? " osl" : " fit";
      key += v.interpolated ? " interp" : "";
      key += v.interactive ? " inter" : "";
      for (const std::string& w : v.words) key += " [" + w + "]";
      key += "\n";
    }
  }
  for (const std::string& o : g.renderer_outputs) key += "output " + o + "\n";
  for (const std::string& e : g.entry_layers) key += "entry " + e + "\n";
  for (const Connection& c : g.connections)
    key +=
        "connect " + c.src_layer + "." + c.src_param + " " + c.dst_layer + "." + c.dst_param + "\n";
  return key;
}

// Machine code for an emitted group: from the disk cache (disk_cache.h) when an earlier run
// compiled the same module, else optimised and compiled, then cached. The module names host
// objects instead of holding their addresses (codegen::HostSymbols), so the object is a function
// of the module's bits, the optimisation level, the target and LLVM (Jit::target_identity) and,
// at -O2, the shadeop bitcode it links: the key holds all of them, the module's bitcode whole.
bool ShadingSystem::Impl::compile_to_code(llvm::Module& mod, const std::string& entry,
                                          const codegen::HostSymbols& host,
                                          jit::CompiledGroup& code, jit::JitTimes& times,
                                          std::string& err) {
  std::string key;
  if (!jit::cache_folder().empty()) {
    key = "material 1; O" + std::to_string(options.opt_level) + "; " + jit->target_identity() +
          (options.opt_level >= 2 ? "; " + jit::shadeop_bitcode_identity() : "") + "; module ";
    llvm::raw_string_ostream os(key);
    llvm::WriteBitcodeToFile(mod, os);
  }
  std::vector<void*> addresses;
  if (std::string object; !key.empty() && jit::cache_read("material", key, object)) {
    if (jit->add_object(object, {entry}, addresses, code, err, host)) {
      times.from_cache = true;
      return true;
    }
    err.clear(); // an entry that does not load is rebuilt
  }
  std::string object;
  if (!jit->compile_object(mod, options.opt_level, object, times, err)) return false;
  if (!key.empty()) jit::cache_write("material", key, object);
  auto t0 = Clock::now();
  bool ok = jit->add_object(object, {entry}, addresses, code, err, host);
  times.codegen_ms += ms_since(t0);
  return ok;
}

std::shared_ptr<const Material>
ShadingSystem::Impl::build(const ShaderGroup& g, const std::vector<const ir::Shader*>& layers,
                           CompileStats stats, DiagnosticList& diags) {
  auto t0 = Clock::now();
  group::GroupBuild b;
  b.plan.env = env.get();
  b.plan.colors = colors();
  b.plan.fast_math = options.fast_math;
  b.plan.opt_level = options.opt_level;
  b.plan.userdata_isconnected = options.userdata_isconnected;
  b.plan.lazy_layers = options.lazy_layers;
  b.plan.max_loop_iterations = options.max_loop_iterations;
  b.plan.range_checking = options.range_checking;
  b.plan.debug_nan = options.debug_nan;
  b.plan.debug_uninit = options.debug_uninit;
  bool specialize = options.specialize && options.opt_level > 0;
  group::EagerLayers eager;
  eager.global_writers = !options.lazy_globals;
  eager.unconnected = !options.lazy_unconnected;
  eager.error_callers = !options.lazy_error;
  if (!group::build_group(g, layers, specialize, b, diags, options.lockgeom_default,
                          options.opt_level >= 2, options.merge_instances, eager))
    return nullptr;
  stats.specialize_ms = ms_since(t0);

  auto t1 = Clock::now();
  auto ctx = std::make_unique<llvm::LLVMContext>();
  auto mod = std::make_unique<llvm::Module>(g.name.empty() ? "group" : g.name, *ctx);
  jit->configure(*mod);
  codegen::HostSymbols host;
  std::string err = codegen::emit_group(b.plan, *mod, host);
  if (!err.empty()) {
    // Codegen errors name their place already (`file:line:col: error: ...`).
    diags.push_back(group::located_error(err, diag::DiagId::codegen));
    return nullptr;
  }
  stats.llvm_ir_ms = ms_since(t1);

  jit::CompiledGroup code;
  jit::JitTimes times;
  if (!compile_to_code(*mod, b.plan.entry_name, host, code, times, err)) {
    diags.push_back(group::runtime_diag(diag::DiagId::jit, "JIT: " + err));
    return nullptr;
  }
  stats.optimize_ms = times.optimize_ms;
  stats.codegen_ms = times.codegen_ms;
  stats.object_from_disk = times.from_cache;
  stats.noise_batched = times.noise_batched;

  std::map<std::string, group::OutputSlot> slots;
  for (size_t li = 0; li < b.shaders.size(); ++li) {
    const ir::Shader& sh = *b.shaders[li];
    for (size_t s = 0; s < sh.symbols.size(); ++s)
      if (b.plan.layers[li].symbol_offset[s] >= 0)
        slots[b.layer_names[li] + "." + sh.symbols[s].name] = {
            size_t(b.plan.layers[li].symbol_offset[s]), sh.symbols[s].type,
            sh.symbols[s].kind == ir::SymKind::OutputParam};
  }
  // Registry ids of the closures the specialised layers can create (for closure kernels).
  std::vector<int> closure_ids;
  for (const auto& shp : b.shaders)
    for (const ir::Op& op : shp->ops) {
      if (op.opcode != ir::Opcode::Closure || op.args.size() < 2) continue;
      const ir::Symbol& key = shp->symbols[size_t(op.args[1])];
      if (key.kind != ir::SymKind::Const || key.init.empty()) continue;
      int id = registry::id_of(key.init[0].s);
      if (id >= 0 && std::find(closure_ids.begin(), closure_ids.end(), id) == closure_ids.end())
        closure_ids.push_back(id);
    }
  return std::make_shared<group::MaterialImpl>(jit, env, code, std::move(b.groupdata),
                                               std::move(slots), b.globals_read, stats,
                                               std::move(closure_ids));
}

bool ShadingSystem::strings_exhausted() const { return impl_->env->strings.exhausted(); }
uint64_t ShadingSystem::strings_budget_bytes() const { return impl_->env->strings.budget(); }

std::shared_ptr<const Material> ShadingSystem::compile(const ShaderGroup& group,
                                                       DiagnosticList& diags) {
  Impl& m = *impl_;
  if (!m.jit) {
    diags.push_back(group::runtime_diag(diag::DiagId::jit, "JIT unavailable: " + m.jit_error));
    return nullptr;
  }
  if (group.layers.empty()) {
    diags.push_back(group::runtime_diag(diag::DiagId::group_empty));
    return nullptr;
  }
  CompileStats stats;
  std::vector<ir::Shader> loaded;
  loaded.reserve(group.layers.size());
  std::map<std::string, size_t> by_name; // a shader used by several layers loads once
  std::vector<size_t> which;
  for (const auto& layer : group.layers) {
    auto it = by_name.find(layer.shader);
    if (it == by_name.end()) {
      auto sh = m.load(layer.shader, diags, stats);
      if (!sh) return nullptr;
      it = by_name.emplace(layer.shader, loaded.size()).first;
      loaded.push_back(std::move(*sh));
    }
    which.push_back(it->second);
  }
  std::vector<const ir::Shader*> layers;
  for (size_t w : which) layers.push_back(&loaded[w]);

  std::string key = m.cache_key(group, layers);
  {
    std::lock_guard<std::mutex> lock(m.mutex);
    auto it = m.cache.find(key);
    if (it != m.cache.end()) {
      stats.cache_hit = true;
      return std::make_shared<group::CachedMaterial>(it->second, stats);
    }
  }
  auto mat = m.build(group, layers, stats, diags);
  if (mat) {
    std::lock_guard<std::mutex> lock(m.mutex);
    m.cache.emplace(key, mat);
  }
  return mat;
}

} // namespace lobe

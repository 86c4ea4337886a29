// Material backend selection (see material_backend.h).
#include "material_backend.h"

#include "native_materials.h"

#ifdef LOBE_HAVE_JIT
#include "lobe/shadingsys.h"
#endif

namespace lobe::render {

#ifdef LOBE_HAVE_JIT
struct MaterialBackend::Jit {
  // ShadingSystem::compile is thread-safe (it serialises only the LLJIT step itself), so
  // materials compile in parallel; only this backend's own bookkeeping is locked (mu_).
  ShadingSystem ss;
};
bool MaterialBackend::jit_available() { return true; }
#else
struct MaterialBackend::Jit {};
bool MaterialBackend::jit_available() { return false; }
#endif

MaterialBackend::MaterialBackend(const std::string& mode, std::vector<std::string> search_dirs)
    : mode_(mode) {
#ifdef LOBE_HAVE_JIT
  if (mode_ != "native") {
    jit_ = std::make_unique<Jit>();
    auto& inc = jit_->ss.options().include_dirs;
    inc.insert(inc.end(), search_dirs.begin(), search_dirs.end());
    inc.push_back(LOBE_STDLIB_SHADER_DIR);
  }
#else
  (void)search_dirs;
#endif
}

MaterialBackend::~MaterialBackend() = default;

MaterialCompiler MaterialBackend::compiler() {
  return [this](const scene::MaterialDesc& m, std::string& error) { return compile(m, error); };
}

std::shared_ptr<const Material> MaterialBackend::compile(const scene::MaterialDesc& m,
                                                         std::string& error) {
#ifdef LOBE_HAVE_JIT
  if (jit_) {
    DiagnosticList diags;
    std::shared_ptr<const Material> mat = jit_->ss.compile(m.group, diags);
    if (mat) {
      std::lock_guard<std::mutex> lock(mu_);
      used_jit_ = true;
      return mat;
    }
    std::string text;
    for (const Diagnostic& d : diags) text += (text.empty() ? "" : "\n") + d.text;
    bool fallback = mode_ == "auto" && m.group.layers.size() == 1 &&
                    has_native_material(m.group.layers[0].shader);
    if (!fallback) {
      error = "compile failed:\n" + text;
      return nullptr;
    }
    std::lock_guard<std::mutex> lock(mu_);
    warnings_.push_back(m.where + ": JIT failed, using the native '" + m.group.layers[0].shader +
                        "':\n" + text);
  }
#endif
  if (mode_ == "jit") {
    error = "this build has no JIT";
    return nullptr;
  }
  auto mat = make_native_material(m.group, error);
  std::lock_guard<std::mutex> lock(mu_);
  used_native_ |= mat != nullptr;
  return mat;
}

std::string MaterialBackend::name() const {
  std::lock_guard<std::mutex> lock(mu_);
  if (used_jit_ && used_native_) return "jit+native";
  return used_jit_ ? "jit" : "native";
}

std::vector<std::string> MaterialBackend::warnings() const {
  std::lock_guard<std::mutex> lock(mu_);
  return warnings_;
}

} // namespace lobe::render

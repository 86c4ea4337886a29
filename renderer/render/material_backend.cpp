// Material backend selection (see material_backend.h).
#include "material_backend.h"

#include "lobe/memory.h"

#ifdef LOBE_HAVE_JIT
#include "lobe/install.h"
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

MaterialBackend::MaterialBackend(const std::string& mode, std::vector<std::string> search_dirs,
                                 MaterialCompiler native)
    : mode_(mode), native_(std::move(native)) {
#ifdef LOBE_HAVE_JIT
  if (mode_ != "native") {
    jit_ = std::make_unique<Jit>();
    auto& inc = jit_->ss.options().include_dirs;
    inc.insert(inc.end(), search_dirs.begin(), search_dirs.end());
    if (std::string stdlib = stdlib_shader_dir(); !stdlib.empty()) inc.push_back(stdlib);
  }
#else
  (void)search_dirs;
#endif
}

MaterialBackend::~MaterialBackend() = default;

void MaterialBackend::set_max_loop_iterations(int64_t n) {
#ifdef LOBE_HAVE_JIT
  if (jit_) jit_->ss.options().max_loop_iterations = n;
#else
  (void)n;
#endif
}

std::string MaterialBackend::set_colorspace(const std::string& name) {
#ifdef LOBE_HAVE_JIT
  if (jit_) jit_->ss.options().colorspace = name;
  return colorspace_error(name);
#else
  (void)name;
  return "";
#endif
}

MaterialCompiler MaterialBackend::compiler() {
  return [this](const scene::MaterialDesc& m, std::string& error) { return compile(m, error); };
}

namespace {

// The errors among `diags`, one per line ("error: " dropped from one-line messages: the
// renderer prefixes its own location).
std::string error_text(const DiagnosticList& diags) {
  std::string text;
  for (const Diagnostic& d : diags) {
    if (d.severity == Diagnostic::Severity::Warning) continue;
    std::string t = d.text;
    if (t.rfind("error: ", 0) == 0 && t.find('\n') == std::string::npos) t = t.substr(7);
    text += (text.empty() ? "" : "\n") + t;
  }
  return text.empty() ? "compile failed" : text;
}

} // namespace

// A JIT error is the user's error and is reported as such: the native twins stand in only
// when the JIT is unavailable (a build without it), never for a material the JIT rejected.
std::shared_ptr<const Material> MaterialBackend::compile(const scene::MaterialDesc& m,
                                                         std::string& error) {
#ifdef LOBE_HAVE_JIT
  if (jit_) {
    DiagnosticList diags;
    std::shared_ptr<const Material> mat = jit_->ss.compile(m.group, diags);
    if (!mat) {
      error = error_text(diags);
      return nullptr;
    }
    // The JIT ignores an instance value for a parameter the shader lacks (with a warning, as
    // OSL does); in a JSON scene that is a mistake (a misspelt parameter), so it is an error;
    // a testrender XML scene warns and renders, as testrender does.
    std::vector<std::string> ignored;
    for (const Diagnostic& d : diags)
      if (d.severity == Diagnostic::Severity::Note && d.id == "nonexistent_param") {
        std::string text = d.text.substr(d.text.rfind("note: ", 0) == 0 ? 6 : 0);
        if (!m.unknown_params_warn) {
          error = text;
          return nullptr;
        }
        ignored.push_back(m.where + ": material '" + m.name + "': " + text + " (ignored)");
      } else if (d.id == "builtin_option" || d.id == "closure_keyword") {
        // A keyword argument a texture lookup, noise or closure does not take: dropped, said.
        std::string text = d.text.substr(d.text.rfind("warning: ", 0) == 0 ? 9 : 0);
        ignored.push_back(m.where + ": material '" + m.name + "': " + text + " (ignored)");
      }
    std::lock_guard<std::mutex> lock(mu_);
    warnings_.insert(warnings_.end(), ignored.begin(), ignored.end());
    used_jit_ = true;
    return mat;
  }
#endif
  if (mode_ == "jit") {
    error = "this build has no JIT";
    return nullptr;
  }
  if (!native_) {
    error = "this build has no native materials";
    return nullptr;
  }
  auto mat = native_(m, error);
  std::lock_guard<std::mutex> lock(mu_);
  used_native_ |= mat != nullptr;
  return mat;
}

std::string MaterialBackend::name() const {
  std::lock_guard<std::mutex> lock(mu_);
  if (used_jit_ && used_native_) return "jit+native";
  return used_jit_ ? "jit" : "native";
}

std::string MaterialBackend::strings_error() const {
#ifdef LOBE_HAVE_JIT
  if (jit_ && jit_->ss.strings_exhausted())
    return "the shaders' strings passed the " +
           format_bytes(double(jit_->ss.strings_budget_bytes())) +
           " of memory kept for them (a quarter of what was available): a string that did not "
           "fit was made empty";
#endif
  return "";
}

std::vector<std::string> MaterialBackend::warnings() const {
  std::lock_guard<std::mutex> lock(mu_);
  return warnings_;
}

} // namespace lobe::render

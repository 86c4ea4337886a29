// Which implementation compiles scene materials: the JIT (ShadingSystem, OSL source from the
// stdlib_shaders/ folder and the scene's folder) or the native C++ stdlib twins, which the
// caller passes in (`native`: renderer/native's native_compiler(); empty: none).
//
// "auto" uses the JIT when this build has it (LOBE_HAVE_JIT), else the native versions of the
// stdlib shaders; a material the JIT rejects is an error in every mode (never replaced by its
// native twin). "jit" fails without the JIT; "native" never uses it.
#pragma once

#include "scene_setup.h"

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace lobe::render {

class MaterialBackend {
public:
  explicit MaterialBackend(const std::string& mode, std::vector<std::string> search_dirs = {},
                           MaterialCompiler native = {});
  ~MaterialBackend();
  MaterialCompiler compiler();
  std::string name() const; // "jit", "native" or "jit+native"
  std::vector<std::string> warnings() const;
  // "" unless the strings JIT materials made passed their memory (ShadingSystem::
  // strings_exhausted): then why, naming the budget (a string past it was made empty).
  std::string strings_error() const;
  static bool jit_available();
  // The RGB space of JIT materials' colours (CompileOptions::colorspace: transformc, luminance,
  // blackbody...); set before the first compile. Native materials are Rec709. Returns OSL's
  // message for an unknown name (`Unknown color space "X"`; Rec709 is used), else "".
  std::string set_colorspace(const std::string& name);
  // CompileOptions::max_loop_iterations of JIT materials (0: unlimited); before the first compile.
  void set_max_loop_iterations(int64_t n);

private:
  std::shared_ptr<const Material> compile(const scene::MaterialDesc& m, std::string& error);
  struct Jit;
  std::unique_ptr<Jit> jit_;
  std::string mode_;
  MaterialCompiler native_;
  mutable std::mutex mu_;
  std::vector<std::string> warnings_;
  bool used_native_ = false, used_jit_ = false;
};

} // namespace lobe::render

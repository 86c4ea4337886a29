// Which implementation compiles scene materials: the JIT (ShadingSystem, OSL source from the
// stdlib_shaders/ folder and the scene's folder) or the native C++ stdlib twins.
//
// "auto" uses the JIT when this build has it (LOBE_HAVE_JIT) and falls back to the native
// version of a stdlib shader only if the JIT fails on it (recorded in warnings()); "jit" never
// falls back; "native" never uses the JIT.
#pragma once

#include "scene_setup.h"

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace lobe::render {

class MaterialBackend {
public:
  explicit MaterialBackend(const std::string& mode, std::vector<std::string> search_dirs = {});
  ~MaterialBackend();
  MaterialCompiler compiler();
  std::string name() const; // "jit", "native" or "jit+native"
  std::vector<std::string> warnings() const;
  static bool jit_available();

private:
  std::shared_ptr<const Material> compile(const scene::MaterialDesc& m, std::string& error);
  struct Jit;
  std::unique_ptr<Jit> jit_;
  std::string mode_;
  mutable std::mutex mu_;
  std::vector<std::string> warnings_;
  bool used_native_ = false, used_jit_ = false;
};

} // namespace lobe::render

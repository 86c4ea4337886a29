// Run-time places of Lobe's files (see install_paths.h) and the public lobe/install.h.
#include "install_paths.h"

#include "lobe/install.h"

#include <dlfcn.h>

#include <cstdlib>

namespace lobe {
namespace fs = std::filesystem;
namespace install {

namespace {

bool exists(const fs::path& p) {
  std::error_code ec;
  return fs::exists(p, ec);
}

// The folders an installed library or executable keeps its private files in (<libdir>/lobe):
// the binary is liblobe.so in <libdir>, or an executable in <bindir>.
std::vector<fs::path> private_folders() {
  std::vector<fs::path> dirs;
  fs::path here = own_folder();
  if (here.empty()) return dirs;
  dirs.push_back(here / "lobe");
  dirs.push_back((here / LOBE_REL_BIN_TO_LIB / "lobe").lexically_normal());
  return dirs;
}

} // namespace

// Found once: dladdr takes the loader's lock, which a dlopen on another thread (the image
// library, loaded in the background while a scene loads: half a second) holds throughout.
fs::path own_folder() {
  static const fs::path folder = [] {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&own_folder), &info) && info.dli_fname) {
      std::error_code ec;
      fs::path p = fs::canonical(info.dli_fname, ec);
      if (!ec) return p.parent_path();
    }
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : exe.parent_path();
  }();
  return folder;
}

std::vector<std::string> oiio_module_candidates() {
  const char* name = "liblobe_oiio.so";
  std::vector<std::string> tried;
  if (const char* env = std::getenv("LOBE_OIIO_MODULE"); env && *env) tried.push_back(env);
  if (fs::path here = own_folder(); !here.empty()) tried.push_back((here / name).string());
  for (const fs::path& d : private_folders()) tried.push_back((d / name).string());
#ifndef LOBE_INSTALL_RELATIVE_ONLY
  tried.push_back(LOBE_BUILD_OIIO_MODULE);
#endif
  return tried;
}

namespace {

// A private file: $<env> when set, else the first of <libdir>/lobe/<file> and `build_path` (the
// build tree's, outside the installed library) that exists, else the first place looked (for
// the error message).
std::string private_file(const char* env, const char* file, const char* build_path) {
  if (const char* e = std::getenv(env); e && *e) return e;
  std::vector<std::string> tried;
  for (const fs::path& d : private_folders()) tried.push_back((d / file).string());
#ifndef LOBE_INSTALL_RELATIVE_ONLY
  tried.push_back(build_path);
#else
  (void)build_path;
#endif
  for (const std::string& p : tried)
    if (exists(p)) return p;
  return tried.empty() ? file : tried.front();
}

#ifdef LOBE_INSTALL_RELATIVE_ONLY
constexpr const char* kBuildClosuresBc = "";
constexpr const char* kBuildShadeopsBc = "";
#else
constexpr const char* kBuildClosuresBc = LOBE_BUILD_CLOSURES_BC;
constexpr const char* kBuildShadeopsBc = LOBE_BUILD_SHADEOPS_BC;
#endif

} // namespace

std::string closures_bitcode() {
  return private_file("LOBE_CLOSURES_BC", "lobe_closures.bc", kBuildClosuresBc);
}

std::string shadeops_bitcode() {
  return private_file("LOBE_SHADEOPS_BC", "lobe_shadeops.bc", kBuildShadeopsBc);
}

} // namespace install

const char* version() { return LOBE_VERSION_TEXT; }

std::string stdlib_shader_dir() {
  std::vector<fs::path> tried;
  if (fs::path here = install::own_folder(); !here.empty()) {
    tried.push_back(here / LOBE_REL_LIB_TO_SHADERS);
    tried.push_back(here / LOBE_REL_BIN_TO_SHADERS);
  }
#ifndef LOBE_INSTALL_RELATIVE_ONLY
  tried.push_back(LOBE_BUILD_STDLIB_SHADERS);
#endif
  for (const fs::path& p : tried)
    if (exists(p / "matte.osl")) return p.lexically_normal().string();
  return "";
}

} // namespace lobe

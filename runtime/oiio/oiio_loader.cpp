// Finds and loads liblobe_oiio.so once (oiio_module.h describes the search).
#include "oiio_module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>

namespace lobe::oiio {

namespace {

struct Loaded {
  const Api* api = nullptr;
  std::string why;
};

// The folder of the binary or shared library this code was linked into.
std::filesystem::path own_folder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&own_folder), &info) && info.dli_fname) {
    std::error_code ec;
    std::filesystem::path p = std::filesystem::canonical(info.dli_fname, ec);
    if (!ec) return p.parent_path();
  }
  std::error_code ec;
  std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path();
}

Loaded load() {
  Loaded r;
  std::vector<std::string> tried;
  if (const char* env = std::getenv("LOBE_OIIO_MODULE"); env && *env) tried.push_back(env);
  std::filesystem::path here = own_folder();
  if (!here.empty()) {
    tried.push_back((here / LOBE_OIIO_MODULE_NAME).string());
    tried.push_back((here / ".." / "lib" / "lobe" / LOBE_OIIO_MODULE_NAME).string());
  }
  tried.push_back(LOBE_OIIO_MODULE_INSTALLED);
  tried.push_back(LOBE_OIIO_MODULE_BUILT);
  std::string errors;
  for (const std::string& path : tried) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) continue;
    void* h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!h) {
      errors += std::string("; ") + dlerror();
      continue;
    }
    using Entry = const Api* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(h, "lobe_oiio_module_api"));
    const Api* api = entry ? entry() : nullptr;
    if (!api || api->abi != kAbi) {
      errors += "; " + path + ": not a Lobe OpenImageIO module of this version";
      dlclose(h);
      continue;
    }
    r.api = api; // never unloaded: texture systems live until exit
    return r;
  }
  r.why = "cannot load Lobe's OpenImageIO module " LOBE_OIIO_MODULE_NAME " (looked for ";
  for (size_t i = 0; i < tried.size(); ++i) r.why += (i ? ", " : "") + tried[i];
  r.why += ")" + errors;
  return r;
}

} // namespace

const Api* module(std::string* why) {
  static const Loaded loaded = load();
  if (!loaded.api && why) *why = loaded.why;
  return loaded.api;
}

} // namespace lobe::oiio

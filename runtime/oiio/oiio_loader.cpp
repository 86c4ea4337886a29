// Finds and loads liblobe_oiio.so once (oiio_module.h describes the search).
#include "oiio_module.h"

#include "install_paths.h"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>

namespace lobe::oiio {

namespace {

struct Loaded {
  const Api* api = nullptr;
  std::string why;
};

Loaded load() {
  Loaded r;
  std::vector<std::string> tried = install::oiio_module_candidates();
  std::string errors;
  for (const std::string& path : tried) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) continue;
    void* h = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
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
  r.why = "cannot load Lobe's OpenImageIO module liblobe_oiio.so (looked for ";
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

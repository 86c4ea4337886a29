// StringTable: interning behind a mutex (shader code interns only when it builds new strings).
#include "env.h"

namespace lobe::shadeops {

const char* StringTable::intern(std::string_view s) {
  std::lock_guard<std::mutex> lock(mutex_);
  return strings_.emplace(s).first->c_str();
}

const DeclaredClosureInfo* DeclaredClosureTable::get(const char* name,
                                                     const std::vector<DeclaredClosureArg>& args,
                                                     uint32_t block_size) {
  std::string key = name;
  for (const DeclaredClosureArg& a : args)
    key += "|" + std::string(a.keyword ? a.keyword : "") + ":" + std::to_string(int(a.base)) + "[" +
           std::to_string(a.arraylen) + "]@" + std::to_string(a.offset);
  std::lock_guard<std::mutex> lock(mutex_);
  auto [it, fresh] = entries_.try_emplace(key);
  Entry& e = it->second;
  if (fresh) {
    e.args = args;
    e.info = {name, e.args.data(), uint32_t(e.args.size()), block_size};
  }
  return &e.info;
}

} // namespace lobe::shadeops

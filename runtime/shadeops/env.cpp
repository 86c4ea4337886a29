// StringTable: interning behind a mutex (shader code interns only when it builds new strings).
#include "env.h"

namespace lobe::shadeops {

const char* StringTable::intern(std::string_view s) {
  std::lock_guard<std::mutex> lock(mutex_);
  return strings_.emplace(s).first->c_str();
}

} // namespace lobe::shadeops

// Instance values: text in OSL's `param` syntax turned into constants of a parameter's type.
#include "group_build.h"

#include <cstdlib>
#include <sstream>

namespace lobe::group {

bool parse_value(const std::string& text, const ir::Type& t, std::vector<ir::ConstValue>& out,
                 int& arraylen) {
  out.clear();
  int comps = t.components();
  if (t.base == ir::BaseType::String) { // one string (arrays of strings: space-separated words)
    if (!t.is_array()) {
      out.push_back({0, 0, text});
      arraylen = 0;
      return true;
    }
    std::istringstream in(text);
    for (std::string w; in >> w;) out.push_back({0, 0, w});
  } else if (t.base == ir::BaseType::Closure) {
    return false;
  } else {
    std::istringstream in(text);
    for (std::string w; in >> w;) {
      char* end = nullptr;
      ir::ConstValue v;
      if (t.base == ir::BaseType::Int) {
        v.i = int32_t(std::strtol(w.c_str(), &end, 10));
        if (*end == '.' || *end == 'e') v.i = int32_t(std::strtof(w.c_str(), &end));
      } else {
        v.f = std::strtof(w.c_str(), &end);
      }
      if (end == w.c_str() || *end) return false;
      out.push_back(v);
    }
  }
  if (out.empty()) return false;
  int elems = t.arraylen > 0 ? t.arraylen : 1;
  if (t.arraylen < 0) { // unsized: the value decides the length
    if (out.size() % size_t(comps)) return false;
    arraylen = int(out.size()) / comps;
    return true;
  }
  arraylen = t.arraylen;
  size_t want = size_t(elems * comps);
  if (out.size() == 1 && want > 1) out.assign(want, out[0]);
  return out.size() == want;
}

} // namespace lobe::group

// The generated closures reference (closure_docs.h).
#include "closure_docs.h"

#include "closure_registry.h"
#include "closure_table.h"

#include <string_view>

namespace lobe::registry {
namespace {

const char* type_name(ArgType t) {
  switch (t) {
  case ArgType::Int:
    return "int";
  case ArgType::Float:
    return "float";
  case ArgType::Color:
    return "color";
  case ArgType::Vector:
    return "vector";
  case ArgType::String:
    return "string";
  case ArgType::Closure:
    return "closure color";
  }
  return "?";
}

std::string signature(const ClosureEntry& e) {
  std::string s = std::string(e.name) + "(";
  bool first = true;
  for (const ClosureParam& p : e.params) {
    if (p.keyword) continue;
    if (!first) s += ", ";
    s += type_name(p.type);
    s += " ";
    s += p.name;
    first = false;
  }
  return s + ")";
}

std::string keywords(const ClosureEntry& e) {
  std::string s;
  for (const ClosureParam& p : e.params) {
    if (!p.keyword || std::string_view(p.name) == "label") continue;
    if (!s.empty()) s += ", ";
    s += '"';
    s += p.name;
    s += "\" (";
    s += type_name(p.type);
    s += ", ";
    s += p.default_value ? p.default_value : "";
    s += ")";
  }
  return s.empty() ? "-" : s;
}

} // namespace

std::string closure_reference_markdown() {
  std::string out = "| key | signature | keywords (type, default) | what |\n"
                    "|---|---|---|---|\n";
  for (const ClosureEntry& e : table::kClosures) // the built-in entries only
    out += "| `" + std::string(e.key) + "` | `" + signature(e) + "` | " + keywords(e) + " | " +
           e.doc + " |\n";
  return out;
}

bool replace_generated_section(std::string& doc) {
  size_t b = doc.find(kDocsBegin);
  if (b == std::string::npos) return false;
  size_t body = doc.find('\n', b);
  size_t e = doc.find(kDocsEnd, b);
  if (body == std::string::npos || e == std::string::npos || e < body) return false;
  doc.replace(body + 1, e - (body + 1), closure_reference_markdown());
  return true;
}

} // namespace lobe::registry

// The generated closures reference (closure_docs.h).
#include "closure_docs.h"
#include "generated_docs.h"

#include "library_calls.h"
#include "math_functions.h"

#include "closure_registry.h"
#include "closure_table.h"

#include <string>
#include <string_view>
#include <type_traits>

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

namespace {

template <class F> struct LibrarySignature;
template <class... P> struct LibrarySignature<void(P...)> {
  static std::string params() {
    std::string s;
    ((std::is_same_v<P, ir::library::Env>
          ? void()
          : void(s.append(s.empty() ? "" : ", ").append(ir::library::type_name<P>()))),
     ...);
    return s;
  }
};

} // namespace

std::string library_reference_markdown() {
  using namespace ir::library;
  std::string out = "| function | what it returns |\n"
                    "|---|---|\n";
#define LOBE_LIBRARY_DOC_ROW(x, e, name, R, P, fn, doc)                                            \
  out.append("| `").append(ir::library::type_name<R>()).append(" ").append(name).append("(");      \
  out.append(LibrarySignature<void P>::params()).append(")` | ").append(doc).append(" |\n");
  LOBE_LIBRARY_CALLS(LOBE_LIBRARY_DOC_ROW, _)
#undef LOBE_LIBRARY_DOC_ROW
  return out;
}

std::string math_reference_markdown() {
  std::string out = "| function | signatures | what |\n"
                    "|---|---|---|\n";
  const char* kGeneric = "float, color, point, vector, normal";
#define LOBE_MATH_DOC_ROW(x, e, name, arity, max, forms, doc)                                      \
  out.append("| `").append(#name).append("` | `").append(arity == 1 ? "T(T)" : "T(T, T)");         \
  out.append("`, T: ").append(std::string_view(#forms) == "Generic" ? kGeneric : "float");         \
  out.append(" | ").append(doc).append(" |\n");
  LOBE_MATH_FUNCTIONS(LOBE_MATH_DOC_ROW, _)
#undef LOBE_MATH_DOC_ROW
  return out;
}

bool replace_generated_section(std::string& doc) {
  int c = replace_between(doc, kDocsBegin, kDocsEnd, closure_reference_markdown());
  int l = replace_between(doc, kLibraryDocsBegin, kLibraryDocsEnd, library_reference_markdown());
  int m = replace_between(doc, kMathDocsBegin, kMathDocsEnd, math_reference_markdown());
  return c >= 0 && l >= 0 && m >= 0 && (c > 0 || l > 0 || m > 0);
}

} // namespace lobe::registry

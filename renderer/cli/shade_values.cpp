// testshade's value reading (see shade_values.h).
#include "shade_values.h"

#include "instance_values.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>

namespace lobe::cli {
namespace {

// The whole text, blanks around it aside, is one number of the kind `read` accepts (testshade
// 1.13.12 reads "2.5 " as the float 2.5).
template <class F> bool whole(const std::string& t, F read) {
  if (t.empty()) return false;
  const char* s = t.c_str();
  char* end = nullptr;
  read(s, &end);
  if (end == s) return false;
  while (std::isspace(static_cast<unsigned char>(*end))) ++end;
  return *end == '\0';
}

} // namespace

std::string guess_type(const std::string& text) {
  float m[16];
  const char* s = text.c_str();
  if (std::sscanf(s, "%g, %g, %g, %g, %g, %g, %g, %g, %g, %g, %g, %g, %g, %g, %g, %g", &m[0], &m[1],
                  &m[2], &m[3], &m[4], &m[5], &m[6], &m[7], &m[8], &m[9], &m[10], &m[11], &m[12],
                  &m[13], &m[14], &m[15]) == 16)
    return "matrix";
  if (std::sscanf(s, "%g, %g, %g", &m[0], &m[1], &m[2]) == 3) return "vector";
  if (whole(text, [](const char* p, char** e) { return std::strtol(p, e, 10); })) return "int";
  if (whole(text, [](const char* p, char** e) { return std::strtod(p, e); })) return "float";
  return "string";
}

DataType value_type(const std::string& type_name, const std::string& text) {
  if (auto t = DataType::parse(type_name)) return *t;
  return *DataType::parse(guess_type(text));
}

std::vector<std::string> value_words(const std::string& text, const DataType& type) {
  if (type.base == DataType::Base::String) {
    if (type.arraylen == 0) return {text};
    std::vector<std::string> out(1);
    for (char c : text) {
      if (c == ',')
        out.emplace_back();
      else
        out.back() += c;
    }
    return out;
  }
  std::vector<std::string> out;
  std::string w;
  for (char c : text) {
    if (c == ' ' || c == '\t' || c == ',') {
      if (!w.empty()) out.push_back(w);
      w.clear();
    } else {
      w += c;
    }
  }
  if (!w.empty()) out.push_back(w);
  return out;
}

InstanceValue param_value(const std::string& type_name, const std::string& name,
                          const std::string& text) {
  // "T[]": an array as long as the value (Lobe's; testshade 1.13.12 aborts on it).
  bool unsized = type_name.size() > 2 && type_name.compare(type_name.size() - 2, 2, "[]") == 0;
  if (unsized) {
    if (auto elem = DataType::parse(type_name.substr(0, type_name.size() - 2))) {
      InstanceValue v{type_name, name, text};
      v.words = value_words(text, *elem);
      v.osl_rules = true;
      return v;
    }
  }
  DataType t = value_type(type_name, text);
  InstanceValue v{t.str(), name, text};
  v.words = value_words(text, t);
  v.osl_rules = true;
  return v;
}

TypedValue read_typed_value(const std::string& type_name, const std::string& text) {
  TypedValue r;
  r.type = value_type(type_name, text);
  r.words = value_words(text, r.type);
  size_t n = size_t(r.type.elements() * r.type.components());
  if (r.type.base == DataType::Base::String) r.words.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const char* w = k < r.words.size() ? r.words[k].c_str() : "";
    if (r.type.base == DataType::Base::Int) // out of range: the nearest int, as testshade
      r.ints.push_back(group::read_int(w, nullptr));
    else if (r.type.is_float_based())
      r.floats.push_back(std::strtof(w, nullptr));
  }
  return r;
}

} // namespace lobe::cli

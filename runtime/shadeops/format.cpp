// OSL printf formatting (see format.h).
#include "format.h"

#include <cstdio>
#include <cstdlib>

namespace lobe::shadeops {
namespace {

struct ArgDesc {
  char code = 'f';
  int count = 1; // array length (1 for a scalar)
};

// Splits "f{3}ts" into argument descriptions.
ArgDesc next_arg(std::string_view codes, size_t& pos) {
  ArgDesc d;
  if (pos >= codes.size()) return {0, 0};
  d.code = codes[pos++];
  if (pos < codes.size() && codes[pos] == '{') {
    d.count = std::atoi(std::string(codes.substr(pos + 1)).c_str());
    pos = codes.find('}', pos) + 1;
  }
  return d;
}

int components(char code) { return code == 't' ? 3 : (code == 'm' ? 16 : 1); }

std::string printf1(const std::string& spec, double v) {
  char buf[512];
  std::snprintf(buf, sizeof buf, spec.c_str(), v);
  return buf;
}
std::string printf1(const std::string& spec, long long v) {
  char buf[512];
  std::snprintf(buf, sizeof buf, spec.c_str(), v);
  return buf;
}
std::string printf1(const std::string& spec, const char* v) {
  char buf[4096];
  std::snprintf(buf, sizeof buf, spec.c_str(), v);
  return buf;
}

std::string closure_text(const RuntimeEnv& env, const ClosureNode* c) {
  if (env.closure_printer) return env.closure_printer(c);
  if (!c) return "(null)";
  return "closure#" + std::to_string(c->id);
}

// Formats one scalar component with conversion `conv` and the spec's flags (`head` is the
// spec without its conversion character).
std::string format_scalar(const RuntimeEnv& env, const std::string& head, char conv, char code,
                          const void* p) {
  bool int_conv = conv == 'd' || conv == 'i' || conv == 'x' || conv == 'X' || conv == 'o' ||
                  conv == 'u' || conv == 'c';
  if (code == 's') return printf1(head + "s", *static_cast<const char* const*>(p));
  if (code == 'c') {
    auto* node = *static_cast<const ClosureNode* const*>(p);
    return printf1(head + "s", closure_text(env, node).c_str());
  }
  if (code == 'i') {
    long long v = *static_cast<const int32_t*>(p);
    if (conv == 's') return std::to_string(v);
    if (int_conv) return printf1(head + "ll" + conv, v);
    return printf1(head + conv, double(v));
  }
  double v = *static_cast<const float*>(p);
  if (conv == 's') return printf1("%g", v);
  if (int_conv) return printf1(head + "ll" + conv, (long long)v);
  return printf1(head + conv, v);
}

// Formats a whole argument: every component of every element, space-separated.
std::string format_arg(const RuntimeEnv& env, const std::string& head, char conv, ArgDesc d,
                       const void* p) {
  size_t stride = (d.code == 's' || d.code == 'c') ? sizeof(void*) : 4;
  int n = components(d.code) * d.count;
  std::string out;
  for (int k = 0; k < n; ++k) {
    if (k) out += ' ';
    out += format_scalar(env, head, conv, d.code, static_cast<const char*>(p) + k * stride);
  }
  return out;
}

} // namespace

std::string format_values(const RuntimeEnv& env, std::string_view fmt, std::string_view codes,
                          const void* const* args) {
  std::string out;
  size_t argpos = 0;
  int argi = 0;
  for (size_t i = 0; i < fmt.size(); ++i) {
    if (fmt[i] != '%') {
      out += fmt[i];
      continue;
    }
    if (i + 1 < fmt.size() && fmt[i + 1] == '%') {
      out += '%';
      ++i;
      continue;
    }
    // %[flags][width][.precision][length]conversion
    size_t j = i + 1;
    std::string head = "%";
    while (j < fmt.size() &&
           std::string_view("-+ #0123456789.*").find(fmt[j]) != std::string_view::npos)
      head += fmt[j++];
    while (j < fmt.size() && std::string_view("hlLqjzt").find(fmt[j]) != std::string_view::npos)
      ++j; // length modifiers are meaningless for shader types
    if (j >= fmt.size()) {
      out += fmt.substr(i);
      break;
    }
    char conv = fmt[j];
    ArgDesc d = next_arg(codes, argpos);
    if (d.code == 0) {
      out += fmt.substr(i, j - i + 1); // more conversions than arguments: print them verbatim
    } else {
      out += format_arg(env, head, conv, d, args[argi++]);
    }
    i = j;
  }
  return out;
}

} // namespace lobe::shadeops

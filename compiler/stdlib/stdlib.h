// The built-in headers, embedded into the compiler at build time (compiler/stdlib/*.h, see
// CMakeLists.txt): stdosl.h, which is included before every shader, and the headers OSL ships
// in its shader folder (color2.h, color4.h, vector2.h, vector4.h, matrix33.h, oslutil.h), which
// `#include` finds after the including file's folder and the -I paths, as oslc does.
#pragma once

#include <optional>
#include <span>
#include <string_view>

namespace lobe::stdlib {

struct Header {
  std::string_view name; // as written in `#include "name"`
  std::string_view text;
};

// Every built-in header, stdosl.h first.
std::span<const Header> headers();
// The text of the built-in header called `name` (no folders), or nullopt.
std::optional<std::string_view> find_header(std::string_view name);

// The text of compiler/stdlib/stdosl.h.
std::string_view stdosl_source();
inline constexpr const char* kStdoslName = "stdosl.h";

} // namespace lobe::stdlib

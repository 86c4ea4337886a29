// The standard header (stdosl.h), embedded into the compiler at build time.
#pragma once

#include <string_view>

namespace lobe::stdlib {

// The text of compiler/stdlib/stdosl.h.
std::string_view stdosl_source();
inline constexpr const char* kStdoslName = "stdosl.h";

} // namespace lobe::stdlib

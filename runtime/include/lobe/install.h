// The library's version and where its installed files are.
//
// `cmake --install` puts the stdlib shaders (matte.osl, plastic.osl, ...) with stdosl.h and the
// other built-in headers in <prefix>/share/lobe/shaders; the library finds them relative to
// itself, so a moved prefix still works. A renderer adds the folder to its shader search path:
//   ss.options().include_dirs.push_back(lobe::stdlib_shader_dir());
#pragma once

#include <string>

namespace lobe {

// "MAJOR.MINOR.PATCH" of the library (the project version; docs/plugin.md on compatibility).
const char* version();

// The folder of the stdlib shaders, or "" when they are not installed beside the library.
std::string stdlib_shader_dir();

} // namespace lobe

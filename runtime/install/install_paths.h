// Where Lobe's own files are at run time (internal; the public part is lobe/install.h).
//
// Installed by `cmake --install`, the files sit at fixed places relative to each other:
//   <libdir>/liblobe.so, <libdir>/lobe/liblobe_oiio.so, <libdir>/lobe/lobe_closures.bc,
//   <bindir>/lobe, <datadir>/lobe/shaders/{*.osl, stdosl.h, ...}
// so each is found relative to the binary this code is linked into (own_folder()), whatever
// the prefix, also after the prefix is moved. The build tree's own places come after those,
// except in liblobe.so (compiled with LOBE_INSTALL_RELATIVE_ONLY).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace lobe::install {

// The folder of the shared library or executable this code was linked into ("" if unknown).
std::filesystem::path own_folder();

// Where to look for liblobe_oiio.so, in order: $LOBE_OIIO_MODULE, beside the binary,
// <libdir>/lobe, then the build tree's.
std::vector<std::string> oiio_module_candidates();

// The closure bitcode: $LOBE_CLOSURES_BC when set, else the first of <libdir>/lobe and the build
// tree's that exists (else the first place looked, for the error message).
std::string closures_bitcode();

// The shadeop bitcode (noise, math; inlined into shaders at -O2): $LOBE_SHADEOPS_BC when set
// ("off" disables it), else the first of <libdir>/lobe and the build tree's that exists.
std::string shadeops_bitcode();

} // namespace lobe::install

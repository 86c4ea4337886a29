// Shadeop bitcode: the pure shadeops (noise, math, hash: lobe_shadeops.bc, built from
// runtime/shadeops by clang-19) linked into a shader module so that LLVM inlines them and
// specialises them on the call's constants (noise kind, dimension, channels, null derivative
// pointers), instead of calling the native library out of line.
//
// Only what the module calls is linked: for each declared function the bitcode defines (and
// the allowlist below admits) with the same type, the definition and what it uses are linked
// lazily from the bitcode, made internal (dropped once inlined) and stripped of the library's
// CPU attributes (the one-point noise functions batching gathers stay external and noinline
// until it has run: noise_batch.h). The linked code may call nothing the JIT does not resolve (the
// shadeop table and intrinsics); if it would, nothing is linked and the calls stay out of line. The
// bitcode is compiled from the native library's sources with the same floating-point flags (no
// contraction), so a linked call computes the native call's bits.
#pragma once

#include <string>

namespace llvm {
class Module;
}

namespace lobe::jit {

// The bitcode file: $LOBE_SHADEOPS_BC when set, else the one in the build tree. Set to "off"
// (or to a file that does not exist) to keep every shadeop out of line.
std::string shadeop_bitcode_path();

// What the bitcode is (its size and hash; "none" without one), for disk-cache keys of code
// optimised at -O2, which links it.
std::string shadeop_bitcode_identity();

// Links the shadeops `module` calls from the bitcode into it; returns how many functions were
// linked (0 when the bitcode is missing or nothing applies). Thread-safe.
int link_shadeop_bitcode(llvm::Module& module);

} // namespace lobe::jit

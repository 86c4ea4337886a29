// Closure kernels: the closure library's eval/sample/albedo for one material, JIT-compiled
// from the library's LLVM bitcode (lobe_closures.bc, runtime/closures/bitcode.cpp).
//
// For the registry ids a material's closures can have, one module gets four dispatchers,
//   unsigned lobe_kernels_setup(int id, params, state)     once per shading point: LobeFlags
//   void lobe_kernels_eval  (int id, state, wo, wi, mode, BsdfEval* out)
//   int  lobe_kernels_sample(int id, state, wo, u,  mode, BsdfSample* out)
//   void lobe_kernels_albedo(int id, state, wo, Vec3* out)
// each a switch over just those ids calling lobe_closure_<key>_* (registry::kernel_symbol); only
// those functions (and what they use) are linked from the bitcode, which is loaded lazily,
// everything but the dispatchers is internalised, and LLVM's O2 pipeline inlines the lobes into the
// switch. So a material pays only for its own closures, and the hot path has no call into the
// library. Ids without bitcode (measured_bsdf reads files; emission and other non-BSDF closures)
// are left out, and Bsdf falls back to the native library for them.
#pragma once

#include "jit.h"
#include "lobe/bsdf.h"
#include "lobe/detail/closure_kernels.h"

#include <string>
#include <vector>

namespace lobe::jit {

// The bitcode file: $LOBE_CLOSURES_BC when set, else the installed one beside the library, else
// the build tree's (runtime/install/install_paths.h).
std::string closure_bitcode_path();

// Compiles the kernels for `ids` into `code` (free it with Jit::remove) and fills `out`.
// False with `error` when the bitcode cannot be read, linked or compiled.
bool compile_closure_kernels(Jit& jit, const std::vector<int>& ids, ClosureKernels& out,
                             CompiledGroup& code, JitTimes& times, std::string& error);

} // namespace lobe::jit

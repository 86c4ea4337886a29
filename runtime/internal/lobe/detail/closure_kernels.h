// ClosureKernels, the JIT-compiled closure functions of one material (internal: the public
// headers know it only by name, as Material::closure_kernels() returns it and Bsdf::build takes
// it).
//
// The closure functions of one material, JIT-compiled from the closure library's LLVM bitcode
// with only that material's closures linked in and inlined (Material::closure_kernels(),
// runtime/jit/closure_kernels.h). C ABI, as lobe_closure_setup/_eval/_sample/_albedo in
// docs/closures.md ("Bitcode for the JIT"): setup writes the lobe of a parameter block into a
// state block (Bsdf::kLobeStateBytes) and returns its LobeFlags (0: no lobe); the others read
// that state; sample returns 0 when there is no sample. A Bsdf built with kernels calls them
// for the ids they cover and the native library for the rest; both give the same results, bit
// for bit (tests/closures/jit_kernels_test.cpp).
#pragma once

#include "lobe/bsdf.h"
#include "lobe/vec.h"

#include <cstdint>

namespace lobe {

struct ClosureKernels {
  using SetupFn = uint32_t (*)(int id, const unsigned char* params, void* state);
  using EvalFn = void (*)(int id, const void* state, const Vec3* wo, const Vec3* wi, int mode,
                          BsdfEval* out);
  using SampleFn = int (*)(int id, const void* state, const Vec3* wo, const Vec3* u, int mode,
                           BsdfSample* out);
  using AlbedoFn = void (*)(int id, const void* state, const Vec3* wo, Vec3* out);
  SetupFn setup = nullptr;
  EvalFn eval = nullptr;
  SampleFn sample = nullptr;
  AlbedoFn albedo = nullptr;
  uint64_t ids[2] = {0, 0}; // bit i: registry id i is compiled in

  static constexpr int kMaxIds = 128;
  bool covers(int id) const {
    return id >= 0 && id < kMaxIds && ((ids[id >> 6] >> (id & 63)) & 1u) != 0;
  }
  void add(int id) {
    if (id >= 0 && id < kMaxIds) ids[id >> 6] |= uint64_t{1} << (id & 63);
  }
};

} // namespace lobe

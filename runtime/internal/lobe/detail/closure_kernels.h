// ClosureKernels, the JIT-compiled closure functions of one material (internal: the public
// headers know it only by name, as Material::closure_kernels() returns it and Bsdf::build takes
// it).
//
// The closure functions of one material, JIT-compiled from the closure library's LLVM bitcode
// with only that material's closures linked in and inlined (Material::closure_kernels(),
// runtime/jit/closure_kernels.h). C ABI, as lobe_closure_eval/_sample/_albedo in
// docs/closures.md ("Bitcode for the JIT"); `out` points to the library's LobeEval/LobeSample.
// A Bsdf built with kernels calls them for the ids they cover and the native library for the
// rest; both give the same results to float rounding (tests/closures/jit_kernels_test.cpp).
#pragma once

#include "lobe/vec.h"

#include <cstdint>

namespace lobe {

struct ClosureKernels {
  using EvalFn = void (*)(int id, const unsigned char* params, const Vec3* wo, const Vec3* wi,
                          int mode, void* out);
  using SampleFn = int (*)(int id, const unsigned char* params, const Vec3* wo, const Vec3* u,
                           int mode, void* out);
  using AlbedoFn = void (*)(int id, const unsigned char* params, const Vec3* wo, Vec3* out);
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

// What batched shading would buy the noise-bound shaders (issue 10: simplex was the case where
// Lobe was only level with OSL per point; the JIT's noise batching, runtime/jit/noise_batch.h,
// now takes these lanes for a point's independent calls): OSL's 3-D simplex noise, value only,
// evaluated for one point per call (Lobe's lobe_noise_d, as a shader calls it) against eight points
// per call with SIMD across the points (AVX2), the same operations in the same order per lane, so
// the same bits (checked before timing). Inside one point LLVM already vectorises the four corners
// (runtime/shadeops/noise.cpp); across points every lane does useful work and there is no
// shuffle, gather or horizontal sum.
//
//   build/bench/noise_batch [benchmark flags]      e.g. --benchmark_repetitions=3
#include "shadeop_decls.h"
#include "shadeops.h"

#include <benchmark/benchmark.h>

#include <immintrin.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

namespace {

constexpr int kPoints = 4096;

struct Points {
  std::vector<float> x, y, z; // structure of arrays, as a batch would hold them
  std::vector<float> scalar, batched;
  Points() : x(kPoints), y(kPoints), z(kPoints), scalar(kPoints), batched(kPoints) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-20.0f, 20.0f);
    for (int i = 0; i < kPoints; ++i)
      x[size_t(i)] = u(rng), y[size_t(i)] = u(rng), z[size_t(i)] = u(rng);
  }
};

Points& points() {
  static Points p;
  return p;
}

void scalar_all(Points& p) {
  for (int i = 0; i < kPoints; ++i) {
    float in[3] = {p.x[size_t(i)], p.y[size_t(i)], p.z[size_t(i)]};
    lobe_noise_d(lobe::shadeops::kSimplex, in, nullptr, nullptr, 3, nullptr, &p.scalar[size_t(i)],
                 nullptr, nullptr, 1);
  }
}

typedef float F8 __attribute__((vector_size(32)));
typedef int32_t I8 __attribute__((vector_size(32)));
typedef uint32_t U8 __attribute__((vector_size(32)));

// The 3-D gradient table (noise.cpp's kGrad3) as 2-bit codes per component, row r at bits 2r:
// 0 for 0, 1 for +1, 3 for -1.
constexpr float kGrad3[16][3] = {{1, 0, 1},  {0, 1, 1},  {-1, 0, 1},  {0, -1, 1},
                                 {1, 0, -1}, {0, 1, -1}, {-1, 0, -1}, {0, -1, -1},
                                 {1, -1, 0}, {1, 1, 0},  {-1, 1, 0},  {-1, -1, 0},
                                 {1, 0, 1},  {-1, 0, 1}, {0, 1, -1},  {0, -1, -1}};
constexpr uint32_t grad_code(int a) {
  uint32_t c = 0;
  for (int r = 0; r < 16; ++r)
    c |= uint32_t(kGrad3[r][a] == 0 ? 0 : (kGrad3[r][a] > 0 ? 1 : 3)) << (2 * r);
  return c;
}

__attribute__((target("avx2"))) inline U8 rot(U8 v, int k) { return (v << k) | (v >> (32 - k)); }

// lookup3's final mix (runtime/mathlib/hashword.h) lane by lane; returns c.
__attribute__((target("avx2"))) inline U8 final_mix(U8 a, U8 b, U8 c) {
  c ^= b, c -= rot(b, 14);
  a ^= c, a -= rot(c, 11);
  b ^= a, b -= rot(a, 25);
  c ^= b, c -= rot(b, 16);
  a ^= c, a -= rot(c, 4);
  b ^= a, b -= rot(a, 14);
  c ^= b, c -= rot(b, 24);
  return c;
}

__attribute__((target("avx2"))) inline I8 ifloor8(F8 v) {
  return (I8)_mm256_cvttps_epi32(_mm256_floor_ps((__m256)v));
}

// noise.cpp's simplex_n<3, false> for eight points, seed 0: skew, rank the offsets, step
// through the four corners, hash each corner's lattice point, and sum t^4 (g . d).
__attribute__((target("avx2"))) void simplex3x8(const float* px, const float* py, const float* pz,
                                                float* out) {
  const float F = 0.333333333f, G = 0.166666667f;
  F8 x[3];
  std::memcpy(&x[0], px, 32), std::memcpy(&x[1], py, 32), std::memcpy(&x[2], pz, 32);
  F8 s = x[0];
  s += x[1];
  s += x[2];
  s *= F;
  I8 cell[3] = {ifloor8(x[0] + s), ifloor8(x[1] + s), ifloor8(x[2] + s)};
  I8 sum = cell[0];
  sum += cell[1];
  sum += cell[2];
  F8 t = __builtin_convertvector(sum, F8) * G, d0[3];
  for (int a = 0; a < 3; ++a) d0[a] = x[a] - (__builtin_convertvector(cell[a], F8) - t);
  I8 rank[3] = {{}, {}, {}};
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) {
      I8 first = (I8)(d0[a] >= d0[b]) & 1; // ties to the earlier coordinate (3-D)
      rank[a] += first, rank[b] += 1 - first;
    }
  const U8 kSeed = U8{} ^ 0xdeadbeefu; // channel 0
  F8 total = F8{};
  for (int c = 0; c <= 3; ++c) {
    F8 d[3], tc = F8{} + 0.5f;
    U8 corner[3];
    for (int a = 0; a < 3; ++a) {
      I8 step = (I8)(rank[a] >= 3 - c) & 1;
      corner[a] = (U8)(cell[a] + step);
      d[a] = c == 0 ? d0[a] : (d0[a] - __builtin_convertvector(step, F8)) + (F8{} + float(c) * G);
      tc -= d[a] * d[a];
    }
    I8 inside = (I8)(tc >= 0.0f);
    U8 inner = final_mix(corner[2], U8{}, kSeed);
    U8 row = final_mix(corner[0], corner[1], inner ^ 0xdeadbeefu) & 15u;
    F8 g[3];
    for (int a = 0; a < 3; ++a) {
      U8 code = (U8{} + grad_code(a)) >> (row * 2u) & 3u;
      code &= (U8)inside;
      g[a] = (F8)((code & 1u) * 0x3f800000u | (code & 2u) << 30);
    }
    F8 dot = g[0] * d[0];
    dot += g[1] * d[1];
    dot += g[2] * d[2];
    F8 t2 = (F8)((I8)(tc * tc) & inside), t4 = t2 * t2;
    F8 nc = (F8)((I8)(t4 * dot) & inside);
    total = c == 0 ? nc : total + nc;
  }
  F8 r = total * 68.0f;
  std::memcpy(out, &r, 32);
}

void batched_all(Points& p) {
  for (int i = 0; i < kPoints; i += 8)
    simplex3x8(&p.x[size_t(i)], &p.y[size_t(i)], &p.z[size_t(i)], &p.batched[size_t(i)]);
}

bool same_bits(Points& p) {
  scalar_all(p);
  batched_all(p);
  return std::memcmp(p.scalar.data(), p.batched.data(), sizeof(float) * kPoints) == 0;
}

void BM_Simplex3_OnePointACall(benchmark::State& state) {
  Points& p = points();
  for (auto _ : state) {
    scalar_all(p);
    benchmark::DoNotOptimize(p.scalar.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * kPoints);
}

void BM_Simplex3_EightPointsACall(benchmark::State& state) {
  if (!__builtin_cpu_supports("avx2")) return state.SkipWithError("no AVX2 on this CPU");
  Points& p = points();
  if (!same_bits(p)) return state.SkipWithError("the batched results differ from lobe_noise_d");
  for (auto _ : state) {
    batched_all(p);
    benchmark::DoNotOptimize(p.batched.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * kPoints);
}

BENCHMARK(BM_Simplex3_OnePointACall);
BENCHMARK(BM_Simplex3_EightPointsACall);

} // namespace

BENCHMARK_MAIN();

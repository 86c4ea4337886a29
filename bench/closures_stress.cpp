// Closure stress benchmark: for every testable closure, >= 1e7 random inputs (directions over
// the whole sphere, so half below the horizon; random numbers incl. exact 0 and 1 - 2^-24;
// parameter blocks drawn from random values and from the extreme values of param_stress.h),
// counting outputs that are NaN, Inf or negative (must be 0); then Google Benchmark timings of
// eval() and sample() per closure (ns per call).
//
//   build/bench/closures_stress [--stress-inputs N] [benchmark flags]
#include "closure_lobe.h"
#include "configs.h"
#include "param_stress.h"
#include "rng.h"
#include "stress.h"

#include "closure_registry.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace lobe;
using namespace lobe::verify;

namespace {

// A pool of parameter blocks for one closure: the extremes and randomised ordinary values.
std::vector<closures::Params> parameter_pool(int id, uint64_t seed) {
  std::vector<ClosureConfig> cs = configs_for(id, Level::Full);
  std::vector<closures::Params> pool;
  for (const ClosureConfig& c : cs) pool.push_back(c.params);
  for (const ParamVariant& v : param_variants(cs.front().params)) pool.push_back(v.params);
  const registry::ClosureEntry& e = registry::closures()[id];
  Pcg32 rng(seed);
  for (int k = 0; k < 128; ++k) {
    closures::Params p = cs[k % cs.size()].params;
    for (const auto& prm : e.params) {
      if (prm.type == registry::ArgType::Float) p.set(prm.name, 2.5f * rng.next_float());
      if (prm.type == registry::ArgType::Color)
        p.set(prm.name, Vec3{3 * rng.next_float(), 3 * rng.next_float(), 3 * rng.next_float()});
    }
    pool.push_back(p);
  }
  return pool;
}

Vec3 random_u(Pcg32& rng) {
  Vec3 u = rng.next_vec3();
  uint32_t pick = rng.next_u32() % 64;
  if (pick == 0) u.x = 0;
  if (pick == 1) u.x = 1.0f - 0x1p-24f;
  if (pick == 2) u.y = 0;
  if (pick == 3) u.y = 1.0f - 0x1p-24f;
  return u;
}

// Runs `n` random inputs through closure `id`; returns the merged stress counts.
StressResult stress_closure(int id, uint64_t n) {
  std::vector<closures::Params> pool = parameter_pool(id, 99 + id);
  std::vector<ClosureLobe> lobes(pool.begin(), pool.end());
  Pcg32 rng(1234 + id);
  StressResult r;
  for (uint64_t k = 0; k < n; ++k) {
    const ClosureLobe& l = lobes[rng.next_u32() % lobes.size()];
    Vec3 wo = uniform_sphere(rng.next_double(), rng.next_double());
    Vec3 wi = uniform_sphere(rng.next_double(), rng.next_double());
    stress_eval(l, wo, wi, r);
    stress_sample(l, wo, random_u(rng), r);
  }
  return r;
}

void BM_Eval(benchmark::State& state, int id) {
  ClosureLobe l(configs_for(id, Level::Quick).front().params);
  Pcg32 rng(7);
  std::vector<Vec3> dirs(1024);
  for (Vec3& d : dirs) d = uniform_sphere(rng.next_double(), rng.next_double());
  for (Vec3& d : dirs) d.z = std::fabs(d.z);
  size_t k = 0;
  for (auto _ : state) {
    BsdfEval e = l.eval(dirs[k & 1023], dirs[(k + 7) & 1023], Transport::Radiance);
    benchmark::DoNotOptimize(e);
    ++k;
  }
}

void BM_Sample(benchmark::State& state, int id) {
  ClosureLobe l(configs_for(id, Level::Quick).front().params);
  Pcg32 rng(8);
  std::vector<Vec3> us(1024);
  for (Vec3& u : us) u = rng.next_vec3();
  Vec3 wo = direction_at(0.6);
  size_t k = 0;
  for (auto _ : state) {
    auto s = l.sample(wo, us[k & 1023], Transport::Radiance);
    benchmark::DoNotOptimize(s);
    ++k;
  }
}

} // namespace

int main(int argc, char** argv) {
  uint64_t inputs = 10000000;
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--stress-inputs") && i + 1 < argc) {
      inputs = std::strtoull(argv[++i], nullptr, 10);
      continue;
    }
    rest.push_back(argv[i]);
  }
  std::vector<int> ids;
  for (int id = 0; id < static_cast<int>(registry::closures().size()); ++id)
    if (is_testable(id)) ids.push_back(id);

  std::printf("%-26s %12s %12s %10s %10s\n", "closure", "inputs", "calls", "invalid", "bad-input");
  uint64_t total_invalid = 0;
  for (int id : ids) {
    StressResult r = stress_closure(id, inputs);
    total_invalid += r.invalid_outputs + r.invalid_inputs;
    std::printf("%-26s %12llu %12llu %10llu %10llu\n", registry::closures()[id].key,
                static_cast<unsigned long long>(inputs), static_cast<unsigned long long>(r.calls),
                static_cast<unsigned long long>(r.invalid_outputs),
                static_cast<unsigned long long>(r.invalid_inputs));
    if (!r.first_failure.empty()) std::printf("  first: %s\n", r.first_failure.c_str());
  }
  std::printf("non-finite or negative outputs in all: %llu\n\n",
              static_cast<unsigned long long>(total_invalid));

  for (int id : ids) {
    std::string key = registry::closures()[id].key;
    benchmark::RegisterBenchmark(("eval/" + key).c_str(), BM_Eval, id);
    benchmark::RegisterBenchmark(("sample/" + key).c_str(), BM_Sample, id);
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return total_invalid == 0 ? 0 : 1;
}

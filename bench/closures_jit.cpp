// Closure speed, native against JIT-inlined, side by side in one run: for every BSDF entry
// with bitcode, ns per eval() and per sample() through the native library (closures::eval /
// closures::sample, the C++ compiled by the project's compiler) and through closure kernels
// (the same C++ compiled by clang-19 to bitcode, linked into a JIT module with a dispatcher
// over the ids and inlined; runtime/jit/closure_kernels.h), each set up and evaluated per call
// (eval/, sample/) and set up once, then evaluated per call (eval_prepared/, sample_prepared/:
// what a Bsdf does at a shading point). Then a two-lobe material's Bsdf
// (diffuse + GGX dielectric) evaluated and sampled both ways. Inputs: 1024 direction pairs
// above the surface and 1024 random triples, the first quick configuration of each closure
// (plus dielectric_bsdf_aniso: roughness (0.3, 0.05), whose compensation reads the 5-D table).
//
//   build/bench/closures_jit [benchmark flags]      e.g. --benchmark_repetitions=3
#include "closure_kernels.h"
#include "closure_registry.h"
#include "closures.h"
#include "common.h"
#include "configs.h"
#include "rng.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

using namespace lobe;
using namespace lobe::verify;

namespace {

ClosureKernels g_kernels;

struct Inputs {
  std::vector<Vec3> dirs, us;
  Inputs() {
    Pcg32 rng(7);
    for (int i = 0; i < 1024; ++i) {
      Vec3 d = uniform_sphere(rng.next_double(), rng.next_double());
      d.z = std::fabs(d.z);
      dirs.push_back(d);
      us.push_back(rng.next_vec3());
    }
  }
};
const Inputs& inputs() {
  static Inputs in;
  return in;
}

void BM_EvalNative(benchmark::State& state, int id, closures::Params p) {
  const Inputs& in = inputs();
  size_t k = 0;
  for (auto _ : state) {
    BsdfEval e = closures::eval(id, p.data(), in.dirs[k & 1023], in.dirs[(k + 7) & 1023]);
    benchmark::DoNotOptimize(e);
    ++k;
  }
}
void BM_EvalJit(benchmark::State& state, int id, closures::Params p) {
  const Inputs& in = inputs();
  size_t k = 0;
  for (auto _ : state) {
    // Set up and evaluate, the same work as the native per-call eval above.
    alignas(Bsdf::kLobeStateAlign) unsigned char st[Bsdf::kLobeStateBytes];
    g_kernels.setup(id, p.data(), st);
    BsdfEval e;
    g_kernels.eval(id, st, &in.dirs[k & 1023], &in.dirs[(k + 7) & 1023], 0, &e);
    benchmark::DoNotOptimize(e);
    ++k;
  }
}
void BM_SampleNative(benchmark::State& state, int id, closures::Params p) {
  const Inputs& in = inputs();
  size_t k = 0;
  for (auto _ : state) {
    auto s = closures::sample(id, p.data(), in.dirs[k & 1023], in.us[(k + 3) & 1023]);
    benchmark::DoNotOptimize(s);
    ++k;
  }
}
void BM_SampleJit(benchmark::State& state, int id, closures::Params p) {
  const Inputs& in = inputs();
  size_t k = 0;
  for (auto _ : state) {
    alignas(Bsdf::kLobeStateAlign) unsigned char st[Bsdf::kLobeStateBytes];
    g_kernels.setup(id, p.data(), st);
    BsdfSample s;
    int ok = g_kernels.sample(id, st, &in.dirs[k & 1023], &in.us[(k + 3) & 1023], 0, &s);
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(s);
    ++k;
  }
}

// Set up once, then evaluated or sampled per call (what a Bsdf does at a shading point:
// Bsdf::build sets each lobe up, its eval and sample read the state).
void BM_Prepared(benchmark::State& state, int id, closures::Params p, bool jit, bool sample) {
  const Inputs& in = inputs();
  alignas(Bsdf::kLobeStateAlign) unsigned char st[Bsdf::kLobeStateBytes];
  if (jit)
    g_kernels.setup(id, p.data(), st);
  else
    closures::setup(id, p.data(), st);
  size_t k = 0;
  for (auto _ : state) {
    const Vec3& wo = in.dirs[k & 1023];
    if (sample && jit) {
      BsdfSample s;
      int ok = g_kernels.sample(id, st, &wo, &in.us[(k + 3) & 1023], 0, &s);
      benchmark::DoNotOptimize(ok);
      benchmark::DoNotOptimize(s);
    } else if (sample) {
      auto s = closures::sample_prepared(id, st, wo, in.us[(k + 3) & 1023]);
      benchmark::DoNotOptimize(s);
    } else if (jit) {
      BsdfEval e;
      g_kernels.eval(id, st, &wo, &in.dirs[(k + 7) & 1023], 0, &e);
      benchmark::DoNotOptimize(e);
    } else {
      BsdfEval e = closures::eval_prepared(id, st, wo, in.dirs[(k + 7) & 1023]);
      benchmark::DoNotOptimize(e);
    }
    ++k;
  }
}

// A diffuse + rough dielectric material flattened into a Bsdf, with or without kernels.
struct Material2 {
  closures::Params a{"diffuse"}, b{"dielectric_bsdf"};
  alignas(16) unsigned char storage[2][sizeof(ClosureComponent) + closures::Params::kMaxBytes];
  ClosureAdd sum;
  Material2() {
    a.set("N", Vec3{0, 0, 1});
    b.set("N", Vec3{0, 0, 1}).set("roughness_x", 0.2f).set("roughness_y", 0.2f);
    b.set("ior", 1.5f).set("reflection_tint", Vec3{1, 1, 1});
    const closures::Params* ps[2] = {&a, &b};
    ClosureNode* nodes[2];
    for (int i = 0; i < 2; ++i) {
      auto* c = new (storage[i]) ClosureComponent;
      c->id = ps[i]->id();
      c->weight = Color3{0.5f, 0.5f, 0.5f};
      std::memcpy(c->params(), ps[i]->data(), ps[i]->size());
      nodes[i] = c;
    }
    sum.id = kClosureAdd;
    sum.a = nodes[0];
    sum.b = nodes[1];
  }
};

void BM_Material(benchmark::State& state, bool jit, bool sample) {
  static Material2 m;
  const Inputs& in = inputs();
  Vec3 wo = normalize(Vec3{0.3f, 0.2f, 0.9f});
  Bsdf bsdf;
  bsdf.build(&m.sum, wo, Vec3{0, 0, 1}, jit ? &g_kernels : nullptr);
  size_t k = 0;
  for (auto _ : state) {
    if (sample) {
      auto s = bsdf.sample(wo, in.us[k & 1023]);
      benchmark::DoNotOptimize(s);
    } else {
      BsdfEval e = bsdf.eval(wo, in.dirs[k & 1023]);
      benchmark::DoNotOptimize(e);
    }
    ++k;
  }
}

} // namespace

int main(int argc, char** argv) {
  std::string err;
  std::unique_ptr<jit::Jit> jit = jit::Jit::create(err);
  if (!jit) {
    std::fprintf(stderr, "closures_jit: %s\n", err.c_str());
    return 1;
  }
  std::vector<int> ids; // every closure the property suites test: all BSDFs with bitcode
  auto all = registry::closures();
  for (int id = 0; id < int(all.size()); ++id)
    if (is_testable(id)) ids.push_back(id);
  jit::CompiledGroup code;
  jit::JitTimes times;
  if (!jit::compile_closure_kernels(*jit, ids, g_kernels, code, times, err)) {
    std::fprintf(stderr, "closures_jit: %s\n", err.c_str());
    return 1;
  }
  std::printf("kernels for %zu closures: optimise %.1f ms, machine code %.1f ms\n", ids.size(),
              times.optimize_ms, times.codegen_ms);
  auto add = [](const std::string& key, int id, const closures::Params& p) {
    benchmark::RegisterBenchmark(("eval/native/" + key).c_str(), BM_EvalNative, id, p);
    benchmark::RegisterBenchmark(("eval/jit/" + key).c_str(), BM_EvalJit, id, p);
    benchmark::RegisterBenchmark(("sample/native/" + key).c_str(), BM_SampleNative, id, p);
    benchmark::RegisterBenchmark(("sample/jit/" + key).c_str(), BM_SampleJit, id, p);
    benchmark::RegisterBenchmark(("eval_prepared/native/" + key).c_str(), BM_Prepared, id, p, false,
                                 false);
    benchmark::RegisterBenchmark(("eval_prepared/jit/" + key).c_str(), BM_Prepared, id, p, true,
                                 false);
    benchmark::RegisterBenchmark(("sample_prepared/native/" + key).c_str(), BM_Prepared, id, p,
                                 false, true);
    benchmark::RegisterBenchmark(("sample_prepared/jit/" + key).c_str(), BM_Prepared, id, p, true,
                                 true);
  };
  for (int id : ids) {
    std::string key = all[size_t(id)].key;
    closures::Params p = configs_for(id, Level::Quick).front().params;
    add(key, id, p);
    if (key == "dielectric_bsdf") { // anisotropic: the 5-D compensation table
      p.set("roughness_x", 0.3f).set("roughness_y", 0.05f);
      add(key + "_aniso", id, p);
    }
  }
  benchmark::RegisterBenchmark("material_eval/native", BM_Material, false, false);
  benchmark::RegisterBenchmark("material_eval/jit", BM_Material, true, false);
  benchmark::RegisterBenchmark("material_sample/native", BM_Material, false, true);
  benchmark::RegisterBenchmark("material_sample/jit", BM_Material, true, true);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  jit->remove(code);
  return 0;
}

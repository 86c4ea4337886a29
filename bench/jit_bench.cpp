// JIT benchmarks (see docs/runtime.md, "Measured"):
//  * BM_Pipeline/<opt>: compile bench/jit_material.osl (305 lines) from source to machine code,
//    a fresh ShadingSystem each time (no cache); counters give each stage in ms.
//  * BM_MathShader vs BM_MathNative: bench/jit_math.osl per point against the same computation
//    written in C++ and compiled -O2 (counter `ns_per_point`).
#include "grid.h"
#include "lobe/shadingsys.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

namespace {

const std::string kDir = LOBE_BENCH_DIR;

std::shared_ptr<const lobe::Material> compile(lobe::ShadingSystem& ss, const std::string& file,
                                              int opt) {
  ss.options().opt_level = opt;
  ss.options().specialize = opt > 0;
  lobe::ShaderGroup g;
  g.layers.push_back({kDir + "/" + file, "l", {}});
  lobe::DiagnosticList d;
  return ss.compile(g, d);
}

void BM_Pipeline(benchmark::State& state) {
  int opt = int(state.range(0));
  lobe::CompileStats sum;
  double n = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto ss = std::make_unique<lobe::ShadingSystem>();
    state.ResumeTiming();
    auto m = compile(*ss, "jit_material.osl", opt);
    if (!m) {
      state.SkipWithError("compile failed");
      return;
    }
    const lobe::CompileStats& s = m->stats();
    sum.preprocess_ms += s.preprocess_ms;
    sum.parse_ms += s.parse_ms;
    sum.sema_ms += s.sema_ms;
    sum.ir_ms += s.ir_ms;
    sum.specialize_ms += s.specialize_ms;
    sum.llvm_ir_ms += s.llvm_ir_ms;
    sum.optimize_ms += s.optimize_ms;
    sum.codegen_ms += s.codegen_ms;
    n += 1;
    state.PauseTiming();
    m.reset();
    ss.reset();
    state.ResumeTiming();
  }
  double front = (sum.preprocess_ms + sum.parse_ms + sum.sema_ms) / n;
  double total =
      front +
      (sum.ir_ms + sum.specialize_ms + sum.llvm_ir_ms + sum.optimize_ms + sum.codegen_ms) / n;
  state.counters["front_ms"] = front;
  state.counters["lower_ms"] = sum.ir_ms / n;
  state.counters["specialize_ms"] = sum.specialize_ms / n;
  state.counters["llvm_ir_ms"] = sum.llvm_ir_ms / n;
  state.counters["optimize_ms"] = sum.optimize_ms / n;
  state.counters["codegen_ms"] = sum.codegen_ms / n;
  state.counters["total_ms"] = total;
  state.counters["front_pct"] = 100 * front / total;
}
BENCHMARK(BM_Pipeline)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(20);

constexpr int kGrid = 64;

void BM_MathShader(benchmark::State& state) {
  lobe::ShadingSystem ss;
  auto m = compile(ss, "jit_math.osl", 2);
  if (!m) {
    state.SkipWithError("compile failed");
    return;
  }
  lobe::ShadingContext ctx;
  lobe::group::GridSpec grid{kGrid, kGrid, false, lobe::kRayCamera};
  for (auto _ : state)
    for (int y = 0; y < kGrid; ++y)
      for (int x = 0; x < kGrid; ++x) {
        lobe::ShaderGlobals sg = lobe::group::grid_globals(grid, x, y, &ctx);
        m->shade(sg);
      }
  state.counters["ns_per_point"] =
      benchmark::Counter(double(state.iterations()) * kGrid * kGrid,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_MathShader)->Unit(benchmark::kMicrosecond);

} // namespace

// jit_bench_native.cpp (compiled -O2): the shader's computation in C++.
float lobe_math_native(float u, float v);

namespace {

void BM_MathNative(benchmark::State& state) {
  lobe::group::GridSpec grid{kGrid, kGrid, false, lobe::kRayCamera};
  for (auto _ : state)
    for (int y = 0; y < kGrid; ++y)
      for (int x = 0; x < kGrid; ++x) {
        lobe::ShaderGlobals sg = lobe::group::grid_globals(grid, x, y, nullptr);
        benchmark::DoNotOptimize(lobe_math_native(sg.u, sg.v));
      }
  state.counters["ns_per_point"] =
      benchmark::Counter(double(state.iterations()) * kGrid * kGrid,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_MathNative)->Unit(benchmark::kMicrosecond);

} // namespace

BENCHMARK_MAIN();

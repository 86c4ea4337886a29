// Compile-pipeline benchmark: how long each stage takes on a realistic material
// (bench/shaders/material_300.osl, or the file given as the first argument).
//   Frontend   preprocess + lex/parse + sema; the per-stage times are reported as counters
//              (preprocess_ms, parse_ms, sema_ms: mean per iteration)
//   Lower      typed AST -> verified Lobe IR (derivative analysis included), -O0
//   LowerOpt   the same with constant folding and dead-code elimination (-O1)
//   Pipeline   everything, as `lobe compile` runs it
#include "lower/pipeline.h"

#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>

namespace {

std::string g_path = std::string(LOBE_SOURCE_DIR) + "/bench/shaders/material_300.osl";
std::string g_text;

lobe::frontend::SourceInput input() { return {g_path, g_text}; }

void Frontend(benchmark::State& state) {
  double pp = 0, parse = 0, sema = 0;
  for (auto _ : state) {
    lobe::diag::DiagnosticEngine diags;
    lobe::frontend::FrontendTimings t;
    auto tu = lobe::frontend::compile_to_ast(input(), {}, diags, &t);
    if (diags.has_errors()) state.SkipWithError("the shader has errors");
    benchmark::DoNotOptimize(tu.get());
    pp += t.preprocess_ms, parse += t.parse_ms, sema += t.sema_ms;
  }
  using C = benchmark::Counter;
  state.counters["preprocess_ms"] = C(pp, C::kAvgIterations);
  state.counters["parse_ms"] = C(parse, C::kAvgIterations);
  state.counters["sema_ms"] = C(sema, C::kAvgIterations);
}

void Lower(benchmark::State& state, bool optimize) {
  lobe::diag::DiagnosticEngine diags;
  auto tu = lobe::frontend::compile_to_ast(input(), {}, diags);
  if (diags.has_errors()) {
    state.SkipWithError("the shader has errors");
    return;
  }
  size_t ops = 0;
  for (auto _ : state) {
    lobe::lower::LowerResult r = lobe::lower::lower(*tu, diags, {optimize});
    if (!r.shader)
      state.SkipWithError("lowering failed");
    else
      ops = r.shader->ops.size();
    benchmark::DoNotOptimize(r);
  }
  state.counters["ir_ops"] = double(ops);
}

void Pipeline(benchmark::State& state) {
  lobe::lower::PipelineOptions o;
  o.optimize = true;
  for (auto _ : state) {
    lobe::lower::PipelineResult r = lobe::lower::compile_osl(input(), o);
    if (!r.ok) state.SkipWithError("the shader has errors");
    benchmark::DoNotOptimize(r);
  }
}

} // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (argc > 1) g_path = argv[1];
  std::ifstream in(g_path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  g_text = ss.str();
  if (g_text.empty()) {
    std::fprintf(stderr, "compile_pipeline: cannot read %s\n", g_path.c_str());
    return 1;
  }
  benchmark::RegisterBenchmark("Frontend", Frontend)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Lower", Lower, false)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("LowerOpt", Lower, true)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Pipeline", Pipeline)->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// Bounded execution through the API a plugin uses: a shade whose loops run past
// CompileOptions::max_loop_iterations is stopped with an error naming the shader, the layer and
// the loop's line; ShadingContext::stopped is set and no closure leaves it; ShadingContext::cancel
// stops loops with no limit; loops that end are unchanged (at every setting).
#include "grid.h"
#include "lobe/shadingsys.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

namespace {

// Line 4 is the endless loop; x doubles to +Inf (a stopped shade must not hand it on in Ci).
const char* kEndless = "shader endless(output color Cout = 0, output float x = 1)\n"
                       "{\n"
                       "  float y = 0;\n"
                       "  while (1) { x = x * 2; y += 1; }\n"
                       "  Cout = color(x);\n"
                       "  Ci = x * emission();\n"
                       "}\n";

// Sums 0 + 1 + ... + (n-1) in nested loops: n = outer * inner, inner on line 5.
const char* kFinite = "shader finite(int outer = 10, int inner = 100, output float sum = 0)\n"
                      "{\n"
                      "  int k = 0;\n"
                      "  for (int i = 0; i < outer; ++i)\n"
                      "    for (int j = 0; j < inner; ++j) { sum += k; ++k; }\n"
                      "  Ci = sum * emission();\n"
                      "}\n";

std::shared_ptr<const lobe::Material> compile(lobe::ShadingSystem& ss, const char* name,
                                              const char* source,
                                              std::vector<lobe::InstanceValue> values = {}) {
  lobe::DiagnosticList diags;
  EXPECT_TRUE(ss.add_shader_source(name, source, std::string(name) + ".osl", diags));
  lobe::ShaderGroup g;
  g.name = "g";
  g.layers.push_back({name, "l1", std::move(values)});
  auto m = ss.compile(g, diags);
  std::string text;
  for (const auto& d : diags) text += d.text + "\n";
  EXPECT_TRUE(m) << text;
  return m;
}

struct Shaded {
  bool stopped = false;
  int errors = 0;
  std::string output;
  bool has_closure = false;
  std::vector<float> values;
};

Shaded shade(const lobe::Material& m, const char* output,
             const std::atomic<bool>* cancel = nullptr) {
  lobe::ShadingContext ctx;
  ctx.cancel = cancel;
  lobe::group::GridSpec grid;
  lobe::ShaderGlobals sg = lobe::group::grid_globals(grid, 0, 0, &ctx);
  m.shade(sg);
  Shaded r;
  r.stopped = ctx.stopped;
  r.errors = ctx.errors;
  r.output = ctx.output;
  r.has_closure = sg.Ci != nullptr;
  m.read_output(ctx, "l1", output, r.values);
  return r;
}

TEST(BoundedLoops, EndlessLoopStopsWithTheShaderAndLine) {
  for (int opt : {0, 2}) {
    lobe::ShadingSystem ss;
    ss.options().opt_level = opt;
    ss.options().max_loop_iterations = 100000;
    auto m = compile(ss, "endless", kEndless);
    ASSERT_TRUE(m);
    for (int again = 0; again < 2; ++again) { // each shade starts a fresh count
      Shaded r = shade(*m, "x");
      EXPECT_TRUE(r.stopped);
      EXPECT_EQ(r.errors, 1);
      EXPECT_EQ(r.output, "ERROR: shader endless (group g, layer 0 l1): loop at endless.osl:4 ran "
                          "more than 100000 iterations (max_loop_iterations); stopped\n")
          << "-O" << opt;
      EXPECT_FALSE(r.has_closure); // x is +Inf by now: no closure carries it
    }
  }
}

// The default limit (1e8) stops it too; so does a shade without a context (silently).
TEST(BoundedLoops, DefaultLimitAndNoContext) {
  lobe::ShadingSystem ss;
  EXPECT_EQ(ss.options().max_loop_iterations, 100000000);
  auto m = compile(ss, "endless", kEndless);
  ASSERT_TRUE(m);
  Shaded r = shade(*m, "x");
  EXPECT_TRUE(r.stopped);
  EXPECT_NE(r.output.find("ran more than 100000000 iterations"), std::string::npos) << r.output;
  lobe::group::GridSpec grid;
  lobe::ShaderGlobals sg = lobe::group::grid_globals(grid, 0, 0, nullptr);
  m->shade(sg); // returns
  EXPECT_EQ(sg.Ci, nullptr);
}

// With no limit, cancel stops the loop: at once when set before, or when set from another
// thread while the shader runs. No error: the caller asked for it.
TEST(BoundedLoops, CancelStopsAnUnlimitedLoop) {
  lobe::ShadingSystem ss;
  ss.options().max_loop_iterations = 0;
  auto m = compile(ss, "endless", kEndless);
  ASSERT_TRUE(m);
  std::atomic<bool> cancel{true};
  Shaded r = shade(*m, "x", &cancel);
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.errors, 0);
  EXPECT_EQ(r.output, "");
  EXPECT_FALSE(r.has_closure);

  cancel = false;
  std::thread t([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    cancel = true;
  });
  r = shade(*m, "x", &cancel);
  t.join();
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.errors, 0);
}

// Loops that end compute what they compute, whatever the setting; past the limit they stop.
TEST(BoundedLoops, FiniteLoopsAreUnchanged) {
  // 1010 back edges (1000 inner, 10 outer): 2000 is enough.
  for (long long limit : {-1LL, 0LL, 2000LL, 100000000LL}) {
    for (int opt : {0, 2}) {
      lobe::ShadingSystem ss;
      ss.options().opt_level = opt;
      ss.options().max_loop_iterations = limit;
      auto m = compile(ss, "finite", kFinite);
      ASSERT_TRUE(m);
      Shaded r = shade(*m, "sum");
      EXPECT_FALSE(r.stopped) << limit;
      ASSERT_EQ(r.values.size(), 1u);
      EXPECT_EQ(r.values[0], 499500.0f) << limit; // sum of 0..999, exact in a float
      EXPECT_TRUE(r.has_closure);
    }
  }
  // 10 x 100000 iterations against a limit of 200000: stopped in the inner loop (line 5).
  lobe::ShadingSystem ss;
  ss.options().max_loop_iterations = 200000;
  auto m = compile(ss, "finite", kFinite, {{"int", "outer", "10"}, {"int", "inner", "100000"}});
  ASSERT_TRUE(m);
  Shaded r = shade(*m, "sum");
  EXPECT_TRUE(r.stopped);
  EXPECT_NE(r.output.find("loop at finite.osl:5 ran more than 200000 iterations"),
            std::string::npos)
      << r.output;
  ASSERT_EQ(r.values.size(), 1u);
  EXPECT_TRUE(std::isfinite(r.values[0]));
}

} // namespace

// A message sink that throws (here: std::bad_alloc, as when the memory runs out) must not
// unwind through the shader's frames: the shade goes on, the message is counted in
// messages_lost, and the messages the sink takes still arrive.
TEST(ShaderMessages, ASinkThatThrowsLosesTheMessageNotTheProcess) {
  lobe::ShadingSystem ss;
  auto m = compile(ss, "talk",
                   "shader talk(output float f = 0)\n"
                   "{\n"
                   "  printf(\"one\\n\");\n"
                   "  error(\"two\");\n"
                   "  printf(\"three\\n\");\n"
                   "  f = 7;\n"
                   "}\n");
  ASSERT_TRUE(m);
  lobe::ShadingContext ctx;
  std::vector<std::string> taken;
  ctx.report = [&taken](lobe::ShadingContext::MessageKind, const std::string& t) {
    if (t.find("two") != std::string::npos) throw std::bad_alloc();
    taken.push_back(t);
  };
  lobe::group::GridSpec grid;
  lobe::ShaderGlobals sg = lobe::group::grid_globals(grid, 0, 0, &ctx);
  m->shade(sg);
  EXPECT_EQ(ctx.messages_lost, 1u);
  EXPECT_EQ(ctx.errors, 1);
  ASSERT_EQ(taken.size(), 2u);
  EXPECT_EQ(taken[0], "one\n");
  EXPECT_EQ(taken[1], "three\n");
  std::vector<float> f;
  ASSERT_TRUE(m->read_output(ctx, "l1", "f", f));
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0], 7.0f);
}

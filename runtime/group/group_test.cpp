// Shader groups through the public API, on layers given as IR text (ShadingSystem::add_shader_ir):
// group text, instance values, every kind of connection, lazy layers, specialisation on/off
// giving identical output, the cache, read_output and globals_read.
#include "driver/search.h"
#include "group_build.h"
#include "ir/parser.h"
#include "ir/printer.h"
#include "lobe/bsdf.h"
#include "lobe/shadingsys.h"
#include "shader_source.h"

#include "diag/diag_ids.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>
#include <unistd.h>

using namespace lobe;

namespace {

// upstream: Cout = color(a, 2a, 3a), f[] = {a, 10}, prints when it runs.
const char* kUpstream = R"(lobe-ir 1
shader upstream
symbols
  param float a = 1
  oparam color Cout = 0 0 0
  oparam float[2] f = 0 0
  oparam float s.x = 0 struct=S
  oparam float s.y = 0 struct=S
  temp float $t0
  temp float $t1
  const float $c2 = 2
  const float $c3 = 3
  const float $c10 = 10
  const int $i0 = 0
  const int $i1 = 1
  const string $msg = "upstream ran\n"
main
  useparam a
  printf $msg
  mul $t0 a $c2
  mul $t1 a $c3
  construct Cout a $t0 $t1
  aassign f $i0 a
  aassign f $i1 $c10
  assign s.x $c2
  add s.y a $c10
end
)";

// downstream: prints its inputs, but reads `Cin` only when `use` is nonzero.
const char* kDownstream = R"(lobe-ir 1
surface downstream
symbols
  param int use = 1
  param color Cin = 0 0 0
  param float g = 0
  param float h = 0
  param float sx = 0
  param string mode = "plain"
  oparam float result = 0
  temp int $t0
  const string $fmt = "Cin %g g %g h %g sx %g\n"
  const string $fancy = "fancy"
  const string $m1 = "mode fancy\n"
  const string $m2 = "mode plain\n"
  const float $c7 = 7
main
  useparam use
  cbr use -> Lread Lskip
Lread:
  useparam Cin g h sx
  printf $fmt Cin g h sx
Lskip:
  useparam mode
  eq $t0 mode $fancy
  cbr $t0 -> Lfancy Lplain
Lfancy:
  printf $m1
  br -> Ldone
Lplain:
  printf $m2
Ldone:
  assign result $c7
end
)";

struct GroupRun {
  std::string output;
  std::shared_ptr<const Material> mat;
};

GroupRun run_group(ShadingSystem& ss, const std::string& text, bool specialize, int opt = 2) {
  DiagnosticList diags;
  auto g = ss.parse_group(text, "test", diags);
  EXPECT_TRUE(g) << (diags.empty() ? "" : diags[0].text);
  if (!g) return {};
  ss.options().specialize = specialize;
  ss.options().opt_level = opt;
  auto mat = ss.compile(*g, diags);
  EXPECT_TRUE(mat) << (diags.empty() ? "" : diags[0].text);
  if (!mat) return {};
  ShadingContext ctx;
  ShaderGlobals sg{};
  sg.context = &ctx;
  mat->shade(sg);
  return {ctx.output, mat};
}

class Groups : public ::testing::Test {
protected:
  void SetUp() override {
    DiagnosticList d;
    ASSERT_TRUE(ss.add_shader_ir("upstream", kUpstream, d)) << d[0].text;
    ASSERT_TRUE(ss.add_shader_ir("downstream", kDownstream, d)) << d[0].text;
  }
  // Runs with specialisation off (-O0) and on (-O2): the output must be identical.
  std::string both(const std::string& text) {
    GroupRun a = run_group(ss, text, false, 0);
    GroupRun b = run_group(ss, text, true, 2);
    EXPECT_EQ(a.output, b.output) << "specialisation changed the output";
    return b.output;
  }
  ShadingSystem ss;
};

TEST_F(Groups, ParseGroupText) {
  DiagnosticList d;
  auto g =
      ss.parse_group("param float a 0.5 ; param color c 1 0 0 ; shader up u1 ;\n"
                     "param string mode \"fancy\" shader down d1 ; connect u1.Cout d1.Cin[1] ;",
                     "t", d);
  ASSERT_TRUE(g);
  ASSERT_EQ(g->layers.size(), 2u);
  EXPECT_EQ(g->layers[0].values.size(), 2u);
  EXPECT_EQ(g->layers[0].values[1].value, "1 0 0");
  EXPECT_EQ(g->layers[1].values[0].value, "fancy");
  ASSERT_EQ(g->connections.size(), 1u);
  EXPECT_EQ(g->connections[0].src_layer, "u1");
  EXPECT_EQ(g->connections[0].dst_param, "Cin[1]");
  EXPECT_FALSE(ss.parse_group("shader a ; connect x y ;", "t", d));
  EXPECT_FALSE(ss.parse_group("frobnicate ;", "t", d));
}

TEST_F(Groups, InstanceValuesAndDefaults) {
  EXPECT_EQ(both("shader downstream d ;"), "Cin 0 0 0 g 0 h 0 sx 0\nmode plain\n");
  EXPECT_EQ(both("param color Cin 1 2 3 ; param float g 0.5 ; param string mode \"fancy\" ; shader "
                 "downstream d ;"),
            "Cin 1 2 3 g 0.5 h 0 sx 0\nmode fancy\n");
}

TEST_F(Groups, ConnectionsOfEachKind) {
  // whole param, array element, component, struct member (u.s -> whole struct is tested by
  // connecting one member).
  EXPECT_EQ(both("param float a 2 ; shader upstream u ; shader downstream d ;"
                 "connect u.Cout d.Cin ; connect u.f[1] d.g ; connect u.Cout[2] d.h ; connect "
                 "u.s.y d.sx ;"),
            "upstream ran\nCin 2 4 6 g 10 h 6 sx 12\nmode plain\n");
  // a component into a component
  EXPECT_EQ(
      both("param float a 1 ; shader upstream u ; shader downstream d ; connect u.f[0] d.Cin[1] ;"),
      "upstream ran\nCin 0 1 0 g 0 h 0 sx 0\nmode plain\n");
}

TEST_F(Groups, LazyLayersRunOnlyWhenRead) {
  // Cin is connected but never read (use = 0): the upstream layer never runs.
  EXPECT_EQ(
      both("shader upstream u ; param int use 0 ; shader downstream d ; connect u.Cout d.Cin ;"),
      "mode plain\n");
  // An upstream layer nothing connects to never runs either.
  EXPECT_EQ(both("shader upstream u ; shader downstream d ;"),
            "Cin 0 0 0 g 0 h 0 sx 0\nmode plain\n");
  // Two connections from one layer: it runs once.
  EXPECT_EQ(both("shader upstream u ; shader downstream d ; connect u.Cout d.Cin ; connect "
                 "u.Cout[0] d.g ;"),
            "upstream ran\nCin 1 2 3 g 1 h 0 sx 0\nmode plain\n");
}

TEST_F(Groups, CacheHitsAndReadOutput) {
  std::string text =
      "param float a 3 ; shader upstream u ; shader downstream d ; connect u.Cout d.Cin ;";
  // -O1: at -O2 the upstream layer (its Cout a constant) is elided, and has no output to read
  // (checked below).
  GroupRun a = run_group(ss, text, true, 1);
  ASSERT_TRUE(a.mat);
  EXPECT_FALSE(a.mat->stats().cache_hit);
  GroupRun b = run_group(ss, text, true, 1);
  ASSERT_TRUE(b.mat);
  EXPECT_TRUE(b.mat->stats().cache_hit);
  EXPECT_EQ(a.output, b.output);
  std::vector<float> out;
  ShadingContext ctx;
  ShaderGlobals sg{};
  sg.context = &ctx;
  b.mat->shade(sg);
  ASSERT_TRUE(b.mat->read_output(ctx, "d", "result", out));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], 7.0f);
  ASSERT_TRUE(b.mat->read_output(ctx, "u", "Cout", out));
  EXPECT_EQ(out, (std::vector<float>{3, 6, 9}));
  // The same values through output_data at output_info's offset (looked up once, then read by
  // pointer at every point, as lobe shade does).
  auto info = b.mat->output_info("u", "Cout");
  ASSERT_TRUE(info);
  const unsigned char* data = b.mat->output_data(ctx);
  ASSERT_NE(data, nullptr);
  float cout[3];
  std::memcpy(cout, data + info->offset, sizeof cout);
  EXPECT_EQ(std::vector<float>(cout, cout + 3), (std::vector<float>{3, 6, 9}));
  EXPECT_FALSE(b.mat->read_output(ctx, "d", "nope", out));
  GroupRun o2 = run_group(ss, text, true, 2);
  ASSERT_TRUE(o2.mat);
  EXPECT_EQ(o2.output, "Cin 3 6 9 g 0 h 0 sx 0\nmode plain\n"); // no "upstream ran"
  EXPECT_FALSE(o2.mat->read_output(ctx, "u", "Cout", out));
  ASSERT_TRUE(o2.mat->read_output(ctx, "d", "result", out));
  // A different instance value is a different material.
  GroupRun c = run_group(
      ss, "param float a 4 ; shader upstream u ; shader downstream d ; connect u.Cout d.Cin ;",
      true);
  ASSERT_TRUE(c.mat);
  EXPECT_FALSE(c.mat->stats().cache_hit);
}

// read_output reads what the last shade() with the given context left: two contexts shading
// one material keep their own results, and a context that shaded another material since reads
// the values before any shade (here the default 0).
TEST(GroupOutputs, ReadOutputIsPerContext) {
  ShadingSystem ss;
  DiagnosticList d;
  ASSERT_TRUE(ss.add_shader_ir("twice", R"(lobe-ir 1
surface twice
symbols
  global float u
  oparam float r = 0
  const float $c2 = 2
main
  mul r u $c2
end
)",
                               d));
  ASSERT_TRUE(ss.add_shader_ir("other", "lobe-ir 1\nsurface other\nsymbols\nmain\nend\n", d));
  auto twice = ss.compile(*ss.parse_group("shader twice l ;", "t", d), d);
  auto other = ss.compile(*ss.parse_group("shader other l ;", "t", d), d);
  ASSERT_TRUE(twice && other);
  ShadingContext c1, c2;
  ShaderGlobals s1{}, s2{};
  s1.context = &c1;
  s1.u = 1;
  s2.context = &c2;
  s2.u = 3;
  twice->shade(s1);
  twice->shade(s2);
  std::vector<float> out;
  ASSERT_TRUE(twice->read_output(c1, "l", "r", out));
  EXPECT_EQ(out, std::vector<float>{2});
  ASSERT_TRUE(twice->read_output(c2, "l", "r", out));
  EXPECT_EQ(out, std::vector<float>{6});
  ShaderGlobals s3{};
  s3.context = &c1;
  other->shade(s3);
  ASSERT_TRUE(twice->read_output(c1, "l", "r", out));
  EXPECT_EQ(out, std::vector<float>{0});
  ASSERT_TRUE(twice->read_output(c2, "l", "r", out));
  EXPECT_EQ(out, std::vector<float>{6});
}

// Unsized array parameters (`float[]`) take their length per instance: the default's (its
// values, or `len=` for a computed default), an instance value's, or a connected array's
// (a connection wins over an instance value). arraylength() and the elements follow.
const char* kSizes = R"(lobe-ir 1
shader sizes
symbols
  param float[] a = 1 2
  param float[] b init=0:2 len=3
  temp int $na
  temp int $nb
  temp int $k
  temp float $ta
  temp float $tb
  const int $i0 = 0
  const int $i1 = 1
  const int $i2 = 2
  const float $c5 = 5
  const string $fmt = "a %d alast %g b %d blast %g\n"
init
  aassign b $i0 $c5
  aassign b $i2 $c5
main
  useparam a b
  arraylength $na a
  arraylength $nb b
  sub $k $na $i1
  aref $ta a $k
  sub $k $nb $i1
  aref $tb b $k
  printf $fmt $na $ta $nb $tb
end
)";

TEST_F(Groups, UnsizedArrayLengthComesFromTheInstance) {
  DiagnosticList d;
  ASSERT_TRUE(ss.add_shader_ir("sizes", kSizes, d)) << d[0].text;
  EXPECT_EQ(both("shader sizes s ;"), "a 2 alast 2 b 3 blast 5\n");
  EXPECT_EQ(both("param float[] a 4 5 6 ; param float[] b 7 8 ; shader sizes s ;"),
            "a 3 alast 6 b 2 blast 8\n");
  EXPECT_EQ(both("param float[] a 9 ; shader sizes s ;"), "a 1 alast 9 b 3 blast 5\n");
  // upstream's f is float[2] = {a, 10}: the connection fixes a's length, not the value.
  EXPECT_EQ(both("shader upstream u ; param float[] a 4 5 6 ; shader sizes s ; connect u.f s.a ;"),
            "upstream ran\na 2 alast 10 b 3 blast 5\n");
}

TEST_F(Groups, ErrorsAreDiagnostics) {
  DiagnosticList d;
  auto g = ss.parse_group("shader nosuchshader x ;", "t", d);
  ASSERT_TRUE(g);
  EXPECT_FALSE(ss.compile(*g, d));
  ASSERT_FALSE(d.empty());
  EXPECT_NE(d.back().text.find("not found"), std::string::npos);
  g = ss.parse_group("shader downstream d ; shader upstream u ; connect u.Cout d.Cin ;", "t", d);
  EXPECT_FALSE(ss.compile(*g, d)); // source layer after destination
  // A typed value reads as C's atof does, as in OSL (oops is 0), with a warning from Lobe.
  g = ss.parse_group("param float g oops ; shader downstream d ;", "t", d);
  d.clear();
  EXPECT_TRUE(ss.compile(*g, d));
  ASSERT_FALSE(d.empty());
  EXPECT_NE(d[0].text.find("value 'oops' for parameter 'g' is not a number"), std::string::npos)
      << d[0].text;
  g = ss.parse_group("param float g 1 ; shader downstream d ; shader nosuch n ;", "t", d);
  EXPECT_FALSE(ss.compile(*g, d)); // a missing shader
}

TEST(GroupGlobals, GlobalsRead) {
  ShadingSystem ss;
  DiagnosticList d;
  ASSERT_TRUE(ss.add_shader_ir("g", R"(lobe-ir 1
surface g
symbols
  global float u
  global normal N
  global closure Ci
  local float x
  const string $f = "%g\n"
main
  Dx x u
  printf $f x
end
)",
                               d));
  auto grp = ss.parse_group("shader g l ;", "t", d);
  auto mat = ss.compile(*grp, d);
  ASSERT_TRUE(mat);
  uint64_t m = mat->globals_read();
  auto bit = [&](const char* name) {
    for (size_t i = 0; i < std::size(kGlobalFields); ++i)
      if (!std::strcmp(kGlobalFields[i].name, name)) return (m >> i) & 1;
    return uint64_t(99);
  };
  EXPECT_EQ(bit("u"), 1u);
  EXPECT_EQ(bit("dudx"), 1u); // Dx(u) reads u's derivatives
  EXPECT_EQ(bit("N"), 0u);
  EXPECT_EQ(bit("P"), 0u);
  EXPECT_EQ(m & Material::kReadsRaytype, 0u);
}

// A group that calls raytype() says so (Material::kReadsRaytype: its closure may differ by the
// ray that hit, so a renderer that shades a point as another ray would, light paths, must not).
TEST(GroupGlobals, RaytypeCallsAreNoted) {
  ShadingSystem ss;
  DiagnosticList d;
  ASSERT_TRUE(ss.add_shader_source(
      "rt", "surface rt() { Ci = raytype(\"camera\") ? diffuse(N) : 0.5 * diffuse(N); }", "rt.osl",
      d))
      << (d.empty() ? "" : d[0].text);
  auto grp = ss.parse_group("shader rt l ;", "t", d);
  auto mat = ss.compile(*grp, d);
  ASSERT_TRUE(mat);
  EXPECT_NE(mat->globals_read() & Material::kReadsRaytype, 0u);
}

// Material::kUniform: set for a group whose result is the same at every point of a shape and
// for every ray (a constant emitter, even one that divides by surfacearea(), even across
// layers), unset as soon as anything may vary or has an effect.
TEST(GroupGlobals, UniformGroupsAreNoted) {
  struct Case {
    const char* name;
    const char* source;
    bool uniform;
  } cases[] = {
      {"k_const",
       "surface k_const(float power = 2, color Cs = 1) {"
       " Ci = power / (M_PI * surfacearea()) * Cs * emission(); }",
       true},
      {"k_branch", "surface k_branch(int on = 1) { if (on > 0) Ci = emission(); else Ci = 0; }",
       true},
      {"k_P", "surface k_P() { Ci = P[0] * emission(); }", false},
      {"k_N", "surface k_N() { Ci = diffuse(N); }", false},
      {"k_back", "surface k_back() { Ci = backfacing() ? 0 : emission(); }", false},
      {"k_ray", "surface k_ray() { Ci = raytype(\"camera\") ? emission() : 0; }", false},
      {"k_print", "surface k_print() { printf(\"x\\n\"); Ci = emission(); }", false},
      {"k_tex", "surface k_tex() { Ci = texture(\"nosuch.exr\", 0.5, 0.5) * emission(); }", false},
      {"k_attr", "surface k_attr() { float a = 1; getattribute(\"a\", a); Ci = a * emission(); }",
       false},
      {"k_user", "surface k_user(float k = 1 [[ int lockgeom = 0 ]]) { Ci = k * emission(); }",
       false},
  };
  for (const Case& c : cases) {
    ShadingSystem ss;
    DiagnosticList d;
    ASSERT_TRUE(ss.add_shader_source(c.name, c.source, std::string(c.name) + ".osl", d))
        << c.name << ": " << (d.empty() ? "" : d[0].text);
    auto grp = ss.parse_group(std::string("shader ") + c.name + " l ;", "t", d);
    auto mat = ss.compile(*grp, d);
    ASSERT_TRUE(mat) << c.name;
    EXPECT_EQ((mat->globals_read() & Material::kUniform) != 0, c.uniform) << c.name;
  }
  // Two layers: uniform only if the upstream one is too.
  for (bool up_uniform : {true, false}) {
    ShadingSystem ss;
    DiagnosticList d;
    ASSERT_TRUE(ss.add_shader_source("up",
                                     up_uniform ? "shader up(output float k = 0) { k = 3; }"
                                                : "shader up(output float k = 0) { k = u; }",
                                     "up.osl", d));
    ASSERT_TRUE(ss.add_shader_source("down", "surface down(float k = 1) { Ci = k * emission(); }",
                                     "down.osl", d));
    auto grp = ss.parse_group("shader up a ; shader down b ; connect a.k b.k ;", "t", d);
    auto mat = ss.compile(*grp, d);
    ASSERT_TRUE(mat);
    EXPECT_EQ((mat->globals_read() & Material::kUniform) != 0, up_uniform);
  }
}

// String compares of constants fold by content when the group is specialised (constant
// folding compares strings, so no op is hidden from it), and give OSL's results. OSL 1.13.12:
//   surface strcmp(string mode = "plain", output int same = 0, output int differ = 0,
//                  output int lit = 0) { same = mode == "fancy"; differ = mode != "fancy";
//     lit = "a" == "b"; printf("same %d differ %d lit %d\n", same, differ, lit); }
//   testshade strcmp                     -> same 0 differ 1 lit 0
//   testshade --param mode fancy strcmp  -> same 1 differ 0 lit 0 (also at -O0)
const char* kStrcmp = R"(lobe-ir 1
surface strcmp
symbols
  param string mode = "plain"
  oparam int same = 0
  oparam int differ = 0
  oparam int lit = 0
  const string $fancy = "fancy"
  const string $a = "a"
  const string $b = "b"
  const string $fmt = "same %d differ %d lit %d\n"
main
  useparam mode
  eq same mode $fancy
  neq differ mode $fancy
  eq lit $a $b
  printf $fmt same differ lit
end
)";

TEST_F(Groups, StringComparesOfConstantsFold) {
  DiagnosticList d;
  ASSERT_TRUE(ss.add_shader_ir("strcmp", kStrcmp, d)) << d[0].text;
  EXPECT_EQ(both("shader strcmp s ;"), "same 0 differ 1 lit 0\n");
  EXPECT_EQ(both("param string mode \"fancy\" ; shader strcmp s ;"), "same 1 differ 0 lit 0\n");
  // Specialised, the compares are constants: no eq/neq op is left.
  ir::ParseResult src = ir::parse(kStrcmp);
  ASSERT_TRUE(src.shader);
  auto g = ss.parse_group("param string mode \"fancy\" ; shader strcmp s ;", "t", d);
  ASSERT_TRUE(g);
  group::GroupBuild built;
  ASSERT_TRUE(group::build_group(*g, {&*src.shader}, true, built, d));
  ASSERT_EQ(built.shaders.size(), 1u);
  for (const ir::Op& op : built.shaders[0]->ops)
    EXPECT_TRUE(op.opcode != ir::Opcode::Eq && op.opcode != ir::Opcode::Neq)
        << ir::print(*built.shaders[0]);
}

} // namespace

namespace {

// One compiled material shaded from several threads at once, each with its own context; and a
// material that outlives its ShadingSystem.
TEST(GroupThreads, ConcurrentShadingAndLifetime) {
  std::shared_ptr<const Material> mat;
  {
    ShadingSystem ss;
    DiagnosticList d;
    ASSERT_TRUE(ss.add_shader_ir("sq", R"(lobe-ir 1
surface sq
symbols
  global float u
  oparam float r = 0
  const string $f = "%g\n"
main
  mul r u u
  printf $f r
end
)",
                                 d));
    auto g = ss.parse_group("shader sq l ;", "t", d);
    mat = ss.compile(*g, d);
    ASSERT_TRUE(mat);
  } // the ShadingSystem is gone; the material keeps its JIT and strings alive
  std::vector<std::thread> threads;
  std::vector<std::string> outputs(4);
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      ShadingContext ctx;
      for (int i = 0; i < 100; ++i) {
        ShaderGlobals sg{};
        sg.context = &ctx;
        sg.u = float(t + 1);
        mat->shade(sg);
      }
      outputs[size_t(t)] = ctx.output.substr(0, ctx.output.find('\n'));
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(outputs, (std::vector<std::string>{"1", "4", "9", "16"}));
}

} // namespace

namespace {

// compile() from several threads at once: distinct instance values, one shared cache.
TEST(GroupThreads, ConcurrentCompiles) {
  ShadingSystem ss;
  DiagnosticList d;
  ASSERT_TRUE(ss.add_shader_ir("scaled", R"(lobe-ir 1
surface scaled
symbols
  global float u
  param float k = 1
  oparam float r = 0
main
  mul r u k
end
)",
                               d));
  std::vector<std::thread> threads;
  std::vector<float> results(8, -1);
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&, t] {
      DiagnosticList diags;
      auto g = ss.parse_group("param float k " + std::to_string(t % 4) + " ; shader scaled l ;",
                              "t", diags);
      auto mat = ss.compile(*g, diags);
      if (!mat) return;
      ShadingContext ctx;
      ShaderGlobals sg{};
      sg.context = &ctx;
      sg.u = 2;
      mat->shade(sg);
      std::vector<float> out;
      if (mat->read_output(ctx, "l", "r", out)) results[size_t(t)] = out[0];
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(results, (std::vector<float>{0, 2, 4, 6, 0, 2, 4, 6}));
}

} // namespace

namespace {

// An error found while generating code names its place as the front end does,
// `file:line:col: error: ...` (from the op's @loc), or the shader when the op has none.
TEST(GroupErrors, CodegenErrorsNameTheirPlace) {
  const char* body = R"(lobe-ir 1
surface bad
symbols
  global normal N
  global closure Ci
  const string $c0 = "nosuch"
main
  closure Ci $c0 N%s
end
)";
  for (bool located : {true, false}) {
    ShadingSystem ss;
    DiagnosticList d;
    char text[512];
    std::snprintf(text, sizeof text, body, located ? " @bad.osl:3:8" : "");
    ASSERT_TRUE(ss.add_shader_ir("bad", text, d));
    auto g = ss.parse_group("shader bad layer ;", "t", d);
    ASSERT_TRUE(g);
    DiagnosticList diags;
    EXPECT_EQ(ss.compile(*g, diags), nullptr);
    ASSERT_EQ(diags.size(), 1u);
    EXPECT_EQ(diags[0].text, located ? "bad.osl:3:8: error: closure: unknown closure 'nosuch'"
                                     : "bad: error: closure: unknown closure 'nosuch'");
    // The same, structured.
    EXPECT_EQ(diags[0].id, "codegen");
    EXPECT_EQ(diags[0].file, located ? "bad.osl" : "bad");
    EXPECT_EQ(diags[0].line, located ? 3 : 0);
    EXPECT_EQ(diags[0].column, located ? 8 : 0);
    EXPECT_EQ(diags[0].message, "closure: unknown closure 'nosuch'");
  }
}

} // namespace

// The ShadingSystem's search path is include_dirs in order (then the current directory): the
// folder given first wins over a later one (a scene's folder over stdlib_shaders/), and an .osl
// over an older .lir in the same folder (edited since it was compiled).
TEST(ShaderLookup, IncludeDirsInOrder) {
  namespace fs = std::filesystem;
  fs::path root = fs::temp_directory_path() / ("lobe_order_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "mine");
  fs::create_directories(root / "lib");
  std::ofstream(root / "mine" / "m.osl") << "surface m(output float mine = 1) { Ci = 0; }\n";
  std::ofstream(root / "lib" / "m.osl") << "surface m(output float lib = 1) { Ci = 0; }\n";
  std::ofstream(root / "mine" / "m.lir") << "not IR at all\n";
  fs::last_write_time(root / "mine" / "m.lir",
                      fs::last_write_time(root / "mine" / "m.osl") - std::chrono::seconds(10));
  for (bool mine_first : {true, false}) {
    ShadingSystem ss;
    ss.options().include_dirs = {(root / (mine_first ? "mine" : "lib")).string(),
                                 (root / (mine_first ? "lib" : "mine")).string()};
    ShaderGroup g;
    g.layers.push_back({"m", "l", {}});
    DiagnosticList diags;
    auto mat = ss.compile(g, diags);
    ASSERT_TRUE(mat) << (diags.empty() ? "" : diags[0].text);
    EXPECT_EQ(mat->output_info("l", "mine").has_value(), mine_first);
    EXPECT_EQ(mat->output_info("l", "lib").has_value(), !mine_first);
  }
  fs::remove_all(root);
}

// A renderer plugin gets the compiler's diagnostics structured, through the public API: severity,
// id, file, line, column and message, besides the caret form a command line prints.
TEST(GroupErrors, CompilerDiagnosticsAreStructured) {
  ShadingSystem ss;
  DiagnosticList d;
  EXPECT_FALSE(
      ss.add_shader_source("bad", "surface bad() {\n  Ci = nope * diffuse(N);\n}\n", "bad.osl", d));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].severity, Diagnostic::Severity::Error);
  EXPECT_EQ(d[0].id, "err_undeclared");
  EXPECT_EQ(d[0].file, "bad.osl");
  EXPECT_EQ(d[0].line, 2);
  EXPECT_EQ(d[0].column, 8);
  EXPECT_EQ(d[0].message, "use of undeclared identifier 'nope'");
  EXPECT_EQ(d[0].text, "bad.osl:2:8: error: use of undeclared identifier 'nope'\n"
                       "  Ci = nope * diffuse(N);\n"
                       "       ^~~~\n");
  // A shader the search does not find: one line, with its id.
  auto g = ss.parse_group("shader no_such_shader_anywhere layer ;", "t", d);
  ASSERT_TRUE(g);
  DiagnosticList missing;
  EXPECT_EQ(ss.compile(*g, missing), nullptr);
  ASSERT_FALSE(missing.empty());
  EXPECT_EQ(missing[0].id, "err_shader_not_found");
  EXPECT_EQ(missing[0].text, "error: shader 'no_such_shader_anywhere' not found");
  EXPECT_EQ(missing[0].line, 0);
  // The runtime's own diagnostics carry ids too (docs/diagnostics.md): group text.
  DiagnosticList syntax;
  EXPECT_FALSE(ss.parse_group("shader m l ;\nbogus x ;", "g.txt", syntax));
  ASSERT_EQ(syntax.size(), 1u);
  EXPECT_EQ(syntax[0].id, "group_syntax");
  EXPECT_EQ(syntax[0].file, "g.txt");
  EXPECT_EQ(syntax[0].line, 2);
  EXPECT_EQ(syntax[0].message, "expected `param`, `shader` or `connect`, found `bogus`");
  EXPECT_EQ(syntax[0].text, "g.txt:2: error: " + syntax[0].message);
  // ... and so do group building's, rows of the same table (compiler/diag/diag_ids.cpp): a
  // connection from a missing layer, its message apart from its text.
  DiagnosticList added;
  ASSERT_TRUE(ss.add_shader_source("tint", "surface tint(color Cs = 1) { Ci = Cs * diffuse(N); }",
                                   "tint.osl", added));
  auto conn = ss.parse_group("shader tint a ;\nshader tint b ;\nconnect x.Cs b.Cs ;", "c", d);
  ASSERT_TRUE(conn);
  DiagnosticList connect;
  EXPECT_EQ(ss.compile(*conn, connect), nullptr);
  ASSERT_EQ(connect.size(), 1u);
  EXPECT_EQ(connect[0].id, "connect_layer");
  EXPECT_EQ(connect[0].severity, Diagnostic::Severity::Error);
  EXPECT_EQ(connect[0].message, "ConnectShaders: source layer \"x\" not found");
  EXPECT_EQ(connect[0].text, "error: " + connect[0].message);
  EXPECT_STREQ(diag::diag_name(diag::DiagId::connect_layer), "connect_layer");
}

// CompileOptions::colorspace picks the colour system (part of the cache key); an unknown name
// compiles as Rec709, and colorspace_error words it as OSL does. Values: OSL 1.13.12,
// printf("%.9g\n", luminance(color(.1, .7, .2) + k)) with k = 0 under
// `testshade -g 1 1 --colorspace NAME` (u is 0 here); the message as testshade prints it.
TEST(ColorSpace, OptionSelectsTheSystemAndKeysTheCache) {
  ShadingSystem ss;
  DiagnosticList d;
  ASSERT_TRUE(ss.add_shader_source(
      "lum", "shader lum() { printf(\"%.9g\\n\", luminance(color(.1, .7, .2) + u)); }", "lum.osl",
      d));
  EXPECT_EQ(run_group(ss, "shader lum l ;", true).output, "0.536424339\n");
  ss.options().colorspace = "ACEScg";
  EXPECT_EQ(run_group(ss, "shader lum l ;", true).output, "0.509817958\n");
  ss.options().colorspace = "Rec2020";
  EXPECT_EQ(run_group(ss, "shader lum l ;", true).output, "0.536424339\n");
  EXPECT_EQ(colorspace_error("Rec2020"), "Unknown color space \"Rec2020\"");
  EXPECT_EQ(colorspace_error("ACEScg"), "");
  EXPECT_EQ(colorspace_error(""), "");
  EXPECT_EQ(colorspace_names().front(), "Rec709");
}

// A shader is found by the name its source declares when no file has that name (oslc names its
// .oso so: raytype-envmap.osl declaring raytype_envmap is raytype_envmap.oso to OSL).
TEST(ShaderLookup, ByDeclaredName) {
  EXPECT_EQ(driver::declared_shader_name("// surface wrong()\n/* shader no() */ #define X \"a\"\n"
                                         "surface\n  raytype_envmap [[ string help = \"x\" ]] ()"
                                         " { Ci = 0; }"),
            "raytype_envmap");
  EXPECT_EQ(driver::declared_shader_name("float f(float shader) { return shader; }"), "");
  namespace fs = std::filesystem;
  fs::path d = fs::temp_directory_path() / ("lobe_lookup_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "raytype-envmap.osl") << "surface raytype_envmap() { Ci = 0; }\n";
  std::ofstream(d / "other.osl") << "shader other_name() {}\n";
  CompileOptions o;
  o.include_dirs = {d.string()};
  EXPECT_EQ(group::find_shader_file("raytype_envmap", o), (d / "raytype-envmap.osl").string());
  EXPECT_EQ(group::find_shader_file("other", o), (d / "other.osl").string()); // file name first
  EXPECT_EQ(group::find_shader_file("nothing_declares_this", o), "");
  ShadingSystem ss;
  ss.options().include_dirs = {d.string()};
  ShaderGroup g;
  g.layers.push_back({"raytype_envmap", "l", {}});
  DiagnosticList diags;
  EXPECT_TRUE(ss.compile(g, diags)) << (diags.empty() ? "" : diags[0].text);
  fs::remove_all(d);
}

// The closure builders (lobe_closure_component/_mul/_add) are linked into shader code from the
// shadeop bitcode at -O2 and inlined; -O1 calls the native library. Both build the same tree
// with the same weights and parameters, fold zero weights alike, and drop the same components
// when the arena runs out (counted in closures_dropped), for arenas from roomy to none.
namespace {
std::string closure_tree(const ClosureNode* c) {
  if (!c) return "null";
  if (c->id == kClosureAdd) {
    auto* a = static_cast<const ClosureAdd*>(c);
    return "(" + closure_tree(a->a) + " + " + closure_tree(a->b) + ")";
  }
  if (c->id == kClosureMul) {
    auto* m = static_cast<const ClosureMul*>(c);
    char w[96];
    std::snprintf(w, sizeof w, "[%.9g %.9g %.9g]*", m->weight.x, m->weight.y, m->weight.z);
    return w + closure_tree(m->closure);
  }
  // The component and its parameters as Lobe prints them (weight 1 here: the nodes above it
  // are printed by this function, a weight set in place by closure_to_string).
  return "{" + closure_to_string(c) + "}";
}
} // namespace

TEST(ClosureBuilders, InlinedAtO2BuildWhatTheNativeOnesBuild) {
  ShadingSystem ss;
  DiagnosticList d;
  ASSERT_TRUE(ss.add_shader_source("layered",
                                   "surface layered(float k = 1) {\n"
                                   "  closure color a = (u - 0.25) * k * oren_nayar(N, v);\n"
                                   "  closure color b = color(u, 0, v) * translucent(N);\n"
                                   "  Ci = a + 0.5 * b + v * microfacet(\"ggx\", N, u, 1.5, 0)"
                                   " + 0 * diffuse(N);\n"
                                   "}\n",
                                   "layered.osl", d))
      << (d.empty() ? "" : d[0].text);
  auto g = ss.parse_group("shader layered l ;", "g", d);
  ASSERT_TRUE(g);
  std::shared_ptr<const Material> mats[2];
  for (int i = 0; i < 2; ++i) {
    ss.options().opt_level = i == 0 ? 1 : 2; // specialised alike: only the builders differ
    ss.options().specialize = true;
    mats[i] = ss.compile(*g, d);
    ASSERT_TRUE(mats[i]) << (d.empty() ? "" : d[0].text);
  }
  int dropped_somewhere = 0;
  for (size_t arena : {size_t(4096), size_t(100), size_t(48), size_t(0)})
    for (float u : {0.0f, 0.25f, 0.6f})
      for (float v : {0.0f, 0.3f}) {
        std::string tree[2];
        uint64_t dropped[2];
        for (int i = 0; i < 2; ++i) {
          ShadingContext ctx(arena);
          ShaderGlobals sg{};
          sg.context = &ctx;
          sg.u = u;
          sg.v = v;
          sg.N = sg.Ng = {0, 0, 1};
          mats[i]->shade(sg);
          tree[i] = closure_tree(sg.Ci);
          dropped[i] = ctx.closures_dropped;
        }
        EXPECT_EQ(tree[0], tree[1]) << "arena " << arena << " u " << u << " v " << v;
        EXPECT_EQ(dropped[0], dropped[1]) << "arena " << arena << " u " << u << " v " << v;
        dropped_somewhere += dropped[1] > 0;
        if (arena == 4096 && u == 0.6f && v == 0.3f) { // all three terms, none dropped
          size_t adds = 0;
          for (size_t at = tree[1].find(" + "); at != std::string::npos;
               at = tree[1].find(" + ", at + 1))
            ++adds;
          EXPECT_EQ(adds, 2u) << tree[1];
        }
        if (arena == 0) {
          EXPECT_EQ(tree[1], "null");
        }
      }
  EXPECT_GT(dropped_somewhere, 0);
}

// OSL -O2 elides outputs nothing reads (opt_elide_unconnected_outputs): with renderer outputs
// named, an output no connection takes and no renderer output names is not computed (its
// printf-free computation removed), while one that is named, or connected downstream, is; -O1
// and a group without renderer outputs compute every output.
TEST(GroupOutputs, UnreadOutputsAreNotComputedAtO2) {
  ShadingSystem ss;
  DiagnosticList d;
  ASSERT_TRUE(ss.add_shader_source("two",
                                   "shader two(output float cheap = 0, output float costly = 0,"
                                   " output float fed = 0) {\n"
                                   "  cheap = 2;\n  costly = sqrt(u + 16);\n  fed = u - 6;\n}\n",
                                   "two.osl", d));
  ASSERT_TRUE(ss.add_shader_source(
      "sink", "shader sink(float x = 0, output float y = 0) { y = x; }", "sink.osl", d));
  auto run = [&](int opt, std::vector<std::string> outputs) {
    auto g = ss.parse_group("shader two a ; shader sink b ; connect a.fed b.x ;", "g", d);
    EXPECT_TRUE(g);
    g->renderer_outputs = outputs;
    ss.options().opt_level = opt;
    auto mat = ss.compile(*g, d);
    EXPECT_TRUE(mat) << (d.empty() ? "" : d[0].text);
    ShadingContext ctx;
    ShaderGlobals sg{};
    sg.context = &ctx;
    sg.u = 9; // costly = 5
    mat->shade(sg);
    std::vector<float> out;
    std::string r;
    for (const char* o : {"cheap", "costly", "fed"}) {
      if (!mat->read_output(ctx, "a", o, out) || out.size() != 1) return std::string("missing");
      r += std::to_string(int(out[0]));
    }
    EXPECT_TRUE(mat->read_output(ctx, "b", "y", out));
    return r + "|" + std::to_string(int(out.at(0)));
  };
  EXPECT_EQ(run(2, {"a.cheap", "b.y"}), "203|3"); // costly unread: its default stays
  EXPECT_EQ(run(2, {"a.cheap", "a.costly", "b.y"}), "253|3");
  EXPECT_EQ(run(1, {"a.cheap", "b.y"}), "253|3");
  EXPECT_EQ(run(2, {}), "253|3");
}

// A component read only by the op weighting it gets the weight in place (codegen's
// lobe_closure_weight: no ClosureMul node); one read twice, as a variable or as a temporary the
// optimiser shares, keeps a node per weight, so each use has its own. Either way the tree's
// terms and weights are those of the source, at every -O level.
TEST(ClosureBuilders, FreshComponentsAreWeightedInPlaceSharedOnesAreNot) {
  ShadingSystem ss;
  DiagnosticList d;
  ASSERT_TRUE(ss.add_shader_source("w",
                                   "surface w(int mode = 0) {\n"
                                   "  closure color c = diffuse(N);\n"
                                   "  if (mode == 0) Ci = 0.5 * translucent(N) + u * diffuse(N);\n"
                                   "  else if (mode == 1) Ci = 0.5 * c + 0.25 * c;\n"
                                   "  else Ci = 0.5 * diffuse(N) + 0.25 * diffuse(N);\n"
                                   "}\n",
                                   "w.osl", d))
      << (d.empty() ? "" : d[0].text);
  for (int opt : {0, 1, 2})
    for (int mode : {0, 1, 2}) {
      auto g = ss.parse_group("param int mode " + std::to_string(mode) + " ; shader w l ;", "g", d);
      ASSERT_TRUE(g);
      ss.options().opt_level = opt;
      auto mat = ss.compile(*g, d);
      ASSERT_TRUE(mat) << (d.empty() ? "" : d[0].text);
      ShadingContext ctx;
      ShaderGlobals sg{};
      sg.context = &ctx;
      sg.u = 0.75f;
      sg.N = sg.Ng = {0, 0, 1};
      mat->shade(sg);
      std::string t = closure_tree(sg.Ci);
      // Weights multiply down the tree: a node [w]* over a component, or its own weight.
      auto weight_of = [](const ClosureNode* c, float& w) {
        w = 1;
        while (c && c->id == kClosureMul) {
          w *= static_cast<const ClosureMul*>(c)->weight.x;
          c = static_cast<const ClosureMul*>(c)->closure;
        }
        if (c && c->id >= 0) w *= static_cast<const ClosureComponent*>(c)->weight.x;
        return c ? c->id : -100;
      };
      ASSERT_TRUE(sg.Ci && sg.Ci->id == kClosureAdd) << t;
      auto* add = static_cast<const ClosureAdd*>(sg.Ci);
      float wa, wb;
      int ia = weight_of(add->a, wa), ib = weight_of(add->b, wb);
      const float want_b = mode == 0 ? 0.75f : 0.25f;
      EXPECT_EQ(wa, 0.5f) << "opt " << opt << " mode " << mode << ": " << t;
      EXPECT_EQ(wb, want_b) << "opt " << opt << " mode " << mode << ": " << t;
      EXPECT_GE(ia, 0) << t;
      EXPECT_GE(ib, 0) << t;
      if (mode == 0) { // no ClosureMul node
        EXPECT_EQ(t.find("]*"), std::string::npos) << t;
      }
      if (mode == 1) { // two nodes over the one component
        EXPECT_NE(add->a, add->b);
      }
    }
}

// Machine code from the disk cache (runtime/jit/disk_cache.h): a material compiled by another
// ShadingSystem (whose interned strings, environment and declared closures live elsewhere, as in
// another run) loads the cached object, binds its names to this one's objects and computes
// exactly what the compiled one does; a corrupt entry is rebuilt; LOBE_CACHE_DIR=off compiles.
namespace {

// String constants (compared, formatted and printed), a colour-space conversion and a closure:
// every kind of host reference the code makes.
const char* kCachedShader = R"(
shader cached(float k = 2, output color Cout = 0) {
  string mode = k > 1 ? "big" : "small";
  if (mode == "big") Cout = transformc("hsv", "rgb", color(0.25, 0.5, k / 4));
  printf("%s %s %g\n", mode, format("%d-%s", 7, "x"), Cout);
  Ci = Cout * diffuse(N) + 0.5 * oren_nayar(N, 0.3);
}
)";

struct CachedRun {
  std::string output, closure;
  bool from_disk = false;
};

CachedRun run_cached(int opt) {
  ShadingSystem ss; // fresh each time: nothing shared in memory with an earlier compile
  DiagnosticList d;
  EXPECT_TRUE(ss.add_shader_source("cached", kCachedShader, "cached.osl", d))
      << (d.empty() ? "" : d[0].text);
  GroupRun r = run_group(ss, "param float k 3 ; shader cached c ;", true, opt);
  if (!r.mat) return {};
  ShadingContext ctx;
  ShaderGlobals sg{};
  sg.N = {0, 0, 1};
  sg.context = &ctx;
  r.mat->shade(sg);
  return {r.output, closure_to_string(sg.Ci), r.mat->stats().object_from_disk};
}

} // namespace

TEST(MaterialDiskCache, HitRebindsHostObjectsCorruptEntryRebuiltOffSwitch) {
  char dir[] = "/tmp/lobe_material_cache_XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  setenv("LOBE_CACHE_DIR", dir, 1);
  for (int opt : {0, 2}) {
    CachedRun first = run_cached(opt);
    EXPECT_FALSE(first.from_disk);
    // OSL's hsv (0.25, 0.5, 0.75) is rgb (0.5625, 0.75, 0.375).
    EXPECT_EQ(first.output, "big 7-x 0.5625 0.75 0.375\n") << opt;
    EXPECT_NE(first.closure.find("diffuse"), std::string::npos) << first.closure;
    EXPECT_NE(first.closure.find("oren_nayar"), std::string::npos) << first.closure;
    CachedRun second = run_cached(opt);
    EXPECT_TRUE(second.from_disk) << opt;
    EXPECT_EQ(second.output, first.output);
    EXPECT_EQ(second.closure, first.closure);
  }
  int entries = 0;
  for (const auto& f : std::filesystem::directory_iterator(dir)) {
    ++entries;
    std::fstream io(f.path(), std::ios::in | std::ios::out | std::ios::binary);
    const auto near_end = std::streamoff(std::filesystem::file_size(f.path()) - 40);
    char c = 0;
    io.seekg(near_end);
    io.get(c);
    io.seekp(near_end);
    io.put(char(c ^ 0x5a)); // a changed byte in the object
  }
  EXPECT_EQ(entries, 2); // one per optimisation level
  CachedRun rebuilt = run_cached(2);
  EXPECT_FALSE(rebuilt.from_disk);
  EXPECT_EQ(rebuilt.output, "big 7-x 0.5625 0.75 0.375\n");
  EXPECT_TRUE(run_cached(2).from_disk); // replaced by the rebuild

  setenv("LOBE_CACHE_DIR", "off", 1);
  EXPECT_FALSE(run_cached(2).from_disk);
  unsetenv("LOBE_CACHE_DIR");
  std::filesystem::remove_all(dir);
}

// The lowering corpus: each tests/lower/*.osl goes through the whole pipeline (front end,
// lowering, verifier) at -O0 and -O1; its IR text must read back to the same text; its
// `// ir-has: text`, `// ir-not: text` and `// ir-count: opcode N` lines are checked against
// the -O0 IR; and when `<name>.expected` exists, its printed output when run through the
// ShadingSystem (specialisation off and on) must equal that hand-computed file.
// Also every shader shipped in the repository (materials corpus, stdlib, benchmarks, the
// execution corpus) lowers to verified IR, and every builtin the type checker knows lowers.
#include "grid.h"
#include "ir/opcodes.h"
#include "ir/parser.h"
#include "ir/printer.h"
#include "lobe/shadingsys.h"
#include "lower/pipeline.h"
#include "sema/builtins.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = LOBE_SOURCE_DIR;
const fs::path kCorpus = kRoot / "tests" / "lower";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> osl_files(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".osl") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

std::string test_name(const std::string& path) {
  std::string n = fs::relative(path, kRoot).string();
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

// The values after `// key:` on each line that has one.
std::vector<std::string> directives(const std::string& text, const std::string& key) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string tag = "// " + key + ":";
  for (std::string line; std::getline(in, line);) {
    size_t at = line.find(tag);
    if (at == std::string::npos) continue;
    std::string v = line.substr(at + tag.size());
    v.erase(0, v.find_first_not_of(' '));
    out.push_back(v);
  }
  return out;
}

lobe::lower::PipelineResult compile(const std::string& path, bool optimize) {
  lobe::lower::PipelineOptions o;
  o.optimize = optimize;
  o.frontend.include_dirs.push_back(fs::path(path).parent_path().string());
  return lobe::lower::compile_osl({path, std::nullopt}, o);
}

// Compiles at -O0 and -O1; both must succeed, verify, and round-trip through the IR text.
std::string compile_checked(const std::string& path) {
  std::string o0;
  for (bool opt : {false, true}) {
    lobe::lower::PipelineResult r = compile(path, opt);
    EXPECT_TRUE(r.ok) << path << (opt ? " -O1" : " -O0") << ":\n" << r.diagnostics;
    if (!r.ok) return "";
    std::string text = lobe::ir::print(*r.shader);
    lobe::ir::ParseResult back = lobe::ir::parse(text);
    EXPECT_TRUE(back.shader.has_value()) << back.error.line << ": " << back.error.message;
    if (back.shader) {
      EXPECT_EQ(lobe::ir::print(*back.shader), text) << path;
    }
    if (!opt) o0 = text;
  }
  return o0;
}

int count_ops(const std::string& ir, const std::string& opcode) {
  std::istringstream in(ir.substr(ir.find("\nmain\n")));
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string w;
    words >> w;
    n += w == opcode;
  }
  return n;
}

// The IR without its `@file:line:col` source locations, so that `ir-not` looks at ops and
// symbols only (a checkout path may contain any word).
std::string without_locations(const std::string& ir) {
  std::string out;
  out.reserve(ir.size());
  for (size_t i = 0; i < ir.size(); ++i) {
    if (ir[i] == '@' && (i == 0 || ir[i - 1] == ' ')) {
      while (i < ir.size() && ir[i] != ' ' && ir[i] != '\n') ++i;
      if (i < ir.size()) out += ir[i];
      continue;
    }
    out += ir[i];
  }
  return out;
}

// ---- the corpus ----------------------------------------------------------------------------

class LowerCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(LowerCorpus, LowersVerifiesAndMeetsIrExpectations) {
  std::string text = slurp(GetParam());
  std::string ir = compile_checked(GetParam());
  ASSERT_FALSE(ir.empty());
  for (const std::string& s : directives(text, "ir-has"))
    EXPECT_NE(ir.find(s), std::string::npos) << "missing '" << s << "' in\n" << ir;
  std::string ir_ops = without_locations(ir);
  for (const std::string& s : directives(text, "ir-not"))
    EXPECT_EQ(ir_ops.find(s), std::string::npos) << "unexpected '" << s << "' in\n" << ir;
  for (const std::string& s : directives(text, "ir-count")) {
    std::istringstream in(s);
    std::string op;
    int n = -1;
    in >> op >> n;
    EXPECT_EQ(count_ops(ir, op), n) << "count of '" << op << "' ops in\n" << ir;
  }
}

// Runs the shader over its `// shade: -g W H` grid and returns everything it printed.
std::string run(const std::string& path, int opt, std::string& error) {
  lobe::ShadingSystem ss;
  ss.options().opt_level = opt;
  ss.options().specialize = opt > 0;
  lobe::ShaderGroup g;
  g.layers.push_back({path, fs::path(path).stem().string(), {}});
  lobe::DiagnosticList diags;
  auto mat = ss.compile(g, diags);
  if (!mat) {
    for (auto& x : diags) error += x.text + "\n";
    return "";
  }
  lobe::group::GridSpec grid;
  std::vector<std::string> d = directives(slurp(path), "shade");
  if (!d.empty()) {
    std::istringstream in(d[0]);
    for (std::string w; in >> w;)
      if (w == "-g") in >> grid.width >> grid.height;
  }
  lobe::ShadingContext ctx;
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < grid.width; ++x) {
      ctx.reset();
      lobe::ShaderGlobals sg = lobe::group::grid_globals(grid, x, y, &ctx);
      mat->shade(sg);
    }
  return ctx.output;
}

TEST_P(LowerCorpus, RunsToTheHandComputedOutput) {
  fs::path expected = fs::path(GetParam()).replace_extension(".expected");
  if (!fs::exists(expected)) GTEST_SKIP() << "no .expected file";
  std::string want = slurp(expected);
  for (int opt : {0, 2}) {
    std::string err;
    std::string got = run(GetParam(), opt, err);
    ASSERT_TRUE(err.empty()) << err;
    EXPECT_EQ(got, want) << "-O" << opt;
  }
}

INSTANTIATE_TEST_SUITE_P(Lower, LowerCorpus, ::testing::ValuesIn(osl_files(kCorpus)),
                         [](const auto& i) { return test_name(i.param); });

// ---- every shader in the repository ---------------------------------------------------------

std::vector<std::string> repository_shaders() {
  std::vector<std::string> all;
  for (const char* dir :
       {"tests/parse/materials", "stdlib_shaders", "bench/shaders", "tests/shade"})
    for (const std::string& f : osl_files(kRoot / dir)) all.push_back(f);
  return all;
}

class RepositoryShader : public ::testing::TestWithParam<std::string> {};

TEST_P(RepositoryShader, CompilesToVerifiedIr) {
  EXPECT_FALSE(compile_checked(GetParam()).empty());
}

INSTANTIATE_TEST_SUITE_P(Lower, RepositoryShader, ::testing::ValuesIn(repository_shaders()),
                         [](const auto& i) { return test_name(i.param); });

TEST(RepositoryShaders, TheMaterialAndStdlibCorporaAreThere) {
  EXPECT_GE(osl_files(kRoot / "stdlib_shaders").size(), 8u);
  EXPECT_GE(osl_files(kRoot / "tests" / "parse" / "materials").size(), 5u);
  EXPECT_EQ(osl_files(kRoot / "bench" / "shaders").size() >= 1, true);
}

// The benchmark material is what its name says: over 300 lines, with structs, helper
// functions, noise and several kinds of closure.
TEST(BenchMaterial, IsAThreeHundredLineMaterialThatLowers) {
  fs::path p = kRoot / "bench" / "shaders" / "material_300.osl";
  std::string text = slurp(p);
  EXPECT_GT(std::count(text.begin(), text.end(), '\n'), 300);
  lobe::lower::PipelineResult r = compile(p.string(), false);
  ASSERT_TRUE(r.ok) << r.diagnostics;
  std::string ir = lobe::ir::print(*r.shader);
  EXPECT_GE(count_ops(ir, "closure"), 5);
  EXPECT_GT(count_ops(ir, "noise") + count_ops(ir, "snoise") + count_ops(ir, "cellnoise"), 3);
  EXPECT_NE(ir.find("struct=Slab"), std::string::npos) << "no struct parameter/local";
}

// ---- front-end features the corpus once found missing ---------------------------------------

lobe::lower::PipelineResult compile_text(const std::string& text, bool optimize = false) {
  lobe::lower::PipelineOptions o;
  o.optimize = optimize;
  return lobe::lower::compile_osl({"gap.osl", text}, o);
}

// OSL overloads user functions by return type alone: the context's expected type chooses
// (`c = pick()` inlines the colour one), so f gets 1.5 and c gets (1, 2, 3).
TEST(FrontEnd, UserFunctionsOverloadedByReturnTypeOnly) {
  lobe::lower::PipelineResult r = compile_text(
      "float pick() { return 1.5; }\ncolor pick() { return color(1, 2, 3); }\n"
      "shader gap(output float f = 0, output color c = 0) { f = pick(); c = pick(); }\n",
      true);
  ASSERT_TRUE(r.ok) << r.diagnostics;
  std::string ir = lobe::ir::print(*r.shader);
  EXPECT_NE(ir.find("const float $c0 = 1.5"), std::string::npos) << ir;
  EXPECT_NE(ir.find("const color $c1 = 1 2 3"), std::string::npos) << ir;
  EXPECT_NE(ir.find("assign f $c0"), std::string::npos) << ir;
  EXPECT_NE(ir.find("assign c $c1"), std::string::npos) << ir;
}

// An unsized array parameter (`float a[] = {1, 2}`) stays unsized in the IR (`float[]`), so
// an instance value of another length fits; arraylength() is an op the runtime answers (after
// specialisation, from the instance value's length), not a constant 2.
TEST(FrontEnd, UnsizedArrayParameterStaysUnsized) {
  lobe::lower::PipelineResult r =
      compile_text("shader gap(float a[] = {1, 2}, output int n = 0) { n = arraylength(a); }\n");
  ASSERT_TRUE(r.ok) << r.diagnostics;
  std::string ir = lobe::ir::print(*r.shader);
  EXPECT_NE(ir.find("param float[] a = 1 2"), std::string::npos) << ir;
  EXPECT_NE(ir.find("arraylength n a"), std::string::npos) << ir;
}

// All-constant casts, constructors and arithmetic lower to one constant, with no temporaries
// for converted literals: color(1) * 0.5 + float(1) / 4 is the constant 0.75 0.75 0.75.
TEST(ConstantExpressions, LowerToOneConstant) {
  lobe::lower::PipelineResult r = compile_text(
      "shader k(output color c = 0, output int n = 0) { c = color(1) * 0.5 + float(1) / 4; "
      "n = -2 * 3; }\n");
  ASSERT_TRUE(r.ok) << r.diagnostics;
  std::string ir = lobe::ir::print(*r.shader);
  EXPECT_NE(ir.find("color $c0 = 0.75 0.75 0.75"), std::string::npos) << ir;
  EXPECT_NE(ir.find("int $c1 = -6"), std::string::npos) << ir;
  EXPECT_EQ(ir.find("temp"), std::string::npos) << ir;
  EXPECT_EQ(ir.find("mul"), std::string::npos) << ir;
}

// ---- builtins -------------------------------------------------------------------------------

// Every function in the type checker's builtin table has an IR opcode or a lowering of its own.
TEST(Builtins, EveryBuiltinHasALowering) {
  const std::set<std::string> lowered = {"radians", "degrees", "exit"};
  for (const lobe::sema::BuiltinSig& s : lobe::sema::builtins().all())
    EXPECT_TRUE(lobe::ir::opcode_from_name(s.name) || lowered.count(s.name)) << s.signature();
}

// ---- shading globals -------------------------------------------------------------------------

// One table (lobe/shading_globals.h) declares the globals to the type checker and places them
// in ShaderGlobals. The globals a shader may name are OSL's (the OSL specification's list, with
// their types); each reaches the IR as a global of that type, and has a ShaderGlobals member
// of that type's size (taken from the struct itself). Derivative fields are no globals to
// shaders; only P, I, N and Ci may be assigned.
TEST(Globals, TypeCheckerAndShaderGlobalsAgree) {
  const std::map<std::string, std::string> osl = {
      {"P", "point"},     {"I", "vector"},       {"N", "normal"},    {"Ng", "normal"},
      {"u", "float"},     {"v", "float"},        {"dPdu", "vector"}, {"dPdv", "vector"},
      {"dPdx", "vector"}, {"dPdy", "vector"},    {"dPdz", "vector"}, {"time", "float"},
      {"dtime", "float"}, {"dPdtime", "vector"}, {"Ps", "point"},    {"Ci", "closure"}};
  std::map<std::string, size_t> member_bytes;
#define LOBE_MEMBER_BYTES(member, ...) member_bytes[#member] = sizeof(lobe::ShaderGlobals::member);
  LOBE_SHADING_GLOBALS(LOBE_MEMBER_BYTES)
#undef LOBE_MEMBER_BYTES
  std::string body;
  int k = 0;
  for (const auto& [name, type] : osl)
    body += "  " + std::string(type == "closure" ? "closure color" : type) + " x" +
            std::to_string(k++) + " = " + name + ";\n";
  lobe::lower::PipelineResult r = compile_text("shader gap() {\n" + body + "}\n");
  ASSERT_TRUE(r.shader) << r.diagnostics;
  int globals = 0;
  for (const lobe::ir::Symbol& s : r.shader->symbols) {
    if (s.kind != lobe::ir::SymKind::Global) continue;
    ++globals;
    ASSERT_TRUE(osl.count(s.name)) << s.name;
    EXPECT_EQ(lobe::ir::to_string(s.type), osl.at(s.name)) << s.name;
    size_t bytes = s.type.base == lobe::ir::BaseType::Closure ? sizeof(void*)
                                                              : 4 * size_t(s.type.components());
    ASSERT_TRUE(member_bytes.count(s.name)) << s.name;
    EXPECT_EQ(member_bytes.at(s.name), bytes) << s.name;
    const lobe::GlobalField* f = nullptr;
    for (const lobe::GlobalField& g : lobe::kGlobalFields)
      if (s.name == g.name) f = &g;
    ASSERT_TRUE(f) << s.name;
    EXPECT_LE(f->offset + bytes, sizeof(lobe::ShaderGlobals)) << s.name;
  }
  EXPECT_EQ(globals, int(osl.size()));
  for (const char* hidden : {"dudx", "dvdy", "dIdx", "dPsdx", "raytype", "surfacearea"})
    EXPECT_FALSE(compile_text(std::string("shader gap() { printf(\"%g\", ") + hidden + "); }\n").ok)
        << hidden;
  // Every global may be written, as in oslc; all but P, I, N, Ci with oslc's warning.
  for (const auto& [name, type] : osl) {
    std::string value = type == "closure" ? "0" : type == "float" ? "1" : type + "(1)";
    lobe::lower::PipelineResult w =
        compile_text("shader gap() { " + name + " = " + value + "; }\n");
    EXPECT_TRUE(w.ok) << name << w.diagnostics;
    bool warned = w.diagnostics.find("cannot write to non-output parameter") != std::string::npos;
    EXPECT_EQ(warned, !(name == "P" || name == "I" || name == "N" || name == "Ci")) << name;
  }
}

// Ps has derivatives (dPsdx, dPsdy in ShaderGlobals); reading them once dereferenced a missing
// field. OSL 1.13.12, `testshade psd` of `shader psd() { printf("%g\n", Dx(Ps)); }`: "0 0 0".
TEST(Globals, DerivativesOfPs) {
  lobe::ShadingSystem ss;
  lobe::DiagnosticList d;
  ASSERT_TRUE(
      ss.add_shader_source("psd", "shader psd() { printf(\"%g\\n\", Dx(Ps)); }\n", "psd.osl", d))
      << (d.empty() ? "" : d[0].text);
  lobe::ShaderGroup g;
  g.layers.push_back({"psd", "l", {}});
  auto mat = ss.compile(g, d);
  ASSERT_TRUE(mat) << (d.empty() ? "" : d[0].text);
  lobe::ShadingContext ctx;
  lobe::ShaderGlobals sg{};
  sg.context = &ctx;
  mat->shade(sg);
  EXPECT_EQ(ctx.output, "0 0 0\n");
  sg.dPsdx = lobe::Vec3{1, 2, 3}; // Dx(Ps) is dPsdx, as Dx(P) is dPdx
  ctx.output.clear();
  mat->shade(sg);
  EXPECT_EQ(ctx.output, "1 2 3\n");
}

} // namespace

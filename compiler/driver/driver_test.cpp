// The compile driver: the one search order (search.h), IR text vs OSL source loading, and the
// structured diagnostics every stage reports (driver.h).
#include "driver/driver.h"

#include "ir/printer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace lobe::driver {
namespace {

namespace fs = std::filesystem;

// A scratch directory with a few files, removed afterwards.
struct TempDir {
  fs::path root;
  TempDir() {
    root = fs::temp_directory_path() /
           ("lobe_driver_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root);
    fs::create_directories(root);
  }
  ~TempDir() { fs::remove_all(root); }
  std::string put(const std::string& rel, const std::string& text) const {
    fs::path p = root / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
  std::string dir(const std::string& rel) const { return (root / rel).string(); }
};

const char* kMatte = "surface matte(float Kd = 0.5) { Ci = Kd * diffuse(N); }\n";

// The directory given first wins: a user's folder before the stdlib's, whatever holds the
// other.
TEST(Search, DirectoriesInOrder) {
  TempDir t;
  std::string mine = t.put("mine/matte.osl", kMatte);
  std::string lib = t.put("stdlib/matte.osl", kMatte);
  EXPECT_EQ(find_shader("matte", {t.dir("mine"), t.dir("stdlib")}), mine);
  EXPECT_EQ(find_shader("matte", {t.dir("stdlib"), t.dir("mine")}), lib);
  EXPECT_EQ(find_shader("matte.osl", {t.dir("mine"), t.dir("stdlib")}), mine); // named file
  EXPECT_EQ(find_shader("matte.oso", {t.dir("stdlib"), t.dir("mine")}), lib);  // .oso is .osl
  EXPECT_EQ(find_shader("nosuch", {t.dir("mine"), t.dir("stdlib")}), "");
}

// Within a directory name.osl comes before name.lir; a directory's .lir before a later
// directory's .osl (directories first).
TEST(Search, SourceBeforeIrWithinADirectory) {
  TempDir t;
  std::string osl = t.put("a/m.osl", kMatte);
  std::string lir = t.put("a/m.lir", "lobe-ir 1\n");
  std::string later = t.put("b/n.osl", kMatte);
  std::string first = t.put("a/n.lir", "lobe-ir 1\n");
  EXPECT_EQ(find_shader("m", {t.dir("a")}), osl);
  EXPECT_EQ(find_shader("m.lir", {t.dir("a")}), lir);
  EXPECT_EQ(find_shader("n", {t.dir("a"), t.dir("b")}), first);
}

// For shading, the compiled form comes first when it is at least as new as its source (what
// `lobe compile -DX` wrote is what runs, as testshade runs what oslc wrote); a source edited
// after it wins again. Compiling always starts from the source.
TEST(Search, CompiledFormWhenUpToDate) {
  TempDir t;
  std::string osl = t.put("a/m.osl", kMatte);
  std::string lir = t.put("a/m.lir", "lobe-ir 1\n");
  auto now = fs::file_time_type::clock::now();
  fs::last_write_time(osl, now - std::chrono::seconds(10));
  fs::last_write_time(lir, now);
  EXPECT_EQ(find_shader("m", {t.dir("a")}, Prefer::Compiled), lir);
  EXPECT_EQ(find_shader("m.oso", {t.dir("a")}, Prefer::Compiled), lir);
  EXPECT_EQ(find_shader("m", {t.dir("a")}, Prefer::Source), osl);
  EXPECT_EQ(find_shader("m.osl", {t.dir("a")}, Prefer::Compiled), osl); // a named file
  fs::last_write_time(osl, now + std::chrono::seconds(10));             // edited since
  EXPECT_EQ(find_shader("m", {t.dir("a")}, Prefer::Compiled), osl);
  std::string only = t.put("b/n.lir", "lobe-ir 1\n");
  EXPECT_EQ(find_shader("n", {t.dir("b")}, Prefer::Compiled), only);
}

// A path to an existing file is that file, as given; an absolute name is not searched for in
// the directories.
TEST(Search, PathsAndAbsoluteNames) {
  TempDir t;
  std::string p = t.put("a/m.osl", kMatte);
  t.put("b/m.osl", kMatte);
  EXPECT_EQ(find_shader(p, {t.dir("b")}), p);
  EXPECT_EQ(find_shader((t.root / "a" / "m").string(), {t.dir("b")}), p);
  EXPECT_EQ(find_shader((t.root / "c" / "m").string(), {t.dir("b")}), "");
  // A directory part relative to each search directory.
  EXPECT_EQ(find_shader("a/m", {t.root.string()}), p);
}

// The declared-name fallback: only when no directory has a file of that name, and the first
// directory's match wins.
TEST(Search, DeclaredNameAfterFileNames) {
  TempDir t;
  std::string declared = t.put("a/ray-type.osl", "surface ray_type() { Ci = 0; }\n");
  std::string named = t.put("b/ray_type.osl", kMatte);
  EXPECT_EQ(find_shader("ray_type", {t.dir("a"), t.dir("b")}), named);
  EXPECT_EQ(find_shader("ray_type", {t.dir("a")}), declared);
  EXPECT_EQ(find_shader("ray_type.osl", {t.dir("a")}), ""); // a file name is not a shader name
}

// A shader name the preprocessor makes (OSL's *_xmacro.h test headers: `shader
// __OSL_CONCAT(test_, __OSL_XMACRO_OPNAME)`, oslc naming the .oso after it) is found too, the
// header found beside the file.
TEST(Search, DeclaredNameMadeByMacros) {
  TempDir t;
  t.put("common/name_xmacro.h", "#define CAT2(a, b) a##b\n#define CAT(a, b) CAT2(a, b)\n"
                                "shader CAT(test_, OPNAME) (float x = 1) { printf(\"%g\", x); }\n");
  std::string f = t.put("c/sqrt_u_float.osl",
                        "#define OPNAME sqrt_u_float\n#include \"../common/name_xmacro.h\"\n");
  std::string g = t.put("c/other.osl", "#define NAME(a) test_##a\nshader NAME(cos) () {}\n");
  EXPECT_EQ(find_shader("test_sqrt_u_float", {t.dir("c")}), f);
  EXPECT_EQ(find_shader("test_cos", {t.dir("c")}), g);
  EXPECT_EQ(find_shader("test_tan", {t.dir("c")}), "");
}

// IR text and OSL source give the same shader: `lobe compile`'s .lir loads back unchanged.
TEST(Load, IrTextAndSourceAgree) {
  TempDir t;
  std::string osl = t.put("m.osl", kMatte);
  Options o;
  o.optimize = true;
  Loaded src = load_file(osl, o);
  ASSERT_TRUE(src.ok) << src.rendered();
  ASSERT_TRUE(src.shader);
  EXPECT_TRUE(src.tu);
  EXPECT_GE(src.timings.sema_ms, 0.0);
  std::string text = ir::print(*src.shader);
  std::string lir = t.put("m.lir", text);
  Loaded ir = load_file(lir, o);
  ASSERT_TRUE(ir.ok) << ir.rendered();
  EXPECT_FALSE(ir.tu); // no AST for IR text
  EXPECT_EQ(ir::print(*ir.shader), text);
  EXPECT_TRUE(ir.diagnostics.empty());
}

// Optimising IR text folds what the text left unfolded: `$t = 2 * 3` becomes a constant and
// the dead temporary goes.
TEST(Load, IrTextOptimisedWhenAsked) {
  const char* text = R"(lobe-ir 1
shader fold
symbols
  oparam float r = 0
  temp float $t0
  const float $c2 = 2
  const float $c3 = 3
main
  mul $t0 $c2 $c3
  assign r $t0
end
)";
  Loaded plain = parse_ir("fold.lir", text, {});
  ASSERT_TRUE(plain.ok) << plain.rendered();
  EXPECT_EQ(plain.shader->ops.size(), 2u);
  Options o;
  o.optimize = true;
  Loaded folded = parse_ir("fold.lir", text, o);
  ASSERT_TRUE(folded.ok) << folded.rendered();
  ASSERT_EQ(folded.shader->ops.size(), 1u);
  EXPECT_EQ(folded.shader->ops[0].opcode, ir::Opcode::Assign);
}

// Every stage's error arrives structured: id, severity, file, line, column, message, and the
// caret form.
TEST(Diagnostics, FrontEndErrorIsStructured) {
  Loaded l =
      compile_source("bad.osl", "surface bad() {\n  float a = 1;\n  Ci = b * diffuse(N);\n}\n", {});
  EXPECT_FALSE(l.ok);
  EXPECT_FALSE(l.shader);
  ASSERT_EQ(l.diagnostics.size(), 1u) << l.rendered();
  const diag::Report& d = l.diagnostics[0];
  EXPECT_EQ(d.id, diag::DiagId::err_undeclared);
  EXPECT_EQ(d.severity, diag::Severity::Error);
  EXPECT_EQ(d.file, "bad.osl");
  EXPECT_EQ(d.line, 3);
  EXPECT_EQ(d.column, 8);
  EXPECT_EQ(d.message, "use of undeclared identifier 'b'");
  EXPECT_EQ(d.text, "bad.osl:3:8: error: use of undeclared identifier 'b'\n"
                    "  Ci = b * diffuse(N);\n"
                    "       ^\n");
}

TEST(Diagnostics, WarningsComeWithTheShader) {
  Loaded l = compile_source("w.osl", "#warning careful\nsurface w() { Ci = 0; }\n", {});
  EXPECT_TRUE(l.ok) << l.rendered();
  EXPECT_TRUE(l.shader);
  ASSERT_EQ(l.diagnostics.size(), 1u);
  EXPECT_EQ(l.diagnostics[0].severity, diag::Severity::Warning);
  EXPECT_EQ(l.diagnostics[0].line, 1);
  Options werror;
  werror.warnings_as_errors = true;
  Loaded e = compile_source("w.osl", "#warning careful\nsurface w() { Ci = 0; }\n", werror);
  EXPECT_FALSE(e.ok);
  EXPECT_EQ(e.diagnostics[0].severity, diag::Severity::Error);
}

TEST(Diagnostics, IrParseErrorIsLocated) {
  Loaded l = parse_ir("x.lir", "lobe-ir 1\nsurface x\nsymbols\n  bogus float a\n", {});
  EXPECT_FALSE(l.ok);
  ASSERT_EQ(l.diagnostics.size(), 1u);
  const diag::Report& d = l.diagnostics[0];
  EXPECT_EQ(d.id, diag::DiagId::err_ir_parse);
  EXPECT_EQ(d.file, "x.lir");
  EXPECT_EQ(d.line, 4);
  EXPECT_GE(d.column, 1);
  EXPECT_EQ(d.text.rfind("x.lir:4:", 0), 0u) << d.text;
  EXPECT_NE(d.text.find("\n  bogus float a\n"), std::string::npos) << d.text; // the line
}

TEST(Diagnostics, UnreadableFile) {
  Loaded l = load_file("/nonexistent/dir/x.lir", {});
  ASSERT_EQ(l.diagnostics.size(), 1u);
  EXPECT_EQ(l.diagnostics[0].id, diag::DiagId::err_file_unreadable);
  EXPECT_EQ(l.diagnostics[0].text, "error: cannot read '/nonexistent/dir/x.lir'\n");
  Loaded s = load_file("/nonexistent/dir/x.osl", {});
  ASSERT_EQ(s.diagnostics.size(), 1u);
  EXPECT_EQ(s.diagnostics[0].id, diag::DiagId::err_file_not_found);
}

// Lowering reports through the same engine: a shader-less file passes the type checker and
// stops in lowering with err_lower_no_shader.
TEST(Diagnostics, LoweringErrorHasAnId) {
  Loaded l = compile_source("lib.osl", "float twice(float x) { return 2 * x; }\n", {});
  EXPECT_FALSE(l.ok);
  ASSERT_EQ(l.diagnostics.size(), 1u) << l.rendered();
  EXPECT_EQ(l.diagnostics[0].id, diag::DiagId::err_lower_no_shader);
  EXPECT_EQ(l.diagnostics[0].text, "error: no shader declared\n");
}

// A located lowering error: the same fields and the same caret form as the front end's. A
// non-void function declared without a body passes the type checker and has nothing to
// inline; oslc 1.13 says, for this source (`oslc p.osl`):
//   p.osl:3: error: non-void function "f" had no 'return' statement.
TEST(Diagnostics, LoweringErrorIsLocated) {
  Loaded l = compile_source(
      "p.osl", "float f(float x);\nsurface s() {\n  float y = f(1);\n  Ci = y * diffuse(N);\n}\n",
      {});
  EXPECT_FALSE(l.ok);
  ASSERT_EQ(l.diagnostics.size(), 1u) << l.rendered();
  const diag::Report& d = l.diagnostics[0];
  EXPECT_EQ(d.id, diag::DiagId::err_lower_no_body);
  EXPECT_EQ(d.file, "p.osl");
  EXPECT_EQ(d.line, 3);
  EXPECT_EQ(d.column, 13);
  EXPECT_EQ(d.text, "p.osl:3:13: error: non-void function 'f' had no 'return' statement\n"
                    "  float y = f(1);\n"
                    "            ^\n");
}

// A void function without a body: oslc 1.13 compiles its call, which does nothing (`oslc
// q.osl` prints "Compiled q.osl -> s.oso"); so does Lobe.
TEST(Diagnostics, VoidFunctionWithoutBodyDoesNothing) {
  Loaded l = compile_source(
      "q.osl", "void g(float x);\nsurface s() {\n  g(1);\n  Ci = diffuse(N);\n}\n", {});
  EXPECT_TRUE(l.ok) << l.rendered();
  EXPECT_TRUE(l.diagnostics.empty()) << l.rendered();
}

} // namespace
} // namespace lobe::driver

// `lobe compile` and `lobe info` on OSL source, run as a user would: the executable with its
// arguments, checking exit status, stdout and stderr.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = LOBE_SOURCE_DIR;
// 'path', built by appending ("'" + std::string trips GCC 12's false -Wrestrict).
std::string quoted(const fs::path& p) {
  std::string s = "'";
  s += p.string();
  s += '\'';
  return s;
}

struct CliRun {
  int status = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `lobe <args>` in `dir`, capturing stdout and stderr through files named after this
// process (ctest runs the tests of this binary as concurrent processes).
CliRun lobe(const std::string& args, const fs::path& dir = fs::temp_directory_path()) {
  std::string tag = std::to_string(::getpid());
  fs::path out = dir / ("lobe_cli_test_" + tag + ".out"),
           err = dir / ("lobe_cli_test_" + tag + ".err");
  std::string cmd = "cd '" + dir.string() + "' && '" + std::string(LOBE_EXE) + "' " + args + " >'" +
                    out.string() + "' 2>'" + err.string() + "'";
  CliRun r;
  int st = std::system(cmd.c_str());
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// A scratch directory with one shader file in it.
fs::path scratch(const std::string& name, const std::string& text) {
  fs::path dir = fs::temp_directory_path() / ("lobe_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir;
}

TEST(LobeCompile, PrintsVerifiedIrForOslSource) {
  CliRun r = lobe("compile '" + (kRoot / "stdlib_shaders" / "plastic.osl").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("lobe-ir 1\nsurface plastic", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("param float roughness = 0.2"), std::string::npos);
  EXPECT_NE(r.out.find("closure Ci"), std::string::npos);
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(LobeCompile, ReportsErrorsWithLocationSourceLineAndCaret) {
  fs::path dir = scratch("bad.osl", "surface bad()\n{\n    float x = 1 + nope;\n}\n");
  CliRun r = lobe("compile bad.osl", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("bad.osl:3:19: error:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("    float x = 1 + nope;\n                  ^"), std::string::npos) << r.err;
}

TEST(LobeCompile, DefinesIncludesOutputFileAndAst) {
  fs::path dir = scratch(
      "defs.osl", "#include \"k.h\"\nshader defs(float k = K * SCALE) { printf(\"%g\", k); }\n");
  std::ofstream(dir / "k.h") << "#define K 3\n";
  CliRun r = lobe("compile defs.osl -I . -D SCALE=2 -O0 -o defs.lir", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(slurp(dir / "defs.lir").find("param float k = 6"), std::string::npos);
  r = lobe("compile defs.osl -DSCALE=2 --emit=ast", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("shader"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("faceforward"), std::string::npos) << "the standard header is not dumped";
  r = lobe("compile defs.osl", dir); // SCALE undefined: an error
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("SCALE"), std::string::npos) << r.err;
  // The IR it wrote compiles again as Lobe IR text.
  r = lobe("compile defs.lir", dir);
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST(LobeCompile, EmitLlvmPrintsTheGroupAfterTheJitPipeline) {
  std::string matte = quoted(kRoot / "stdlib_shaders" / "matte.osl");
  for (const char* opt : {"-O0", "-O1", "-O2"}) {
    CliRun r = lobe("compile " + matte + " --emit=llvm " + opt);
    ASSERT_EQ(r.status, 0) << opt << r.err;
    EXPECT_NE(r.out.find("target triple = "), std::string::npos) << opt;
    EXPECT_NE(r.out.find("define void @group_entry(ptr"), std::string::npos) << opt << r.out;
    EXPECT_NE(r.out.find("ret void"), std::string::npos) << opt;
    EXPECT_NE(r.out.find("@lobe_closure_component"), std::string::npos) << opt;
    EXPECT_TRUE(r.err.empty()) << r.err;
  }
  // The layer function itself, before the -O2 inliner folds it into group_entry.
  CliRun r = lobe("compile " + matte + " --emit=llvm -O0");
  EXPECT_NE(r.out.find("define internal void @layer_0_matte(ptr"), std::string::npos) << r.out;
  // -O0 neither specialises nor optimises: k * 3 is computed from the param's group data;
  // above it the default is folded (3 * 2 = 6 stored for printf).
  fs::path dir = scratch("k3.osl", "shader k3(float k = 2) { printf(\"%g\\n\", k * 3); }\n");
  r = lobe("compile k3.osl --emit=llvm -O0", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("fmul float"), std::string::npos) << r.out;
  r = lobe("compile k3.osl --emit=llvm -O2 -o k3.ll", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  std::string ll = slurp(dir / "k3.ll");
  EXPECT_NE(ll.find("float 6.000000e+00"), std::string::npos) << ll;
  EXPECT_EQ(ll.find("fmul"), std::string::npos) << ll;
  // Lobe IR text works too.
  r = lobe("compile '" + (kRoot / "tests" / "shade" / "math_specials.lir").string() +
           "' --emit=llvm");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("define void @group_entry("), std::string::npos);
}

TEST(LobeCompile, EmitAsmPrintsHostAssembly) {
  std::string matte = quoted(kRoot / "stdlib_shaders" / "matte.osl");
  for (const char* opt : {"-O0", "-O2"}) {
    CliRun r = lobe("compile " + matte + " --emit=asm " + opt);
    ASSERT_EQ(r.status, 0) << opt << r.err;
    EXPECT_NE(r.out.find(".text"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\n\t.globl\tgroup_entry\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\ngroup_entry:"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\n\tret"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("lobe_closure_component"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("define "), std::string::npos) << "assembly, not LLVM IR";
  }
}

TEST(LobeCompile, EmitLlvmReportsSourceErrors) {
  fs::path dir = scratch("bad2.osl", "surface bad2()\n{\n    float x = 1 + nope;\n}\n");
  CliRun r = lobe("compile bad2.osl --emit=llvm", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("bad2.osl:3:19: error:"), std::string::npos) << r.err;
  r = lobe("compile bad2.osl --emit=obj", dir);
  EXPECT_EQ(r.status, 2);
}

TEST(LobeInfo, FindsTheShaderByNameAndPrintsOslinfoStyle) {
  CliRun r = lobe("info params -I '" + (kRoot / "tests" / "lower").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const char* want[] = {
      "surface \"params\"\n",
      "    metadata: string help = \"parameter corpus\"\n",
      "    metadata: int version = 2\n",
      "    \"Kd\" \"float\"\n\t\tDefault value: 0.5\n\t\tmetadata: float min = 0\n",
      "\t\tmetadata: string widget = \"slider\"\n",
      "\t\tDefault value: [ 1 2 4 ]\n\t\tmetadata: string help = \"unsized\"\n",
      "    \"look\" \"struct Look\"\n    \"look.tint\" \"color\"\n\t\tDefault value: [ 1 0.5 0.25 "
      "]\n",
      "    \"uu\" \"float\"\n\t\tDefault value: (computed at run time)\n",
      "    \"mode\" \"string\"\n\t\tDefault value: \"a\"\n\t\tmetadata: string options = \"a|b\"\n",
      "    \"result\" \"output float\"\n\t\tDefault value: 0\n",
  };
  for (const char* w : want) EXPECT_NE(r.out.find(w), std::string::npos) << w << "\nin\n" << r.out;
}

TEST(LobeInfo, NumberAsMatrixDefaultPrintsItsSixteenValues) {
  // As oslinfo does: `matrix m = 1` is the identity, `matrix s = 2.5` a diagonal.
  fs::path dir = scratch("mats.osl", "shader mats(matrix m = 1, matrix s = 2.5, matrix w = "
                                     "matrix(\"world\", 1)) { }\n");
  CliRun r = lobe("info mats.osl", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "shader \"mats\"\n"
                   "    \"m\" \"matrix\"\n"
                   "\t\tDefault value: [ 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 ]\n"
                   "    \"s\" \"matrix\"\n"
                   "\t\tDefault value: [ 2.5 0 0 0 0 2.5 0 0 0 0 2.5 0 0 0 0 2.5 ]\n"
                   "    \"w\" \"matrix\"\n"
                   "\t\tDefault value: (computed at run time)\n");
}

TEST(LobeInfo, UnknownShaderIsAnError) {
  CliRun r = lobe("info no_such_shader_here");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("cannot find shader"), std::string::npos);
}

} // namespace

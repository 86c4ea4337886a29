// `lobe compile` and `lobe info` on OSL source, run as a user would: the executable with its
// arguments, checking exit status, stdout and stderr. `lobe info` must print what OSL's oslinfo
// prints (the expected texts in tests/lower/oslinfo/ are its output), `lobe compile` behave as
// oslc does (its output file, `Compiled`/`FAILED` lines, options).
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

// A scratch directory with one shader file in it (`name` may have a directory part).
fs::path scratch(const std::string& name, const std::string& text) {
  fs::path dir = fs::temp_directory_path() / ("lobe_cli_" + std::to_string(::getpid()));
  fs::create_directories((dir / name).parent_path());
  std::ofstream(dir / name) << text;
  return dir;
}

// ---- lobe compile ---------------------------------------------------------------------------

TEST(LobeCompile, WritesTheIrFileInTheCurrentDirectoryAsOslcDoes) {
  // oslc sub2/p.osl writes ./p.oso and prints `Compiled sub2/p.osl -> p.oso`.
  fs::path dir = scratch("sub2/p.osl", "surface p(float k = 2) { Ci = k * diffuse(N); }\n");
  fs::remove(dir / "p.lir");
  CliRun r = lobe("compile sub2/p.osl", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "Compiled sub2/p.osl -> p.lir\n");
  EXPECT_TRUE(r.err.empty()) << r.err;
  std::string ir = slurp(dir / "p.lir");
  EXPECT_EQ(ir.rfind("lobe-ir 1\nsurface p", 0), 0u) << ir;
  EXPECT_NE(ir.find("param float k = 2"), std::string::npos) << ir;
  // -q is quiet, -v prints the same; the last one wins. -o names the file.
  r = lobe("compile -v -q sub2/p.osl -o out.ir", dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(slurp(dir / "out.ir"), ir);
  r = lobe("compile -q -v sub2/p.osl -o sub2/p.lir", dir);
  EXPECT_EQ(r.out, "Compiled sub2/p.osl -> sub2/p.lir\n");
  // The IR it wrote compiles as Lobe IR text, but not onto itself.
  r = lobe("compile sub2/p.lir", dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "Compiled sub2/p.lir -> p.lir\n");
  r = lobe("compile p.lir", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, "FAILED p.lir\n");
  EXPECT_NE(r.err.find("is the input"), std::string::npos) << r.err;
  // The output is named after the shader, not the file: oslc sub2/afile.osl (holding shader
  // bname) prints `Compiled sub2/afile.osl -> bname.oso`.
  scratch("sub2/afile.osl", "shader bname() { printf(\"x\\n\"); }\n");
  r = lobe("compile sub2/afile.osl", dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "Compiled sub2/afile.osl -> bname.lir\n");
  EXPECT_TRUE(fs::exists(dir / "bname.lir"));
}

TEST(LobeCompile, PrintsVerifiedIrForOslSourceWithEmitIr) {
  CliRun r =
      lobe("compile --emit=ir '" + (kRoot / "stdlib_shaders" / "plastic.osl").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("lobe-ir 1\nsurface plastic", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("param float roughness = 0.2"), std::string::npos);
  EXPECT_NE(r.out.find("closure Ci"), std::string::npos);
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(LobeCompile, ReportsErrorsWithLocationSourceLineAndCaret) {
  // oslc prints `FAILED bad.osl` on stdout, even with -q, and leaves an old output alone.
  fs::path dir = scratch("bad.osl", "surface bad()\n{\n    float x = 1 + nope;\n}\n");
  std::ofstream(dir / "bad.lir") << "old";
  CliRun r = lobe("compile -q bad.osl", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, "FAILED bad.osl\n");
  EXPECT_NE(r.err.find("bad.osl:3:19: error:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("    float x = 1 + nope;\n                  ^"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir / "bad.lir"), "old");
  r = lobe("compile nosuch.osl", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, "FAILED nosuch.osl\n");
  EXPECT_EQ(r.err, "error: Input file \"nosuch.osl\" not found\n");
  std::ofstream(dir / "ok.osl") << "shader ok() {}\n";
  r = lobe("compile -o no/such/dir/x.lir ok.osl", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("could not open \"no/such/dir/x.lir\""), std::string::npos) << r.err;
}

TEST(LobeCompile, WarningsAndWerror) {
  fs::path dir = scratch("w.osl", "shader w(float noise = 1) { printf(\"%g\\n\", noise); }\n");
  CliRun r = lobe("compile w.osl", dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "Compiled w.osl -> w.lir\n");
  EXPECT_NE(r.err.find("w.osl:1:16: warning: "), std::string::npos) << r.err;
  r = lobe("compile -Werror w.osl", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, "FAILED w.osl\n");
  EXPECT_NE(r.err.find("w.osl:1:16: error: "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("warning:"), std::string::npos) << r.err;
}

TEST(LobeCompile, DefinesIncludesOutputFileAndAst) {
  fs::path dir = scratch(
      "defs.osl", "#include \"k.h\"\nshader defs(float k = K * SCALE) { printf(\"%g\", k); }\n");
  fs::create_directories(dir / "inc");
  std::ofstream(dir / "inc" / "k.h") << "#define K 3\n";
  // -I, -D and -U as one word or two.
  for (const char* opts : {"-I inc -D SCALE=2", "-Iinc -DSCALE=2", "-Iinc -DSCALE=2 -UNO"}) {
    CliRun r = lobe(std::string("compile defs.osl -O0 -o defs.lir ") + opts, dir);
    ASSERT_EQ(r.status, 0) << opts << r.err;
    EXPECT_NE(slurp(dir / "defs.lir").find("param float k = 6"), std::string::npos) << opts;
  }
  CliRun r = lobe("compile defs.osl -Iinc -DSCALE=2 --emit=ast", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("shader"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("faceforward"), std::string::npos) << "the standard header is not dumped";
  r = lobe("compile defs.osl", dir); // k.h not found
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("k.h"), std::string::npos) << r.err;
  r = lobe("compile defs.osl -Iinc -D SCALE=4 -O1 --emit=ir", dir);
  EXPECT_NE(r.out.find("param float k = 12"), std::string::npos) << r.out << r.err;
  r = lobe("compile defs.osl -Iinc -D SCALE=4 -U SCALE", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("SCALE"), std::string::npos) << r.err;
}

TEST(LobeCompile, PreprocessOnlyPrintsTheTextWithLineMarkers) {
  fs::path dir =
      scratch("pp.osl", "#define TWICE(x) ((x) * 2)\n\nshader pp(float k = TWICE(W)) {}\n");
  CliRun r = lobe("compile -E -DW=5 pp.osl", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("# 1 \"stdosl.h\"\n", 0), 0u) << r.out.substr(0, 200);
  EXPECT_NE(r.out.find("\n# 2 \"pp.osl\"\n\nshader pp(float k = ( ( 5 ) * 2 ) ) {}\n"),
            std::string::npos)
      << r.out.substr(r.out.size() - 200);
  EXPECT_FALSE(fs::exists(dir / "pp.lir")) << "-E compiles nothing";
  r = lobe("compile -E nosuch.osl", dir);
  EXPECT_EQ(r.status, 1);
}

TEST(LobeCompile, HelpAndOptions) {
  CliRun r = lobe("compile");
  EXPECT_EQ(r.status, 0); // as oslc: no input prints the help
  EXPECT_EQ(r.out.rfind("lobe compile -- ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("\n\t-Werror        Treat all warnings as errors\n"), std::string::npos);
  EXPECT_EQ(lobe("compile --help").out, r.out);
  // oslc ignores options it does not know (Lobe says so) and accepts its debugging options.
  fs::path dir = scratch("opt.osl", "shader opt() {}\n");
  r = lobe("compile --frobnicate -d -embed-source opt.osl", dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "Compiled opt.osl -> opt.lir\n");
  EXPECT_EQ(r.err, "lobe compile: warning: unknown option '--frobnicate' ignored\n");
  EXPECT_EQ(lobe("compile opt.osl other.osl", dir).status, 2);
  EXPECT_EQ(lobe("compile opt.osl -o", dir).status, 2);
}

TEST(LobeCompile, EmitLlvmPrintsTheGroupAfterTheJitPipeline) {
  std::string matte = quoted(kRoot / "stdlib_shaders" / "matte.osl");
  for (const char* opt : {"-O0", "-O1", "-O2"}) {
    CliRun r = lobe("compile " + matte + " --emit=llvm " + opt);
    ASSERT_EQ(r.status, 0) << opt << r.err;
    EXPECT_NE(r.out.find("target triple = "), std::string::npos) << opt;
    EXPECT_NE(r.out.find("define void @group_entry(ptr"), std::string::npos) << opt << r.out;
    EXPECT_NE(r.out.find("ret void"), std::string::npos) << opt;
    // The closure builder is called below -O2 and inlined from the shadeop bitcode at -O2.
    EXPECT_EQ(r.out.find("@lobe_closure_component") != std::string::npos, std::string(opt) != "-O2")
        << opt;
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
    // Called at -O0, inlined at -O2 (the shadeop bitcode).
    EXPECT_EQ(r.out.find("lobe_closure_component") != std::string::npos, std::string(opt) == "-O0")
        << r.out;
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

// ---- lobe info ------------------------------------------------------------------------------

const fs::path kOslinfoDir = kRoot / "tests" / "lower" / "oslinfo";

// Each tests/lower/oslinfo/NAME.osl, found on the -p search path: `lobe info -v NAME` prints
// NAME.v.txt and `lobe info NAME` NAME.txt, which OSL's oslinfo printed (see the .osl files).
TEST(LobeInfo, PrintsWhatOslinfoPrints) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(kOslinfoDir)) {
    if (e.path().extension() != ".osl") continue;
    std::string name = e.path().stem().string();
    for (const char* v : {"-v ", ""}) {
      CliRun r = lobe(std::string("info ") + v + "-p " + quoted(kOslinfoDir) + " " + name);
      ASSERT_EQ(r.status, 0) << name << r.err;
      std::string want = slurp(kOslinfoDir / (name + (*v ? ".v.txt" : ".txt")));
      EXPECT_EQ(r.out, want) << name << " " << v;
      EXPECT_EQ(r.err, "") << name;
    }
    ++n;
  }
  EXPECT_GE(n, 4);
}

// oslinfo --param NAME: only that block (a struct's fields line, a nested struct), no shader
// line; nothing for a name it does not have. Several files follow one another.
// Expected texts: oslinfo [-v] --param NAME info, and oslinfo -v floats info (OSL 1.13.12).
TEST(LobeInfo, OneParameterAndSeveralFiles) {
  std::string p = "-p " + quoted(kOslinfoDir) + " ";
  EXPECT_EQ(lobe("info " + p + "--param st info").out, "struct S st fields: {float a, color c}\n");
  EXPECT_EQ(lobe("info " + p + "-v --param tt.s info").out,
            "    \"tt.s\" \"struct S\"\n\t\tfields: {float a, color c}\n");
  EXPECT_EQ(lobe("info " + p + "--param sa info").out, "string[2] sa \"a\" \"b\" \n");
  EXPECT_EQ(lobe("info " + p + "-v --param i info").out,
            "    \"i\" \"int\"\n\t\tDefault value: 1\n\t\tmetadata: string widget = "
            "\"checkBox\"\n\t\tmetadata: int min = 0\n\t\tmetadata: int max = 1\n");
  CliRun r = lobe("info " + p + "--param nosuch info");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, "");
  r = lobe("info -v " + p + "floats info");
  EXPECT_EQ(r.out, slurp(kOslinfoDir / "floats.v.txt") + slurp(kOslinfoDir / "info.v.txt"));
}

// Shaders by name (x, x.osl, x.oso for x.osl, a path) on the current directory, the -p path
// (colon-separated) and stdlib_shaders/, as `lobe render` finds materials.
TEST(LobeInfo, FindsShadersOnTheSearchPath) {
  fs::path dir = scratch("sub/np.osl", "surface np() {}\n");
  fs::remove(dir / "matte.osl");
  for (const char* arg : {"np", "np.osl", "np.oso", "sub/np", "sub/np.osl"}) {
    std::string where = std::string(arg).rfind("sub/", 0) == 0 ? "" : "-p /nonexistent:sub ";
    CliRun r = lobe("info " + where + arg, dir);
    EXPECT_EQ(r.status, 0) << arg << r.err;
    EXPECT_EQ(r.out, "surface \"np\"\n") << arg;
  }
  CliRun r = lobe("info matte", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("surface \"matte\"\ncolor Cs  [ 0.8 0.8 0.8 ]\n", 0), 0u) << r.out;
  // A shader in the current directory comes first; -I also adds a search directory.
  std::ofstream(dir / "matte.osl") << "shader matte(int mine = 1) {}\n";
  EXPECT_EQ(lobe("info matte", dir).out, "shader \"matte\"\nint mine  1\n");
  EXPECT_EQ(lobe("info -I sub np", dir).out, "surface \"np\"\n");
  // What `lobe compile` writes lists the same (structs and folded defaults survive .lir).
  r = lobe("compile -q -o info.lir " + quoted(kOslinfoDir / "info.osl"), dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lobe("info -v info.lir", dir).out, slurp(kOslinfoDir / "info.v.txt"));
}

// A missing shader: oslinfo prints ` ""` and an error in its words, and exits 0; Lobe exits 1 (a
// bad input is an error). The other files are still listed.
TEST(LobeInfo, MissingOrBrokenShaderIsAnError) {
  fs::path dir = scratch("ok.osl", "shader ok() {}\n");
  CliRun r = lobe("info nosuch ok", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, " \"\"\nshader \"ok\"\n");
  EXPECT_EQ(r.err, "ERROR: File nosuch.oso not found\n");
  // oslinfo's words (OSL 1.13.12: `oslinfo nosuch.oso`, `oslinfo nosuch.osl`).
  EXPECT_EQ(lobe("info nosuch.oso", dir).err, "ERROR: File nosuch.oso not found\n");
  EXPECT_EQ(lobe("info nosuch.osl", dir).err, "ERROR: File nosuch.osl.oso not found\n");
  std::ofstream(dir / "broken.osl") << "shader broken() { int x = ; }\n";
  r = lobe("info broken", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, " \"\"\n");
  EXPECT_NE(r.err.find("broken.osl:1:27: error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("ERROR: Failed to compile broken.osl\n"), std::string::npos) << r.err;
}

// oslinfo's help layout; its argument errors (help on stdout, the message on stderr, status 1).
TEST(LobeInfo, HelpAndArgumentErrors) {
  CliRun help = lobe("info --help");
  EXPECT_EQ(help.status, 0);
  EXPECT_EQ(help.out.rfind("lobe info -- list parameters of an OSL shader\n", 0), 0u) << help.out;
  EXPECT_NE(help.out.find("\n\nUsage: lobe info [options] file0 [file1 ...]\n\n"
                          "    --help         Print help message\n"
                          "    -v             Verbose output\n"
                          "    --runstats     Benchmark shader loading time for queries\n"
                          "    -p SEARCHPATH  Set searchpath for shaders\n"
                          "    --param NAME   Output information about just this parameter\n"),
            std::string::npos)
      << help.out;
  CliRun r = lobe("info");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, help.out);
  r = lobe("info --bogus matte");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, help.out);
  EXPECT_EQ(r.err, "lobe info error: Invalid option \"--bogus\"\n");
  r = lobe("info matte --param");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "lobe info error: Missing parameter 1 from option \"--param\"\n");
  EXPECT_EQ(lobe("info -p").err, "lobe info error: Missing parameter 1 from option \"-p\"\n");
}

// --runstats prints only the time each shader took, as oslinfo: `0.000121762 sec for p`.
TEST(LobeInfo, RunstatsPrintsTheLoadTime) {
  CliRun r = lobe("info --runstats -v matte plastic");
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream lines(r.out);
  for (const char* name : {"matte", "plastic"}) {
    std::string line;
    std::getline(lines, line);
    double t = -1;
    char rest[64] = {};
    EXPECT_EQ(std::sscanf(line.c_str(), "%lg sec for %63s", &t, rest), 2) << line;
    EXPECT_GT(t, 0.0);
    EXPECT_STREQ(rest, name);
  }
  EXPECT_TRUE(lines.peek() == EOF) << r.out;
}

} // namespace

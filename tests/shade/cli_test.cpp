// `lobe shade` end to end: layers, instance values, connections of each kind (announced
// first), lazy upstream layers, group files and image output, with specialisation off and on.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace {

std::string run_cmd(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return "<popen failed>";
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
}

std::string run(const std::string& args) {
  return run_cmd(std::string(LOBE_EXE) + " shade -I " + LOBE_SHADE_CORPUS + "/layers " + args +
                 " 2>&1");
}

// Runs at -O0 and -O2 (specialisation off and on); both must print the same.
std::string both(const std::string& args) {
  std::string a = run("-O0 " + args), b = run("-O2 " + args);
  EXPECT_EQ(a, b) << "specialisation changed the output";
  return b;
}

TEST(ShadeCli, ConnectionsAreAnnouncedAndFollowed) {
  EXPECT_EQ(both("-param scale 2 -layer up upstream_color -layer down downstream_print "
                 "-connect up Cout down Cin -connect up f[1] down g -connect up Cout[2] down h "
                 "-connect up pr down pr"),
            "Connect up.Cout to down.Cin\nConnect up.f[1] to down.g\nConnect up.Cout[2] to down.h\n"
            "Connect up.pr to down.pr\nupstream ran\nCin 2 4 6 g 10 h 6 pr 5 12\n");
}

TEST(ShadeCli, UnreadUpstreamLayerNeverRuns) {
  EXPECT_EQ(both("-layer up upstream_color -param:type=int use 0 -layer down downstream_print "
                 "--connect up Cout down Cin"),
            "Connect up.Cout to down.Cin\nunused\n");
  EXPECT_EQ(both("-layer up upstream_color -layer down downstream_print"),
            "Cin 0 0 0 g 0 h 0 pr 0 0\n");
}

TEST(ShadeCli, GroupTextAndGrid) {
  EXPECT_EQ(both("-g 2 1 -group \"param float scale 0.5 ; shader upstream_color up ; "
                 "shader downstream_print down ; connect up.Cout down.Cin ;\""),
            "Connect up.Cout to down.Cin\nupstream ran\nCin 0.5 1 1.5 g 0 h 0 pr 0 0\n"
            "upstream ran\nCin 0.5 1 1.5 g 0 h 0 pr 0 0\n");
}

// testshade's renderer: "s"/"t" user data are u/v with derivatives; --userdata adds more;
// -param:lockgeom=0 unlocks a parameter the shader locked, lockgeom=1 locks one it unlocked.
TEST(ShadeCli, UserDataAndAttributes) {
  EXPECT_EQ(both("-g 2 3 -param:lockgeom=1 t 0.25 userdata_print"),
            "s 0 ds 1 0 t 0.25 dt 0 0 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 0\n"
            "s 1 ds 1 0 t 0.25 dt 0 0 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 0\n"
            "s 0 ds 1 0 t 0.25 dt 0 0 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 0.5\n"
            "s 1 ds 1 0 t 0.25 dt 0 0 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 0.5\n"
            "s 0 ds 1 0 t 0.25 dt 0 0 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 1\n"
            "s 1 ds 1 0 t 0.25 dt 0 0 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 1\n");
  EXPECT_EQ(both("--userdata:type=color tint \"0.5 0.25 2\" --userdata:type=string label "
                 "\"two words\" --userdata fixed 9 -param:type=float:lockgeom=0 fixed 4 "
                 "userdata_print"),
            "s 0.5 ds 1 0 t 0.5 dt 0 1 tint 0.5 0.25 2 label two words fixed 9 res 1 1 1 "
            "t-attr 1 0.5\n");
  EXPECT_EQ(both("--userdata s 0.125 userdata_print"), // the user's "s" replaces testshade's
            "s 0.125 ds 0 0 t 0.5 dt 0 1 tint 1 1 1 label none fixed 3 res 1 1 1 t-attr 1 0.5\n");
  EXPECT_EQ(both("--userdata fixed 9 -param fixed 4 userdata_print"),
            "s 0.5 ds 1 0 t 0.5 dt 0 1 tint 1 1 1 label none fixed 4 res 1 1 1 t-attr 1 0.5\n");
  EXPECT_NE(run("--userdata:type=color tint \"1 2\" userdata_print")
                .find("'1 2' is not a value of type color"),
            std::string::npos);
  EXPECT_NE(run("-param:lockgeom=2 s 1 userdata_print").find("unknown modifier ':lockgeom=2'"),
            std::string::npos);
  EXPECT_NE(
      run("--userdata:type=int fixed 1.5 userdata_print").find("'1.5' is not a value of type int"),
      std::string::npos);
  EXPECT_NE(run("--userdata fixed abc userdata_print").find("'abc' is not a value of type float"),
            std::string::npos);
}

// `float a[] = {1, 2}` stays unsized: an instance value of another length sets arraylength.
TEST(ShadeCli, UnsizedArrayParameterTakesTheInstanceLength) {
  EXPECT_EQ(both("unsized_array"), "arraylength 2 sum 3 last 2\n");
  EXPECT_EQ(both("-param:type=float[] a \"1 2 3\" unsized_array"), "arraylength 3 sum 6 last 3\n");
  EXPECT_EQ(both("-param:type=float[] a \"0.5 1 1.5 2 4\" unsized_array"),
            "arraylength 5 sum 9 last 4\n");
}

TEST(ShadeCli, WritesOutputImage) {
  auto file = std::filesystem::temp_directory_path() /
              ("lobe_shade_cli_test_" + std::to_string(::getpid()) + ".exr");
  std::filesystem::remove(file);
  std::string out = run("-g 4 2 -o Cout " + file.string() + " downstream_print");
  EXPECT_NE(out.find("Cin 0 0 0"), std::string::npos) << out;
  EXPECT_TRUE(std::filesystem::exists(file));
  EXPECT_GT(std::filesystem::file_size(file), 0u);
  std::filesystem::remove(file);
}

// Runs `lobe shade args` in directory `dir` (stdout and stderr together).
std::string run_in(const std::filesystem::path& dir, const std::string& args) {
  return run_cmd("cd '" + dir.string() + "' && " + LOBE_EXE + " shade " + args + " 2>&1");
}

std::filesystem::path scratch_dir(const std::string& name, const std::string& text) {
  auto dir = std::filesystem::temp_directory_path() /
             ("lobe_shade_cli_scratch_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  FILE* f = std::fopen((dir / name).string().c_str(), "wb");
  std::fputs(text.c_str(), f);
  std::fclose(f);
  return dir;
}

// -D and -U as for lobe compile; a shader found by name in the working directory is `w.osl`
// in __FILE__ and in diagnostics (not `./w.osl`), which follow one another without blank lines.
TEST(ShadeCli, PreprocessorOptionsFileNamesAndDiagnosticsAsLobeCompile) {
  auto dir = scratch_dir("w.osl", "shader w()\n{\n#ifdef FOO\n    printf(\"foo\\n\");\n#endif\n"
                                  "    printf(\"%s\\n\", __FILE__);\n}\n");
  EXPECT_EQ(run_in(dir, "-DFOO w"), "foo\nw.osl\n");
  EXPECT_EQ(run_in(dir, "-D FOO -U FOO w"), "w.osl\n");
  EXPECT_EQ(run_in(dir, "-D FOO -UFOO w.osl"), "w.osl\n");
  scratch_dir("bad.osl", "shader bad()\n{\n    float x = 1 + nope;\n    int y = \"s\";\n}\n");
  EXPECT_EQ(run_in(dir, "bad"), "bad.osl:3:19: error: use of undeclared identifier 'nope'\n"
                                "    float x = 1 + nope;\n"
                                "                  ^~~~\n"
                                "bad.osl:4:13: error: cannot assign 'string' to 'int'\n"
                                "    int y = \"s\";\n"
                                "            ^~~\n");
}

// --colorspace sets the material's colour space. Expected: OSL 1.13.12,
//   oslc csli.osl; stdbuf -oL testshade [--colorspace NAME] csli 2>&1; echo $?
// (testshade's closing blank line dropped): an unknown name (names are case-sensitive) is
// reported once before shading, which goes on in Rec709, with exit status 0.
TEST(ShadeCli, ColorspaceOption) {
  auto dir = scratch_dir("csli.osl", "shader csli()\n{\n    printf(\"%.9g | %.9g\\n\", "
                                     "luminance(color(0.1, 0.7, 0.2)), transformc(\"XYZ\", "
                                     "color(1, 0.5, 0.25)));\n}\n");
  const std::string rec709 = "0.536424339 | 0.636061966 0.588217974 0.316401064\n";
  EXPECT_EQ(run_in(dir, "csli 2>&1; echo $?"), rec709 + "0\n");
  EXPECT_EQ(run_in(dir, "--colorspace ACEScg csli 2>&1; echo $?"),
            "0.509817958 | 0.768503129 0.622691929 0.249040425\n0\n");
  EXPECT_EQ(run_in(dir, "-colorspace NTSC -O0 csli"),
            "0.463418633 | 0.743757248 0.620860696 0.311986387\n");
  EXPECT_EQ(run_in(dir, "--colorspace Rec2020 csli 2>&1; echo $?"),
            "ERROR: Unknown color space \"Rec2020\"\n" + rec709 + "0\n");
  EXPECT_EQ(run_in(dir, "--colorspace rec709 csli"),
            "ERROR: Unknown color space \"rec709\"\n" + rec709);
}

TEST(ShadeCli, ErrorsAndUsage) {
  EXPECT_NE(run("no_such_shader").find("not found"), std::string::npos);
  EXPECT_NE(run("--help").find("usage: lobe shade"), std::string::npos);
}

} // namespace

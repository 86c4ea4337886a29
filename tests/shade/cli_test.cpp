// `lobe shade` end to end: layers, instance values, connections of each kind (announced
// first), lazy upstream layers, group files and image output, with specialisation off and on.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
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

// Runs in tests/shade/layers, so that a shader's file name is "x.osl" in messages (as oslc,
// run there, records it), not the path the search found.
std::string run_here(const std::string& args) {
  return run_cmd(std::string("cd ") + LOBE_SHADE_CORPUS + "/layers && " + LOBE_EXE + " shade " +
                 args + " 2>&1");
}

// tests/shade/layers/NAME.expected: what OSL printed (its final blank line dropped), "" if none.
std::string expected_file(const std::string& name) {
  std::ifstream f(std::string(LOBE_SHADE_CORPUS) + "/layers/" + name + ".expected");
  std::stringstream text;
  text << f.rdbuf();
  return text.str();
}

// Runs at -O0 and -O2 (specialisation off and on); both must print the same.
std::string both(const std::string& args) {
  std::string a = run("-O0 " + args), b = run("-O2 " + args);
  EXPECT_EQ(a, b) << "specialisation changed the output";
  return b;
}

// Expected output from OSL 1.13.12's testshade on the same command lines (oslc on the shaders in
// tests/shade/layers, then `testshade ARGS`), except where noted. testshade ends with a blank
// line when there is exactly one output and its file is null (so without -o, whose default is
// `-o Cout null`).
TEST(ShadeCli, ConnectionsAreAnnouncedAndFollowed) {
  // OSL 1.13.12 cannot connect one array element (an assertion fails and g is garbage); Lobe
  // connects f[1] (10) to g.
  EXPECT_EQ(both("-param scale 2.0 -layer up upstream_color -layer down downstream_print "
                 "-connect up Cout down Cin -connect up f[1] down g -connect up Cout[2] down h "
                 "-connect up pr down pr"),
            "Connect up.Cout to down.Cin\nConnect up.f[1] to down.g\nConnect up.Cout[2] to down.h\n"
            "Connect up.pr to down.pr\nupstream ran\nCin 2 4 6 g 10 h 6 pr 5 12\n\n");
  // An int for a float parameter is no float: OSL's warning, and the default stays.
  EXPECT_EQ(both("-param scale 2 -layer up upstream_color -layer down downstream_print "
                 "-connect up Cout down Cin"),
            "WARNING: attempting to set parameter with wrong type: scale (expected 'float', "
            "received 'int')\nConnect up.Cout to down.Cin\nupstream ran\nCin 1 2 3 g 0 h 0 pr 0 "
            "0\n\n");
}

// Connections OSL refuses are refused with its ConnectShaders words, its group line and exit
// status 1 (Lobe used to connect them and shade garbage); a number into a triple connects.
// Expected: OSL 1.13.12, `oslc connect_types_src.osl connect_types_dst.osl; testshade -g 1 1
// -layer A connect_types_src -layer B connect_types_dst -connect A X B Y` (stdout, then stderr).
TEST(ShadeCli, ConnectionsOfTypesOslRefusesAreErrors) {
  auto connect_from = [](const std::string& shader, const std::string& src,
                         const std::string& dst) {
    return run_cmd(std::string("cd ") + LOBE_SHADE_CORPUS + "/layers && { " + LOBE_EXE +
                   " shade -g 1 1 -layer A " + shader + " -layer B connect_types_dst -connect A " +
                   src + " B " + dst + " 2>&1; echo \"rc $?\"; }");
  };
  auto connect = [&](const std::string& src, const std::string& dst) {
    return connect_from("connect_types_src", src, dst);
  };
  const std::string group = "        group: unnamed_group_1\n";
  // OSL's words for a refused connection of src to dst: "cannot connect a <what>".
  auto refused = [&](const std::string& src, const std::string& dst, const std::string& what) {
    return "Connect A." + src + " to B." + dst + "\nERROR: ConnectShaders: cannot connect a " +
           what + "\n" + group + "rc 1\n";
  };
  EXPECT_EQ(connect("f", "i"), refused("f", "i", "float (f) to a int (i)"));
  EXPECT_EQ(connect("c", "f"), refused("c", "f", "color (c) to a float (f)"));
  EXPECT_EQ(connect("a3", "a2"), refused("a3", "a2", "float[3] (a3) to a float[2] (a2)"));
  EXPECT_EQ(connect("s", "f"), refused("s", "f", "string (s) to a float (f)"));
  // A closure is a "closure color" in OSL's words (`-layer A connect_closure_src`).
  EXPECT_EQ(connect_from("connect_closure_src", "cc", "c"),
            refused("cc", "c", "closure color (cc) to a color (c)"));
  EXPECT_EQ(connect_from("connect_closure_src", "ca", "f"),
            refused("ca", "f", "closure color[2] (ca) to a float (f)"));
  EXPECT_EQ(connect("nosuch", "f"),
            "Connect A.nosuch to B.f\nERROR: ConnectShaders: \"nosuch\" is not a parameter or "
            "global of layer \"A\" (shader \"connect_types_src\")\nERROR: ConnectShaders: cannot "
            "connect a unknown (nosuch) to a float (f), invalid connection\n" +
                group + "rc 1\n");
  // An index out of range or on a scalar connects nothing (OSL reports it and shades garbage
  // for c[5]; Lobe stops): exit 1, a ConnectShaders error.
  for (const char* bad : {"c[5]", "f[1]", "a3[3]", "c[x]"}) {
    std::string out = connect(bad, "f");
    EXPECT_NE(out.find("ERROR: ConnectShaders: "), std::string::npos) << bad << ": " << out;
    EXPECT_NE(out.find("rc 1\n"), std::string::npos) << bad << ": " << out;
  }
  // A struct connects only to the same struct type (OSL 1.13.12, `testshade -g 1 1 -layer A
  // connect_struct_src -layer B connect_struct_dst -connect A s B si` / `... B sf`).
  auto structs = [](const std::string& dst) {
    return run_cmd(std::string("cd ") + LOBE_SHADE_CORPUS + "/layers && { " + LOBE_EXE +
                   " shade -g 1 1 -layer A connect_struct_src -layer B connect_struct_dst "
                   "-connect A s B " +
                   dst + " 2>&1; echo \"rc $?\"; }");
  };
  EXPECT_EQ(structs("si"), "Connect A.s to B.si\nERROR: ConnectShaders: cannot connect a struct "
                           "SF (s) to a struct SI (si)\n" +
                               group + "rc 1\n");
  EXPECT_EQ(structs("sf"), "Connect A.s to B.sf\nsi 0 0 0 0 sf 1 1 2 3\n\nrc 0\n");
  EXPECT_EQ(connect("i", "c"),
            "Connect A.i to B.c\nf 0 i 0 c 3 3 3 s  a3 0 0 0 p 0 0 0 m 0 a2 0 0\n\nrc 0\n");
}

// A layer runs if something downstream reads a connected output, or if it has a renderer output
// (-o, by default Cout): upstream_color has a Cout, so it runs unless -o names another layer's.
TEST(ShadeCli, LayersRunAsTestshadeRunsThem) {
  EXPECT_EQ(both("-layer up upstream_color -param:type=int use 0 -layer down downstream_print "
                 "--connect up Cout down Cin -o down.Cout null"),
            "Connect up.Cout to down.Cin\n\nunused\n\n");
  EXPECT_EQ(both("-layer up upstream_color -param:type=int use 0 -layer down downstream_print "
                 "--connect up Cout down Cin"),
            "Connect up.Cout to down.Cin\nupstream ran\nunused\n\n");
  EXPECT_EQ(both("-layer up upstream_color -layer down downstream_print"),
            "upstream ran\nCin 0 0 0 g 0 h 0 pr 0 0\n\n");
  EXPECT_EQ(both("-layer up upstream_color -layer down downstream_print -o down.Cout null"),
            "\nCin 0 0 0 g 0 h 0 pr 0 0\n\n");
}

// Connections in group text are not announced (only --connect ones are).
TEST(ShadeCli, GroupTextAndGrid) {
  EXPECT_EQ(both("-g 2 1 -group \"param float scale 0.5 ; shader upstream_color up ; "
                 "shader downstream_print down ; connect up.Cout down.Cin ;\""),
            "upstream ran\nCin 0.5 1 1.5 g 0 h 0 pr 0 0\n"
            "upstream ran\nCin 0.5 1 1.5 g 0 h 0 pr 0 0\n\n");
}

// testshade's renderer: "s"/"t" user data are u/v with derivatives (before the user's own);
// --userdata adds more, of exactly the type asked; --options lockgeom=0 lets every parameter
// take user data. -param:lockgeom=1 locks nothing and -param:lockgeom=0 unlocks nothing: the
// shader's metadata decides, as testshade 1.13.12 does (`testshade -g 2 3 -param:lockgeom=1 t
// 0.25 userdata_print`: t from the user data).
TEST(ShadeCli, UserDataAndAttributes) {
  EXPECT_EQ(both("-g 2 3 -param:lockgeom=1 t 0.25 userdata_print"),
            "s 0 ds 1 0 t 0 dt 0 0.5 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 0\n"
            "s 1 ds 1 0 t 0 dt 0 0.5 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 0\n"
            "s 0 ds 1 0 t 0.5 dt 0 0.5 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 0.5\n"
            "s 1 ds 1 0 t 0.5 dt 0 0.5 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 0.5\n"
            "s 0 ds 1 0 t 1 dt 0 0.5 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 1\n"
            "s 1 ds 1 0 t 1 dt 0 0.5 tint 1 1 1 label none fixed 3 res 1 2 3 t-attr 1 1\n"
            "\n");
  EXPECT_EQ(both("--userdata:type=color tint \"0.5 0.25 2\" --userdata:type=string label "
                 "\"two words\" --userdata fixed 9 -param:type=float:lockgeom=0 fixed 4 "
                 "userdata_print"),
            "s 0.5 ds 1 0 t 0.5 dt 0 1 tint 0.5 0.25 2 label two words fixed 4 res 1 1 1 "
            "t-attr 1 0.5\n\n");
  EXPECT_EQ(both("--userdata s 0.125 userdata_print"),
            "s 0.5 ds 1 0 t 0.5 dt 0 1 tint 1 1 1 label none fixed 3 res 1 1 1 t-attr 1 0.5\n\n");
  // Group text's `interpolated=1` lets the user data bind (`testshade --userdata:type=float
  // fixed 9.0 --group "param float fixed 4 [[int interpolated=1]] ; shader userdata_print L ;"`).
  EXPECT_EQ(both("--userdata:type=float fixed 9.0 --group \"param float fixed 4 [[int "
                 "interpolated=1]] ; shader userdata_print L ;\""),
            "s 0.5 ds 1 0 t 0.5 dt 0 1 tint 1 1 1 label none fixed 9 res 1 1 1 t-attr 1 0.5\n\n");
  EXPECT_EQ(both("--userdata:type=float fixed 9.0 -param fixed 4.0 userdata_print"),
            "s 0.5 ds 1 0 t 0.5 dt 0 1 tint 1 1 1 label none fixed 4 res 1 1 1 t-attr 1 0.5\n\n");
  EXPECT_EQ(both("--userdata:type=float fixed 9.0 --options lockgeom=0 userdata_print"),
            "s 0.5 ds 1 0 t 0.5 dt 0 1 tint 1 1 1 label none fixed 9 res 1 1 1 t-attr 1 0.5\n\n");
  // Missing values are 0 and no broadcast (testshade: "1 2" for a color is 1 2 0).
  EXPECT_EQ(both("--userdata:type=color tint \"1 2\" userdata_print"),
            "s 0.5 ds 1 0 t 0.5 dt 0 1 tint 1 2 0 label none fixed 3 res 1 1 1 t-attr 1 0.5\n\n");
}

// `float a[] = {1, 2}` stays unsized: an instance value of another length sets arraylength
// (testshade 1.13.12 for float[3] and float[5]; "float[]", as long as the value, is Lobe's:
// testshade aborts on it).
TEST(ShadeCli, UnsizedArrayParameterTakesTheInstanceLength) {
  EXPECT_EQ(both("unsized_array"), "arraylength 2 sum 3 last 2\n\n");
  EXPECT_EQ(both("-param:type=float[3] a \"1 2 3\" unsized_array"),
            "arraylength 3 sum 6 last 3\n\n");
  EXPECT_EQ(both("-param:type=float[5] a 0.5,1,1.5,2,4 unsized_array"),
            "arraylength 5 sum 9 last 4\n\n");
  EXPECT_EQ(both("-param:type=float[] a \"0.5 1 1.5 2 4\" unsized_array"),
            "arraylength 5 sum 9 last 4\n\n");
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
  // An output named with its layer is announced so (OSL 1.13.12: `testshade ... -o a.fout
  // f.exr` prints `Output a.fout to f.exr`).
  out = run("-g 1 1 -layer A elide_computed -layer B elide_reader -connect A o B i -o A.o " +
            file.string());
  EXPECT_NE(out.find("\nOutput A.o to " + file.string() + "\n"), std::string::npos) << out;
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
  EXPECT_EQ(run_in(dir, "-DFOO w"), "foo\nw.osl\n\n");
  EXPECT_EQ(run_in(dir, "-D FOO -U FOO w"), "w.osl\n\n");
  EXPECT_EQ(run_in(dir, "-D FOO -UFOO w.oso"), "w.osl\n\n"); // x.oso names x, as in testshade
  scratch_dir("bad.osl", "shader bad()\n{\n    float x = 1 + nope;\n    int y = \"s\";\n}\n");
  EXPECT_EQ(run_in(dir, "bad"), "bad.osl:3:19: error: use of undeclared identifier 'nope'\n"
                                "    float x = 1 + nope;\n"
                                "                  ^~~~\n"
                                "bad.osl:4:13: error: cannot assign 'string' to 'int'\n"
                                "    int y = \"s\";\n"
                                "            ^~~\n");
}

// A shader compiled here prints its warnings as oslc prints them (a testsuite run of testshade
// follows oslc's, and OSL's testsuite records both): `file:line: warning: ...`, an ambiguous
// call with its candidates; -v shows Lobe's own form (column, source line, notes). Expected:
// OSL 1.13.12, `oslc lose.osl` and `oslc amb.osl` (then `testshade -g 1 1 lose`: "1" and the
// closing blank line).
TEST(ShadeCli, CompilerWarningsPrintAsOslcPrintsThem) {
  auto dir =
      scratch_dir("lose.osl", "shader lose()\n{\n    int d = 1.5;\n    printf(\"%d\\n\", d);\n}\n");
  const std::string lose = "lose.osl:3: warning: Assignment may lose precision: int d = float\n";
  EXPECT_EQ(run_in(dir, "-g 1 1 lose"), lose + "1\n\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 lose.osl"), lose + "1\n\n");
  EXPECT_NE(run_in(dir, "-v -g 1 1 lose").find("lose.osl:3:13: warning: "), std::string::npos);
  scratch_dir("amb.osl", "normal func () { return 1; }\nvector func () { return 2; }\n"
                         "shader amb ()\n{\n    point p = func();\n}\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 amb"), "amb.osl:5: warning: Ambiguous call to 'func ()'\n"
                                       "  Chosen function is:\n"
                                       "    amb.osl:2\tvector func ()\n"
                                       "  Other candidates are:\n"
                                       "    amb.osl:1\tnormal func ()\n\n");
}

// testshade knows its camera spaces ("camera", "screen", "NDC", "raster") only as a transform's
// destination: as a source each is an unknown space (an error; getmatrix returns 0 with its own
// half the identity, transform and the spaced constructors leave the value). common -> screen
// is testshade's matrix exactly (an inverse of its inverse left 1.1e-17 for 0). Expected: OSL
// 1.13.12, `oslc cs.osl; testshade -g 1 1 cs 2>&1`.
TEST(ShadeCli, CameraSpacesAreDestinationsOnlyAsInTestshade) {
  auto dir = scratch_dir("cs.osl",
                         "shader cs()\n{\n    matrix m = 7;\n"
                         "    int ok = getmatrix(\"camera\", \"object\", m);\n"
                         "    printf(\"%d %g | %g\\n\", ok, m, transform(\"camera\", \"object\", "
                         "point(1, 2, 3)));\n"
                         "    ok = getmatrix(\"common\", \"screen\", m);\n"
                         "    printf(\"%d %g | %g\\n\", ok, m, point(\"raster\", 1, 2, 3));\n}\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 cs"),
            "ERROR: Unknown transformation \"camera\"\n"
            "0 -4.37114e-08 -1 0 0 1 -4.37114e-08 0 0 0 0 1 0 -1 4.37114e-08 0 1 | 1 2 3\n"
            "ERROR: Unknown transformation \"raster\"\n"
            "1 1 0 0 0 0 1 0 0 0 0 1.0001 1 0 0 -0.10001 0 | 1 2 3\n\n");
}

// common -> object, shader and myspace to nine digits: lobe shade keeps each space's inverse
// (computed once, as the shadeops would at every point) and the bits are testshade's.
// Expected: OSL 1.13.12, `oslc inv.osl; testshade -g 1 1 inv`.
TEST(ShadeCli, InverseSpaceMatricesAsTestshade) {
  auto dir = scratch_dir("inv.osl",
                         "shader inv()\n{\n    matrix m;\n"
                         "    getmatrix(\"common\", \"object\", m);\n    printf(\"%.9g\\n\", m);\n"
                         "    getmatrix(\"world\", \"shader\", m);\n    printf(\"%.9g\\n\", m);\n"
                         "    getmatrix(\"common\", \"myspace\", m);\n    printf(\"%.9g\\n\", m);\n"
                         "    printf(\"%.9g | %.9g\\n\", transform(\"object\", point(1.5, -2, 3)),"
                         " transform(\"common\", \"shader\", vector(0.25, 1, -4)));\n}\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 inv"),
            "-4.37113883e-08 -1 0 0 1 -4.37113883e-08 0 0 0 0 1 0 -1 4.37113883e-08 0 1\n"
            "0.707106829 -0.707106829 0 0 0.707106829 0.707106829 0 0 0 0 1 0 -0.707106829 "
            "0.707106829 0 1\n"
            "1 0 0 0 0 0.5 0 0 0 0 1 0 0 0 0 1\n"
            "-3 -1.49999988 3 | 0.883883536 0.530330122 -4\n\n");
}

// testshade's "screen" and "raster" are perspective spaces: a point's derivatives follow the
// divide by w (at z = 3, one third of P's). Expected: OSL 1.13.12, `oslc scr.osl; testshade
// -g 1 1 scr`.
TEST(ShadeCli, PerspectiveSpaceDerivativesAsTestshade) {
  auto dir = scratch_dir("scr.osl", "shader scr()\n{\n    point p = P + point(0, 0, 2);\n"
                                    "    point q = transform(\"screen\", p);\n"
                                    "    printf(\"%.9g | %.9g | %.9g\\n\", q, Dx(q), Dy(q));\n}\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 scr"),
            "0.166666672 0.166666672 0.966763318 | 0.333333343 0 0 | 0 0.333333343 0\n\n");
}

// matrix("space", 16 values) is space -> common times the values, and the kind of a mixed
// triple sum decides its transform (point + vector is a point, which moves with the
// translation). Expected: OSL 1.13.12, `oslc ms.osl; testshade -g 1 1 ms`.
TEST(ShadeCli, SpacedMatrixAndMixedTripleTransforms) {
  auto dir = scratch_dir(
      "ms.osl",
      "shader ms()\n{\n"
      "    printf(\"%g\\n\", matrix(\"shader\", 2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, "
      "0, 1));\n"
      "    printf(\"%g\\n\", matrix(\"object\", 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, "
      "0, 1));\n"
      "    point p = point(1, 2, 3);\n    vector d = vector(0, 0, 1);\n"
      "    printf(\"%g | %g\\n\", transform(\"object\", p + d), transform(\"object\", "
      "d + p));\n}\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 ms"), "1.41421 0.707107 0 0 -1.41421 0.707107 0 0 0 0 1 0 2 0 0 1\n"
                                      "-4.37114e-08 1 0 0 -1 -4.37114e-08 0 0 0 0 1 0 5 1 0 1\n"
                                      "1 -1 4 | 1 -1 4\n\n");
}

// --entryoutput names outputs the group keeps (read by a connection or the renderer): they are
// announced after the entry layers and the Output lines; the first that is not kept stops the
// run. Expected: OSL 1.13.12, `testshade -g 1 1 -layer A elide_computed -layer B elide_reader
// -connect A o B i ARGS` (its exit status 1 on the missing one).
TEST(ShadeCli, EntryOutputsAsTestshade) {
  const std::string g = "-g 1 1 -layer A elide_computed -layer B elide_reader -connect A o B i ";
  EXPECT_EQ(run(g + "--entryoutput o"),
            "Connect A.o to B.i\nEntry outputs: o\nelide_computed ran\nreader i 2\n\n");
  EXPECT_EQ(run(g + "--entryoutput o --entryoutput o2"),
            "Connect A.o to B.i\nEntry outputs: o\nEntry output o2 not found. Abording.\n");
  EXPECT_EQ(run(g + "--entry A --entryoutput o -o A.o2 null"),
            "Connect A.o to B.i\n\nEntry layers: A(0)\nEntry outputs: o\nelide_computed ran\n\n");
  // A name may be a layer's ("A.o"), and an input parameter a connection leads into ("B.i",
  // "i"); with entry layers too, only those holding an entry output run (upstream layers as
  // they are read): none at all for --entry A --entryoutput B.i.
  EXPECT_EQ(run(g + "--entryoutput A.o"),
            "Connect A.o to B.i\nEntry outputs: A.o\nelide_computed ran\nreader i 2\n\n");
  EXPECT_EQ(run(g + "--entryoutput B.i"),
            "Connect A.o to B.i\nEntry outputs: B.i\nelide_computed ran\nreader i 2\n\n");
  EXPECT_EQ(
      run(g + "--entry A --entry B --entryoutput A.o"),
      "Connect A.o to B.i\nEntry layers: A(0) B(1)\nEntry outputs: A.o\nelide_computed ran\n\n");
  EXPECT_EQ(run(g + "--entry A --entryoutput B.i"),
            "Connect A.o to B.i\nEntry layers: A(0)\nEntry outputs: B.i\n\n");
  EXPECT_EQ(run(g + "--entry B --entryoutput i"),
            "Connect A.o to B.i\nEntry layers: B(1)\n"
            "Entry outputs: i\nelide_computed ran\nreader i 2\n\n");
}

// --expr wraps an expression in a shader of testshade's form (s, t from u, v; outputs result
// and alpha), named expr_0 in a layer expr_0_0. Expected: OSL 1.13.12, `testshade -g 2 1 --expr
// '...'`.
TEST(ShadeCli, ExpressionShader) {
  EXPECT_EQ(run("-g 2 1 --expr 'string n; getattribute(\"shader:layername\", n); "
                "result = color(s, t, 1); printf(\"%s %g %g\\n\", n, s, result);'"),
            "expr_0_0 0 0 0.5 1\nexpr_0_0 1 1 0.5 1\n\n");
  // Its parameters answer --oslquery and --entryoutput as any layer's (testshade -g 1 1
  // --oslquery --expr 'result = color(u);', and with --entryoutput result: not kept, as no
  // connection or -o reads it).
  EXPECT_EQ(run("-g 1 1 --oslquery --expr 'result = color(u);'"),
            "Shader group:\n---\nshader expr_0 expr_0_0 ;\n\n---\n\n"
            "Shader group \"unnamed_group_1\" layers are:\n    expr_0_0\n\tfloat s\n\tfloat t\n"
            "\toutput color result\n\toutput float alpha\n\n\n");
  EXPECT_EQ(run("-g 1 1 --expr 'result = color(u);' --entryoutput result"),
            "Entry outputs:\nEntry output result not found. Abording.\n");
  EXPECT_EQ(run("-g 1 1 --expr 'result = color(u);' --entryoutput result -o result null"),
            "\nEntry outputs: result\n\n");
  // Its compiler warnings, as testshade's own compile of it prints them ("WARNING: " and oslc's
  // text, repeated as oslc repeats it; `testshade --expr 'printf("%g\n", noise(P*10))'`).
  const std::string ambiguous = "WARNING: <buffer>:8: warning: Ambiguous call to 'noise (point)'\n"
                                "  Chosen function is:\n    float noise (point)\n"
                                "  Other candidates are:\n    color noise (point)\n"
                                "    vector noise (point)\n";
  EXPECT_EQ(run("--expr 'printf(\"%g\\n\", noise(P*10))'"), ambiguous + ambiguous + "0.5\n\n");
}

// Attributes as testshade answers them: the camera's whole for any object (no element by index:
// 0, the destination kept), osl:version and shader:* whatever object is named. Expected: OSL
// 1.13.12, `oslc ga.osl; testshade -g 2 1 ga` (its first point).
TEST(ShadeCli, AttributesAsTestshadeAnswersThem) {
  auto dir = scratch_dir(
      "ga.osl",
      "shader ga()\n"
      "{\n"
      "    int ir[2] = {7, 7}; int i = 7; float f = 90; float fc[2] = {5, 5}; string s = \"x\";\n"
      "    int a = getattribute(\"camera:resolution\", ir);\n"
      "    printf(\"%d %d %d\\n\", a, ir[0], ir[1]);\n"
      "    int b = getattribute(\"camera:resolution\", 0, i);\n"
      "    printf(\"%d %d\\n\", b, i);\n"
      "    int c = getattribute(\"camera:clip\", 1, f);\n"
      "    printf(\"%d %g\\n\", c, f);\n"
      "    int d = getattribute(\"object\", \"camera:resolution\", ir);\n"
      "    printf(\"%d %d %d\\n\", d, ir[0], ir[1]);\n"
      "    int e = getattribute(\"object\", \"osl:version\", i);\n"
      "    printf(\"%d %d\\n\", e, i);\n"
      "    int g = getattribute(\"\", \"camera:clip\", fc);\n"
      "    printf(\"%d %g %g\\n\", g, fc[0], fc[1]);\n"
      "    int h = getattribute(\"shader:shadername\", s);\n"
      "    int k = getattribute(\"object\", \"shader:shadername\", s);\n"
      "    printf(\"%d %d %s\\n\", h, k, s);\n"
      "    int m = getattribute(\"options\", \"blahblah\", f);\n"
      "    int n = getattribute(\"blahblah\", f);\n"
      "    printf(\"%d %d %g\\n\", m, n, f);\n"
      "}\n"
      "");
  std::string out = run_in(dir, "-g 2 1 ga");
  EXPECT_EQ(out.substr(0, out.find("1 0 3.14159\n") + 12),
            "1 2 1\n0 7\n0 90\n1 2 1\n1 11312\n1 0.1 1000\n1 1 ga\n1 0 3.14159\n");
}

// --reparam as testshade's ReParameter: a parameter interactive by its own metadata or by
// -param:interactive=1 takes the value from the second iteration; a value of another type is
// ignored without a word (5 for a float), a float for a colour sets its first component only.
// Expected: OSL 1.13.12, `testshade [-O0] -g 1 1 --iters 2 [-param...] -layer A reparam_print
// --reparam A ...`.
TEST(ShadeCli, ReparamAsTestshade) {
  EXPECT_EQ(run("-g 1 1 --iters 2 -layer A reparam_print --reparam A f 5.0"),
            "f=1 c=1 1 1\nf=5 c=1 1 1\n\n");
  EXPECT_EQ(run("-g 1 1 --iters 2 -layer A reparam_print --reparam A f 5"),
            "f=1 c=1 1 1\nf=1 c=1 1 1\n\n");
  EXPECT_EQ(run("-g 1 1 --iters 2 -param:interactive=1 c 0.5 -layer A reparam_print "
                "--reparam A c 0.25"),
            "f=1 c=0.5 0.5 0.5\nf=1 c=0.25 0.5 0.5\n\n");
  EXPECT_EQ(run("-g 1 1 --iters 2 -layer A reparam_print --reparam A c 0.25"),
            "f=1 c=1 1 1\nf=1 c=1 1 1\n\n");
  // A parameter not declared interactive that the group still has is an error (at -O0 every
  // one; at -O2, as above, a plain one is folded away and nothing is said).
  EXPECT_EQ(run("-O0 -g 1 1 --iters 2 -layer A reparam_print --reparam A c 0.25"),
            "ERROR: ReParameter cannot adjust A.c, which was not declared interactive\n"
            "f=1 c=1 1 1\nf=1 c=1 1 1\n\n");
  // A value of the same base type and size is taken: an untyped 7,8,9 (a vector) for a
  // float[3] (`testshade --iters 2 -layer L rp --reparam L fa 7,8,9`).
  auto dir = scratch_dir("rp.osl", "shader rp (float fa[3] = {1,2,3} [[ int interactive = 1 ]])"
                                   " { printf (\"fa = %g\\n\", fa); }\n");
  EXPECT_EQ(run_in(dir, "--iters 2 -layer L rp --reparam L fa 7,8,9"),
            "fa = 1 2 3\nfa = 7 8 9\n\n");
}

// --userdata_isconnected (OSL's userdata_isconnected): isconnected() is 1 for a parameter that
// takes user data (lockgeom = 0), given or not. Expected: OSL 1.13.12, `oslc uc.osl; testshade
// -g 1 1 [--userdata_isconnected --userdata a 5.0] uc`.
TEST(ShadeCli, UserdataIsconnected) {
  auto dir = scratch_dir("uc.osl", "shader uc(float a = 1 [[int lockgeom = 0]], color c = 0 "
                                   "[[int lockgeom = 0]], float b = 2)\n{\n    printf(\"%g %d "
                                   "%d %d\\n\", a, isconnected(a), isconnected(c), "
                                   "isconnected(b));\n}\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 uc"), "1 0 0 0\n\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 --userdata_isconnected --userdata a 5.0 uc"), "5 1 1 0\n\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 --options userdata_isconnected=1 uc"), "1 1 1 0\n\n");
}

// --oslquery lists each layer's parameters as OSLQuery does, under the group as -v prints it
// (the shader as it was named). Expected: OSL 1.13.12, `oslc connect_struct_src.osl;
// testshade -g 1 1 --oslquery -layer A connect_struct_src`.
TEST(ShadeCli, OslqueryListsTheLayersParameters) {
  EXPECT_EQ(run_here("-g 1 1 --oslquery -layer A connect_struct_src"),
            "Shader group:\n---\nshader connect_struct_src A ;\n\n---\n\n"
            "Shader group \"unnamed_group_1\" layers are:\n    A\n\toutput unknown s\n"
            "\toutput float s.a\n\toutput color s.c\n\n\n");
}

// -v prints each connection after the layer it leads into, as OSL's group text has them.
// Expected: OSL 1.13.12, `testshade -g 1 1 -v -layer A elide_computed -layer B elide_reader
// -layer C eager_down -connect A o B i -connect A o2 C x`.
TEST(ShadeCli, VerboseConnectionsFollowTheirLayer) {
  EXPECT_EQ(run_here("-g 1 1 -v -layer A elide_computed -layer B elide_reader -layer C eager_down "
                     "-connect A o B i -connect A o2 C x"),
            "Connect A.o to B.i\nConnect A.o2 to C.x\nShader group:\n---\n"
            "shader elide_computed A ;\nshader elide_reader B ;\nconnect A.o B.i ;\n"
            "shader eager_down C ;\nconnect A.o2 C.x ;\n\n---\n\n"
            "Shader group \"unnamed_group_1\" layers are:\n    A\n    B\n    C\n\n"
            "eager_down skips\n\n");
}

// -v prints a whole struct's connection one line per leaf field, nested structs included, as
// OSL's group text (`testshade -g 1 1 -v -layer A struct_conn_src -layer B struct_conn_dst
// -connect A mx B m`, OSL 1.13.12).
TEST(ShadeCli, VerboseStructConnectionsListTheirLeaves) {
  EXPECT_EQ(
      run_here("-g 1 1 -v -layer A struct_conn_src -layer B struct_conn_dst -connect A mx B m"),
      "Connect A.mx to B.m\nShader group:\n---\nshader struct_conn_src A ;\n"
      "shader struct_conn_dst B ;\nconnect A.mx.c B.m.c ;\nconnect A.mx.f B.m.f ;\n"
      "connect A.mx.name B.m.name ;\nconnect A.mx.i B.m.i ;\n"
      "connect A.mx.in.a B.m.in.a ;\nconnect A.mx.in.b B.m.in.b ;\n\n---\n\n"
      "Shader group \"unnamed_group_1\" layers are:\n    A\n    B\n\nf 0.5 a 4\n\n");
}

// Hints on a group text's param as testshade takes them: comma-separated in the first [[ ]]
// (interactive, lockgeom = 0 printed as interpolated), `param color c 0.5` one component (the
// others 0), and --reparam of the interactive c then changes that component alone
// (`testshade -g 1 1 [-v | --iters 2 --reparam A c 0.25] -group 'param color c 0.5 [[int
// interactive=1, int lockgeom=0]] ; shader reparam_print A ;'`, OSL 1.13.12).
TEST(ShadeCli, GroupTextHints) {
  const std::string g =
      "-group 'param color c 0.5 [[int interactive=1, int lockgeom=0]] ; shader reparam_print A ;'";
  EXPECT_EQ(run_here("-g 1 1 -v " + g),
            "Processing group specification:\n---\nparam color c 0.5 [[int interactive=1, int "
            "lockgeom=0]] ; shader reparam_print A ;\n---\nShader group:\n---\n"
            "param color c 0.5 0 0 [[int interpolated=1]] [[int interactive=1]] ;\n"
            "shader reparam_print A ;\n\n---\n\nShader group \"unnamed_group_2\" layers are:\n"
            "    A\n\nf=1 c=0.5 0 0\n\n");
  EXPECT_EQ(run_here("-g 1 1 --iters 2 --reparam A c 0.25 " + g),
            "f=1 c=0.5 0 0\nf=1 c=0.25 0 0\n\n");
}

// "rgb" is no space transform(), the spaced constructors, getmatrix() or matrix(from, to)
// know: one error (repeats are not printed again) and the identity, getmatrix() 0, as OSL
// 1.13.12 gives (`testshade [-O0] -g 1 1 rgbspace`, both levels alike; `rgbspace_transform`:
// transform() alone reports it too).
TEST(ShadeCli, RgbIsNoTransformationSpace) {
  auto dir = scratch_dir("rgbspace.osl",
                         "shader rgbspace()\n{\n    point p = transform(\"rgb\", point(1, 2, 3));\n"
                         "    point q = point(\"rgb\", 4, 5, 6);\n    matrix m;\n"
                         "    int ok = getmatrix(\"rgb\", \"common\", m);\n"
                         "    matrix a = matrix(\"common\", \"rgb\");\n"
                         "    vector w = transform(\"common\", \"rgb\", vector(1, 0, 0));\n"
                         "    printf(\"%g | %g | %d | %g | %g\\n\", p, q, ok, a[0][0], w);\n}\n");
  const std::string expected = "ERROR: Unknown transformation \"rgb\"\n"
                               "1 2 3 | 4 5 6 | 0 | 1 | 1 0 0\n\n";
  EXPECT_EQ(run_in(dir, "-g 1 1 rgbspace"), expected);
  EXPECT_EQ(run_in(dir, "-O0 -g 1 1 rgbspace"), expected);
  auto alone =
      scratch_dir("rgbspace_transform.osl", "shader rgbspace_transform()\n{\n    printf(\"%g\\n\", "
                                            "transform(\"rgb\", point(1, 2, 3)));\n}\n");
  EXPECT_EQ(run_in(alone, "-g 1 1 rgbspace_transform"),
            "ERROR: Unknown transformation \"rgb\"\n1 2 3\n\n");
}

// At -O2 OSL folds fmod() of triples with C's fmod, so a zero component of the divisor gives nan
// (a float's folds to 0); the elements of a printed closure array run together
// (`testshade -g 1 1 fmodfold`, OSL 1.13.12).
TEST(ShadeCli, TripleFmodFoldsAndClosureArraysPrintAsOsl) {
  auto dir = scratch_dir("fmodfold.osl",
                         "shader fmodfold()\n{\n    vector b = vector(4, 4, 0) + u * 0;\n"
                         "    printf(\"%g | %g | %g\\n\", fmod(color(5, -6, 7), color(4, 4, 0)), "
                         "fmod(vector(5, -6, 7), b), fmod(5.0, 0.0));\n"
                         "    closure color two[2] = { diffuse(N), 0.5 * emission() };\n"
                         "    printf(\"<%s>\\n\", two);\n}\n");
  // An all-zero divisor (or a float 0) folds to 0 as at run time (`testshade -g 1 1 fmodzero`).
  auto zero = scratch_dir("fmodzero.osl",
                          "shader fmodzero() { printf(\"%g | %g | %g | %g\\n\", fmod(color(1,2,3), "
                          "0.0), fmod(color(1,2,3), color(0)), fmod(color(0), color(2,0,1)), "
                          "fmod(color(5,6,7), color(2,0,4))); }\n");
  EXPECT_EQ(run_in(zero, "-g 1 1 fmodzero"), "0 0 0 | 0 0 0 | 0 nan 0 | 1 nan 3\n\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 fmodfold"),
            "1 -2 nan | 1 -2 nan | 0\n<(1, 1, 1) * diffuse ((0, 0, 1), \"label\", \"\")(0.5, 0.5, "
            "0.5) * emission ()>\n\n");
}

// An input connected in and on (B.bi from A, on to C) carries A's value to C although B never
// reads it: A runs when B finishes (`testshade -O<n> -g 2 1 -layer A passon_up -layer B
// passon_mid -layer C passon_down -connect A fo B bi -connect B bi C ci`, OSL 1.13.12).
TEST(ShadeCli, ConnectedInputsLeadTheirUpstreamValueOn) {
  EXPECT_EQ(both("-g 2 1 -layer A passon_up -layer B passon_mid -layer C passon_down -connect A fo "
                 "B bi -connect B bi C ci"),
            "Connect A.fo to B.bi\nConnect B.bi to C.ci\nmid: bj=-2\nup: fo=11\ndown: ci=11\n"
            "mid: bj=-2\nup: fo=12\ndown: ci=12\n\n");
}

// The layer named after a shader given as a file is the name without folder or extension
// (OSL 1.13.12: `testshade -g 1 1 gac.oso` prints gac_0 for getattribute("shader:layername")).
TEST(ShadeCli, LayerNamesDropTheExtension) {
  auto dir = scratch_dir("gac.osl", "shader gac()\n{\n    string s;\n"
                                    "    getattribute(\"shader:layername\", s);\n"
                                    "    printf(\"%s\\n\", s);\n}\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 gac.oso"), "gac_0\n\n");
  EXPECT_EQ(run_in(dir, "-g 1 1 gac.osl"), "gac_0\n\n");
}

// --colorspace sets the material's colour space. Expected: OSL 1.13.12,
//   oslc csli.osl; stdbuf -oL testshade [--colorspace NAME] csli 2>&1; echo $?
// (testshade's closing blank line included): an unknown name (names are case-sensitive) is
// reported once before shading, which goes on in Rec709, with exit status 0.
TEST(ShadeCli, ColorspaceOption) {
  auto dir = scratch_dir("csli.osl", "shader csli()\n{\n    printf(\"%.9g | %.9g\\n\", "
                                     "luminance(color(0.1, 0.7, 0.2)), transformc(\"XYZ\", "
                                     "color(1, 0.5, 0.25)));\n}\n");
  const std::string rec709 = "0.536424339 | 0.636061966 0.588217974 0.316401064\n\n";
  EXPECT_EQ(run_in(dir, "csli 2>&1; echo $?"), rec709 + "0\n");
  EXPECT_EQ(run_in(dir, "--colorspace ACEScg csli 2>&1; echo $?"),
            "0.509817958 | 0.768503129 0.622691929 0.249040425\n\n0\n");
  EXPECT_EQ(run_in(dir, "-colorspace NTSC -O0 csli"),
            "0.463418633 | 0.743757248 0.620860696 0.311986387\n\n");
  EXPECT_EQ(run_in(dir, "--colorspace Rec2020 csli 2>&1; echo $?"),
            "ERROR: Unknown color space \"Rec2020\"\n" + rec709 + "0\n");
  EXPECT_EQ(run_in(dir, "--colorspace rec709 csli"),
            "ERROR: Unknown color space \"rec709\"\n" + rec709);
}

TEST(ShadeCli, ErrorsAndUsage) {
  // Every shader not found, in testshade's words (OSL 1.13.12: `testshade -g 1 1 -layer a
  // nosuch -layer b nosuch2`; it then goes on with nothing to shade, to its closing blank
  // line, with exit status 0; Lobe's is 1).
  EXPECT_EQ(run("-layer a no_such_shader -layer b no_such_2 -groupname G"),
            "ERROR: No .oso file could be found for shader \"no_such_shader\"\n"
            "ERROR: Could not find shader \"no_such_shader\"\n        group: G\n"
            "ERROR: No .oso file could be found for shader \"no_such_2\"\n"
            "ERROR: Could not find shader \"no_such_2\"\n        group: G\n\n");
  EXPECT_NE(run("--help").find("Usage: lobe shade"), std::string::npos);
  EXPECT_EQ(run("--bogus unsized_array"),
            "lobe shade: error: Invalid option \"--bogus\" (lobe shade --help lists them)\n");
  EXPECT_EQ(run("-g 2"), "lobe shade: error: Missing parameter 2 from option \"-g\"\n");
  // A size past int's range (read as an int it wrapped round to 1).
  EXPECT_EQ(run("-g 4294967297 1 unsized_array"),
            "lobe shade: error: -g 4294967297 1: 4294967297 is too large a grid size\n");
  EXPECT_EQ(run("unsized_array -param a 1.0"),
            "ERROR: Pending parameters without a shader: a\n"
            "Did you mistakenly put --param after the shader declaration?\n");
  EXPECT_EQ(run(""), "ERROR: No shader or group was specified.\n\n"
                     "Try `lobe shade --help` for an explanation of all arguments\n");
}

// A layer whose shader is not found is left out and the other layers shade, as testshade shades
// them; a connection from or into it is then an error. Expected: OSL 1.13.12, `testshade -g 1 1
// ARGS` in tests/shade/layers (its exit status 0 where the others shade; Lobe's is 1, as for any
// file not found).
TEST(ShadeCli, AMissingShaderIsLeftOutAndTheOtherLayersShade) {
  const std::string missing = "ERROR: No .oso file could be found for shader \"nosuch\"\n"
                              "ERROR: Could not find shader \"nosuch\"\n"
                              "        group: unnamed_group_1\n";
  auto status = [](const std::string& args) {
    return run_here("-g 1 1 " + args + " >/dev/null 2>&1; echo $?");
  };
  const std::string connected = "-layer A ms_a -layer M nosuch -layer B ms_b -connect A f B x";
  EXPECT_EQ(run_here("-g 1 1 " + connected), missing + "Connect A.f to B.x\nms_b runs 1\n\n");
  EXPECT_EQ(status(connected), "1\n");
  EXPECT_EQ(run_here("-g 1 1 -layer A ms_a -layer M nosuch"), missing + "ms_a runs 1\n\n");
  // An empty grid shades nothing (OSL 1.13.12: `testshade -g 4 0 ms_a`, `-g 0 3 --print -o f
  // null ms_a`).
  EXPECT_EQ(run_here("-g 4 0 ms_a"), "\n");
  EXPECT_EQ(run_here("-g 0 3 --print -o f null ms_a"), "\n\n");
  EXPECT_EQ(run_here("-g 1 1 -v " + connected),
            missing + "Connect A.f to B.x\nShader group:\n---\nshader ms_a A ;\nshader ms_b B ;\n"
                      "connect A.f B.x ;\n\n---\n\nShader group \"unnamed_group_1\" layers are:\n"
                      "    A\n    B\n\nms_b runs 1\n\n");
  EXPECT_EQ(run_here("-g 1 1 -layer A ms_a -layer M nosuch -layer B ms_b -connect M y B x"),
            missing + "Connect M.y to B.x\nERROR: ConnectShaders: source layer \"M\" not found\n"
                      "        group: unnamed_group_1\n");
}

// Probes where Lobe once printed otherwise than OSL (layers/parity_probes.osl says which), at
// -O2 and -O0, whose outputs differ where OSL's -O2 folds. Expected: layers/parity_probes.expected
// and parity_probes.O0.expected, from OSL 1.13.12 (`testshade -g 2 1 [-O0] parity_probes`).
TEST(ShadeCli, ParityProbesPrintAsOsl) {
  std::string o2 = expected_file("parity_probes"), o0 = expected_file("parity_probes.O0");
  ASSERT_FALSE(o2.empty());
  ASSERT_FALSE(o0.empty());
  EXPECT_EQ(run("-O2 -g 2 1 parity_probes"), o2 + "\n");
  EXPECT_EQ(run("-O0 -g 2 1 parity_probes"), o0 + "\n");
}

// `[[ int interpolated = N ]]` makes a parameter take user data as lockgeom = !N does, the last
// of the two counting. Expected: OSL 1.13.12, `testshade [-O0] --userdata:type=float b 2 ...
// --userdata:type=float f 6 interpolated_userdata`.
TEST(ShadeCli, InterpolatedMetadataTakesUserData) {
  std::string ud;
  for (const char* p : {"b 2", "c 3", "d 4", "e 5", "f 6"})
    ud += std::string("--userdata:type=float ") + p + " ";
  EXPECT_EQ(both(ud + "interpolated_userdata"), "b 2 c -1 d -1 e -1 f 6\n\n");
}

// At -O2 a local whose only write is a constant in a branch reads as that constant also where
// the branch did not run. Expected: OSL 1.13.12, `testshade -g 2 1 branch_only_constant`.
TEST(ShadeCli, OnceAssignedLocalsAreConstantsAtO2) {
  EXPECT_EQ(run("-O2 -g 2 1 branch_only_constant"), "x 1 c 1 2 3\nx 1 c 1 2 3\n\n");
}

// --options lazylayers=0 runs every layer the group needs at the start of each shade, in order,
// lazylayers=1 (the default) an upstream one when its output is first read. Expected: OSL
// 1.13.12, `testshade -O<n> -g 2 1 --options lazylayers=<L> -layer A eager_up -layer B
// eager_down -connect A o B x`, and (-O0) with elide_computed/elide_reader.
TEST(ShadeCli, LazyLayersOptionAsTestshade) {
  const std::string g = "-g 2 1 -layer A eager_up -layer B eager_down -connect A o B x";
  EXPECT_EQ(both("--options lazylayers=0 " + g),
            "Connect A.o to B.x\neager_up 0\neager_down skips\neager_up 1\neager_down 11\n\n");
  EXPECT_EQ(both("--options lazylayers=1 " + g),
            "Connect A.o to B.x\neager_down skips\neager_up 1\neager_down 11\n\n");
  EXPECT_EQ(run("-O0 -g 1 1 --options lazylayers=0 -layer A elide_computed -param:type=int use 0 "
                "-layer B elide_reader -connect A o B i"),
            "Connect A.o to B.i\nelide_computed ran\nreader ignores i\n\n");
}

// trace() and getmessage("trace", ...) answer as testshade's stand-in renderer does (no scene:
// layers/trace_testshade.osl says how), at both levels. Expected: layers/trace_testshade.expected,
// from OSL 1.13.12 (`testshade -g 3 3 trace_testshade`; testshade's final blank line added here).
TEST(ShadeCli, TraceAnswersAsTestshade) {
  std::string expected = expected_file("trace_testshade");
  ASSERT_FALSE(expected.empty());
  EXPECT_EQ(both("-g 3 3 trace_testshade"), expected + "\n");
}

// A connection from an input parameter: the downstream layer reads the value the parameter
// holds (its instance value, not the garbage of a parameter folded to a constant), and at -O2,
// as in OSL, a value known before shading replaces the connection and the upstream layer does
// not run; a computed default given an instance value keeps it running (OSL 1.13.12 -O2).
// Expected: OSL 1.13.12, `oslc inparam_src.osl inparam_dst.osl; testshade -g 2 1 -O2|-O0
// -param ... -layer a inparam_src -layer b inparam_dst -connect a f b g -connect a k b h`.
TEST(ShadeCli, InputParamConnectedOnward) {
  const std::string group =
      " -layer a inparam_src -layer b inparam_dst -connect a f b g -connect a k b h";
  const std::string connects = "Connect a.f to b.g\nConnect a.k to b.h\n";
  EXPECT_EQ(run_here("-g 2 1 -O2 -param f 3.0" + group), connects + "dst g 3 h 0\ndst g 3 h 1\n\n");
  EXPECT_EQ(run_here("-g 2 1 -O2 -param k 2.0" + group),
            connects + "src f 1 k 2\ndst g 1 h 2\nsrc f 1 k 2\ndst g 1 h 2\n\n");
  EXPECT_EQ(run_here("-g 2 1 -O0 -param f 3.0" + group),
            connects + "src f 3 k 0\ndst g 3 h 0\nsrc f 3 k 1\ndst g 3 h 1\n\n");
}

// -v prints the group as OSL's group text: the instance values a layer took, in the shader's
// parameter order, with the parameter's type, %.9g floats, quoted strings and their
// interpolated/interactive marks (a value given twice: the last); connected parameters' values
// left out; --group's text echoed first. Expected: OSL 1.13.12, `oslc group_verbose.osl;
// testshade ARGS` with the same arguments.
TEST(ShadeCli, VerboseGroupText) {
  EXPECT_EQ(run_here("-v -param:lockgeom=0 f 0.25 -param:type=float[3] ua 1,2,3 -param st.a 2.0 "
                     "-param s 'he\"l\\lo' -param:interpolated=1 i 4 -param:type=matrix m "
                     "1,0,0,0,0,2,0,0,0,0,1,0,0,0,0,1 -param l 1e-10 -param:type=color p 0.1 "
                     "-param:interactive=1 k 2.0 -param i 7 group_verbose"),
            "Shader group:\n---\n"
            "param float f 0.25 [[int interpolated=1]] ;\n"
            "param float[3] ua 1 2 3 ;\n"
            "param float st.a 2 ;\n"
            "param string s \"he\\\"l\\\\lo\" ;\n"
            "param int i 7 ;\n"
            "param matrix m 1 0 0 0 0 2 0 0 0 0 1 0 0 0 0 1 ;\n"
            "param float l 1.00000001e-10 ;\n"
            "param point p 0.100000001 0 0 ;\n"
            "param float k 2 [[int interactive=1]] ;\n"
            "shader group_verbose group_verbose_0 ;\n\n---\n\n"
            "Shader group \"unnamed_group_1\" layers are:\n    group_verbose_0\n\n"
            "f 0.25 ua 3 l 1e-10 p 0.1 0 0\n\n");
  EXPECT_EQ(run_here("-v -group 'param float f 0.5 ; shader group_verbose a ; param float l 0.25 "
                     "; param float k 3.0 ; shader group_verbose b ; connect a.f b.l ;'"),
            "Processing group specification:\n---\n"
            "param float f 0.5 ; shader group_verbose a ; param float l 0.25 ; param float k 3.0 "
            "; shader group_verbose b ; connect a.f b.l ;\n---\n"
            "Shader group:\n---\n"
            "param float f 0.5 ;\nshader group_verbose a ;\n"
            "param float k 3 ;\nshader group_verbose b ;\n"
            "connect a.f b.l ;\n\n---\n\n"
            "Shader group \"unnamed_group_2\" layers are:\n    a\n    b\n\n"
            "f 0 ua 1 l 0.5 p 0 0 0\n\n");
  // Not locked to the geometry: the shader's lockgeom = 0 (whatever the value says) and the
  // lockgeom=0 option mark a value; a value of the wrong type given last leaves the one before.
  // (`testshade -v ... group_lockgeom`, same arguments.)
  const std::string tail = "shader group_lockgeom group_lockgeom_0 ;\n\n---\n\n"
                           "Shader group \"unnamed_group_1\" layers are:\n    group_lockgeom_0\n\n";
  EXPECT_EQ(run_here("-v -param f 1.5 -param f 2 -param g 1.0 -param:lockgeom=1 h 2.0 "
                     "group_lockgeom"),
            "WARNING: attempting to set parameter with wrong type: f (expected 'float', received "
            "'int')\nShader group:\n---\nparam float f 1.5 ;\n"
            "param float g 1 [[int interpolated=1]] ;\nparam float h 2 ;\n" +
                tail + "1.5 1 2\n\n");
  EXPECT_EQ(run_here("-v --options lockgeom=0 -param f 1.0 -param:lockgeom=1 h 2.0 "
                     "group_lockgeom"),
            "Shader group:\n---\nparam float f 1 [[int interpolated=1]] ;\n"
            "param float h 2 [[int interpolated=1]] ;\n" +
                tail + "1 0 2\n\n");
}

// A warning inside argument i of a call prints i + 1 times (the first argument is 0), as oslc
// prints it, nested calls multiplying: 25 ambiguous-call blocks here. Expected:
// layers/ambiguous_printf.expected, from OSL 1.13.12 (`oslc ambiguous_printf.osl; testshade
// ambiguous_printf`, oslc's "Compiled" line dropped; testshade's final blank line added here).
TEST(ShadeCli, WarningsInArgumentsRepeatAsOslcPrintsThem) {
  std::string expected = expected_file("ambiguous_printf");
  ASSERT_FALSE(expected.empty());
  EXPECT_EQ(run_here("ambiguous_printf"), expected + "\n");
}

// --debuguninit numbers ops as OSL does with output parameters that are read downstream (the
// default renderer output Cout, a computed default): OSL begins the main code with a useparam
// op of them, so the first printf is op 2 (after g's default). Expected: OSL 1.13.12, `oslc
// debug_uninit_outputs.osl; testshade -O0 --debuguninit debug_uninit_outputs`.
TEST(ShadeCli, DebugUninitCountsOslsOutputUseparam) {
  auto line = [](const char* var, int l, int op) {
    return "ERROR: Detected possible use of uninitialized value in float " + std::string(var) +
           " at debug_uninit_outputs.osl:" + std::to_string(l) +
           " (group unnamed_group_1, layer 0 debug_uninit_outputs_0, shader "
           "debug_uninit_outputs, op " +
           std::to_string(op) + " 'printf', arg 1)\n";
  };
  EXPECT_EQ(run_here("-O0 --debuguninit debug_uninit_outputs"),
            line("a", 5, 2) + "a 0\n" + line("b", 7, 3) + "b 0\n\n");
}

// An out-of-range element or component store that no path reads afterwards: OSL's -O2 drops
// the store and its range error, -O0 and -O1 report it. Expected: OSL 1.13.12, `oslc
// range_dead_store.osl; testshade -O0|-O1|-O2 range_dead_store`.
TEST(ShadeCli, DeadStoresOutOfRange) {
  auto err = [](const char* v, const char* idx, int line) {
    return "ERROR: Index [" + std::string(idx) + "] out of range " + v +
           "[0..2]: range_dead_store.osl:" + std::to_string(line) +
           " (group unnamed_group_1, layer 0 range_dead_store_0, shader range_dead_store)\n";
  };
  const std::string all = err("a", "-1", 5) + "a[-1] = 0.5\n" + err("a", "5", 6) +
                          err("c", "5", 8) + err("c", "-1", 9) + "c 0.5\n" + err("c", "5", 10) +
                          "\n";
  EXPECT_EQ(run_here("-O0 range_dead_store"), all);
  EXPECT_EQ(run_here("-O1 range_dead_store"), all);
  EXPECT_EQ(run_here("-O2 range_dead_store"), err("a", "-1", 5) + "a[-1] = 0.5\n" +
                                                  err("c", "5", 8) + err("c", "-1", 9) +
                                                  "c 0.5\n\n");
}

// `lobe shade x` runs the x.lir `lobe compile -DX` wrote (testshade runs oslc's x.oso), until
// x.osl is edited; given -D itself, it compiles the source, where the definition applies.
TEST(ShadeCli, RunsTheCompiledFormUnlessTheSourceIsNewerOrDefinesAreGiven) {
  auto dir =
      std::filesystem::temp_directory_path() / ("lobe_shade_lir_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "w.osl") << "shader w() {\n#ifdef FOO\n  printf(\"foo\\n\");\n#else\n"
                                  "  printf(\"plain\\n\");\n#endif\n}\n";
  std::filesystem::last_write_time(dir / "w.osl", std::filesystem::file_time_type::clock::now() -
                                                      std::chrono::seconds(10));
  std::string in = "cd " + dir.string() + " && " + LOBE_EXE;
  run_cmd(in + " compile -DFOO w.osl 2>&1");
  EXPECT_EQ(run_cmd(in + " shade w 2>&1"), "foo\n\n");
  run_cmd(in + " compile w.osl 2>&1");
  EXPECT_EQ(run_cmd(in + " shade -DFOO w 2>&1"), "foo\n\n");
  std::filesystem::last_write_time(dir / "w.osl", std::filesystem::file_time_type::clock::now() +
                                                      std::chrono::seconds(10));
  run_cmd(in + " compile -DFOO w.osl -o w.lir 2>&1"); // still older than the "edited" source
  std::filesystem::last_write_time(dir / "w.lir", std::filesystem::file_time_type::clock::now());
  EXPECT_EQ(run_cmd(in + " shade w 2>&1"), "plain\n\n");
  std::filesystem::remove_all(dir);
}

// getmessage ignores a source other than "trace": a message set upstream is read whatever
// source is named, and a query naming one counts as a query (the "queried before being set"
// error points at it). Expected: OSL 1.13.12, `oslc msg_src_set.osl msg_src_get.osl;
// testshade -O0 -layer A msg_src_set [-param early 1] -layer B msg_src_get -connect A o B i`.
TEST(ShadeCli, GetmessageIgnoresItsSource) {
  const std::string group = "-layer A msg_src_set -layer B msg_src_get -connect A o B i";
  EXPECT_EQ(run_here("-O0 " + group), "Connect A.o to B.i\n1: 1 3 1 3 1 3\n\n");
  EXPECT_EQ(run_here("-O0 -layer A msg_src_set -param early 1 -layer B msg_src_get -connect A o "
                     "B i"),
            "Connect A.o to B.i\nearly 0\nERROR: message \"msg\" was queried before being set "
            "(queried here: msg_src_get.osl:5) setting it now (msg_src_set.osl:3) would lead to "
            "inconsistent results\n1: 0 -1 0 -1 0 -1\n\n");
}

// --debugnan at -O0, as `testshade -t 1 -O0 --debugnan -g 2 1 debug_nan` (OSL 1.13.12) prints
// it: the same lines, OSL's stderr apart from its stdout where Lobe prints each point's errors
// before its printf. Each message once (an identical one is not repeated); exit status 0.
TEST(ShadeCli, DebugNanReportsNonFiniteResults) {
  auto run = run_here;
  const std::string point0 =
      "ERROR: Detected inf value in big at debug_nan.osl:5 (op mul)\n"
      "ERROR: Detected inf value in inf at debug_nan.osl:6 (op mul)\n"
      "ERROR: Detected inf value in arr at debug_nan.osl:8 (op aassign)\n"
      "ERROR: Detected -nan value in n at debug_nan.osl:11 (op sub)\n"
      "ERROR: Detected -nan value in cc at debug_nan.osl:12 (op compassign)\n"
      "ERROR: Detected -nan value in w at debug_nan.osl:14 (op mul)\n"
      "ERROR: Detected -nan value in dv at debug_nan.osl:15 (op vector)\n"
      "ERROR: Detected -inf value in ninf at debug_nan.osl:16 (op neg)\n"
      "ERROR: Detected -inf value in m at debug_nan.osl:18 (op mxcompassign)\n"
      "ERROR: Detected inf value in the derivatives of y at debug_nan.osl:20 (op mul)\n"
      "ERROR: Detected inf value in d at debug_nan.osl:21 (op Dx)\n"
      "ERROR: Detected inf value in r at debug_nan.osl:23 (op assign)\n"
      "ERROR: Detected -nan value in c at debug_nan.osl:24 (op assign)\n"
      "r inf c 2 1 -nan q -87.3365\n";
  const std::string point1 = "ERROR: Detected inf value in w at debug_nan.osl:14 (op mul)\n"
                             "ERROR: Detected inf value in dv at debug_nan.osl:15 (op vector)\n"
                             "ERROR: Detected inf value in y at debug_nan.osl:20 (op mul)\n"
                             "r inf c 2 1 -nan q 1\n\n";
  EXPECT_EQ(run("-t 1 -O0 --debugnan -g 2 1 debug_nan"), point0 + point1);
  EXPECT_EQ(run("-O0 --options debug_nan=1 -g 2 1 debug_nan"), point0 + point1);
  // Without the option nothing is checked.
  EXPECT_EQ(run("-O0 -g 2 1 debug_nan"), "r inf c 2 1 -nan q -87.3365\nr inf c 2 1 -nan q 1\n\n");
  // -O2 checks what remains after optimisation; OSL's optimiser removes more (it also keeps
  // only big and inf here), so only those two are asserted.
  std::string o2 = run("-O2 --debugnan -g 2 1 debug_nan");
  EXPECT_NE(o2.find("ERROR: Detected inf value in big at debug_nan.osl:5 (op mul)\n"),
            std::string::npos)
      << o2;
  EXPECT_NE(o2.find("ERROR: Detected inf value in inf at debug_nan.osl:6 (op mul)\n"),
            std::string::npos)
      << o2;
}

// --debuguninit at -O0, as `testshade -t 1 -O0 --debuguninit -g 2 1 debug_uninit` (OSL
// 1.13.12) prints it (the same lines; Lobe prints each point's errors before its printf). A
// value found uninitialised is set to 0 (x prints 0 at the first point, i + 1 is 1); an
// element or component read checks only that one (arr[1] and cc[0] were written); a
// non-finite float read counts too (big). At u = 1 x is written, the rest repeats.
TEST(ShadeCli, DebugUninitReportsReadsBeforeWrites) {
  auto run = run_here;
  auto at = [](const std::string& what, int line, int op, const std::string& name, int arg) {
    return "ERROR: Detected possible use of uninitialized value in " + what +
           " at debug_uninit.osl:" + std::to_string(line) +
           " (group unnamed_group_1, layer 0 debug_uninit_0, shader debug_uninit, op " +
           std::to_string(op) + " '" + name + "', arg " + std::to_string(arg) + ")\n";
  };
  const std::string expected =
      at("float[4] arr", 14, 4, "aref", 1) + at("float x", 14, 5, "add", 1) +
      at("int i", 15, 8, "add", 1) + at("color cc", 16, 9, "compref", 1) +
      at("matrix m", 18, 13, "mxcompref", 1) + at("float big", 20, 18, "add", 2) +
      at("float[4] arr", 21, 19, "aref", 1) + at("string s", 21, 20, "printf", 3) +
      "x 0 i 1 s '' arr 0 r 3 big 0\n"
      "x 1 i 1 s '' arr 0 r 4 big 0\n\n";
  EXPECT_EQ(run("-t 1 -O0 --debuguninit -g 2 1 debug_uninit"), expected);
  EXPECT_EQ(run("-O0 --options debug_uninit=1 -g 2 1 debug_uninit"), expected);
  // Op numbers as OSL counts them, with its useparam ops (`testshade -O0 --debuguninit
  // debug_uninit_params`, OSL 1.13.12).
  auto in = [](const std::string& var, int line, int op) {
    return "ERROR: Detected possible use of uninitialized value in float " + var +
           " at debug_uninit_params.osl:" + std::to_string(line) +
           " (group unnamed_group_1, layer 0 debug_uninit_params_0, shader debug_uninit_params, "
           "op " +
           std::to_string(op) + " 'assign', arg 1)\n";
  };
  EXPECT_EQ(run("-O0 --debuguninit debug_uninit_params"),
            in("x1", 5, 0) + in("x2", 7, 3) + in("x3", 9, 6) + in("x4", 11, 10) + "\n");
  // Without the option Lobe's locals start at zero (and big is inf); OSL's hold garbage.
  EXPECT_EQ(run("-O0 -g 2 1 debug_uninit"),
            "x 0 i 1 s '' arr 0 r inf big inf\nx 1 i 1 s '' arr 0 r inf big inf\n\n");
}

// Layers as OSL 1.13.12's testshade runs them (`testshade -O<n> -g 2 1 -layer A <up> -layer B
// elide_reader -connect A o B i`): an upstream layer runs only when its connected value is
// read, and at -O2 not at all when that value is known (a constant, or a copy of a global),
// so its printf disappears.
TEST(ShadeCli, UpstreamLayersOfKnownValueAreElidedAtO2) {
  auto group = [](const std::string& up, const std::string& out) {
    return "-g 2 1 -layer A " + up + " -layer B elide_reader -connect A " + out + " B i";
  };
  for (const char* o : {"-O0 ", "-O1 "}) {
    EXPECT_EQ(run(o + group("elide_const", "o")),
              "Connect A.o to B.i\nelide_const ran\nreader i 3\nelide_const ran\nreader i 3\n\n");
    EXPECT_EQ(run(o + group("elide_global", "o")), "Connect A.o to B.i\nelide_global ran\n"
                                                   "reader i 0\nelide_global ran\nreader i 1\n\n");
  }
  EXPECT_EQ(run("-O2 " + group("elide_const", "o")),
            "Connect A.o to B.i\nreader i 3\nreader i 3\n\n");
  EXPECT_EQ(run("-O2 " + group("elide_global", "o")),
            "Connect A.o to B.i\nreader i 0\nreader i 1\n\n");
  // A copy of a global that only the optimiser made (u * scale, scale 1) keeps the layer.
  EXPECT_EQ(both(group("elide_identity", "o")), "Connect A.o to B.i\nelide_identity ran\n"
                                                "reader i 0\nelide_identity ran\nreader i 1\n\n");
  // A computed value, or one assigned in a branch, keeps the layer at every level.
  EXPECT_EQ(both(group("elide_computed", "o")), "Connect A.o to B.i\nelide_computed ran\n"
                                                "reader i 1\nelide_computed ran\nreader i 3\n\n");
  EXPECT_EQ(both(group("elide_computed", "o2")), "Connect A.o2 to B.i\nelide_computed ran\n"
                                                 "reader i 1\nelide_computed ran\nreader i 1\n\n");
  // Nothing reads the value: the upstream layer does not run, at any level.
  EXPECT_EQ(both("-g 1 1 -layer A elide_computed -param:type=int use 0 -layer B elide_reader "
                 "-connect A o B i"),
            "Connect A.o to B.i\nreader ignores i\n\n");
  EXPECT_EQ(both("-g 1 1 -layer A elide_computed -layer B elide_ignorer -connect A o B i"),
            "Connect A.o to B.i\nignorer ran\n\n");
  // An unconditional constant write after a loop and a branch that may exit is known (a write is
  // conditional only inside an if or a loop), so the second point too reads 3 at -O2.
  EXPECT_EQ(run("-O0 " + group("elide_after_branch", "o")),
            "Connect A.o to B.i\nelide_after_branch loop 0\nelide_after_branch loop 1\nreader i 3\n"
            "elide_after_branch loop 0\nelide_after_branch loop 1\nelide_after_branch exits\n"
            "reader i 0\n\n");
  EXPECT_EQ(run("-O2 " + group("elide_after_branch", "o")),
            "Connect A.o to B.i\nreader i 3\nreader i 3\n\n");
  // Outputs set by user functions (elide_function.osl): a body counts as conditional, and
  // `o = five()` and `set_seven(o2)` write there, so the layer runs at -O2 too; o3, computed
  // after the call from a local it set, is known (`testshade -O2 -g 2 1 -layer A elide_function
  // -layer B elide_reader -connect A o3 B i`, OSL 1.13.12).
  auto ran = [](const std::string& out, const std::string& v) {
    return "Connect A." + out + " to B.i\nelide_function ran\nreader i " + v +
           "\nelide_function ran\nreader i " + v + "\n\n";
  };
  EXPECT_EQ(both(group("elide_function", "o")), ran("o", "5"));
  EXPECT_EQ(both(group("elide_function", "o2")), ran("o2", "7"));
  EXPECT_EQ(run("-O0 " + group("elide_function", "o3")), ran("o3", "6"));
  EXPECT_EQ(run("-O2 " + group("elide_function", "o3")),
            "Connect A.o3 to B.i\nreader i 6\nreader i 6\n\n");
  // mix() is a builtin op in OSL (Lobe's stdosl.h body is osl_builtin): o4 = mix() is known.
  EXPECT_EQ(run("-O0 " + group("elide_function", "o4")), ran("o4", "2"));
  EXPECT_EQ(run("-O2 " + group("elide_function", "o4")),
            "Connect A.o4 to B.i\nreader i 2\nreader i 2\n\n");
  // An input read only by dead code (an output nothing takes, a local never read) is unused at
  // -O2, so its upstream layer does not run (`testshade -O<n> -g 2 1 -layer A elide_computed
  // -layer B elide_deadread -connect A o B i`, OSL 1.13.12).
  const std::string dead =
      "-g 2 1 -layer A elide_computed -layer B elide_deadread -connect A o B i";
  EXPECT_EQ(run("-O0 " + dead), "Connect A.o to B.i\nelide_computed ran\ndeadread ran\n"
                                "elide_computed ran\ndeadread ran\n\n");
  EXPECT_EQ(run("-O2 " + dead), "Connect A.o to B.i\ndeadread ran\ndeadread ran\n\n");
  // Outputs computed from interactive parameters are not known (elide_interactive.osl): the
  // layer runs; a plain value, also one overriding the metadata's interactive = 1, is known
  // (`testshade -O2 -g 2 1 [-param...] -layer A elide_interactive -layer B elide_reader
  // -connect A o B i`, OSL 1.13.12).
  auto ran_i = [](const std::string& out, const std::string& v) {
    return "Connect A." + out + " to B.i\nelide_interactive ran\nreader i " + v +
           "\nelide_interactive ran\nreader i " + v + "\n\n";
  };
  auto elided = [](const std::string& out, const std::string& v) {
    return "Connect A." + out + " to B.i\nreader i " + v + "\nreader i " + v + "\n\n";
  };
  const std::string up = " -layer A elide_interactive -layer B elide_reader -connect A ";
  EXPECT_EQ(run("-O2 -g 2 1" + up + "o B i"), elided("o", "2"));
  EXPECT_EQ(run("-O2 -g 2 1 -param:interactive=1 x 3.0" + up + "o B i"), ran_i("o", "6"));
  EXPECT_EQ(run("-O2 -g 2 1" + up + "om B i"), ran_i("om", "2"));
  EXPECT_EQ(run("-O2 -g 2 1 -param m 3.0" + up + "om B i"), elided("om", "6"));
  EXPECT_EQ(run("-O2 -g 2 1 -param:interactive=1 m 3.0" + up + "om B i"), ran_i("om", "6"));
  // A plain value overriding the metadata leaves m not interactive: --reparam changes nothing
  // and says nothing at -O2 (`testshade -O2 -g 1 1 --iters 2 -param m 3.0 ... --reparam A m 5.0`).
  EXPECT_EQ(run("-O2 -g 1 1 --iters 2 -param m 3.0" + up + "om B i --reparam A m 5.0"),
            "Connect A.om to B.i\nreader i 6\nreader i 6\n\n");
  // isconnected() answers for the connection as made, on both sides, and does not keep the
  // layer: at -O2 `elide_asks` does not run. (`elide_reader_asks` reads `i`.)
  const std::string asks = "-g 2 1 -layer A elide_asks -layer B elide_reader_asks -connect A o B i";
  EXPECT_EQ(run("-O0 " + asks), "Connect A.o to B.i\nelide_asks ran, o connected 2\n"
                                "reader i 2 connected 1\nelide_asks ran, o connected 2\n"
                                "reader i 2 connected 1\n\n");
  EXPECT_EQ(run("-O2 " + asks),
            "Connect A.o to B.i\nreader i 2 connected 1\nreader i 2 connected 1\n\n");
}

// Identical layers merged, as OSL 1.13.12's opt_merge_instances merges them at -O1 and -O2: B
// runs the same shader as A with the same parameter values and the same connections into it,
// so C reads A twice and A's printf shows once (`testshade -g 1 1 -O<n> -layer A merge_mid
// -layer B merge_mid -layer C merge_sum -connect A o C a -connect B o C b`, and the variants
// below, their outputs OSL's).
TEST(ShadeCli, IdenticalLayersAreMergedAtO1AndO2) {
  const std::string abc = " -layer C merge_sum -connect A o C a -connect B o C b";
  const std::string g = "-g 1 1 -layer A merge_mid -layer B merge_mid" + abc;
  const std::string head = "Connect A.o to C.a\nConnect B.o to C.b\n";
  const std::string twice = "mid t 2.5 conn 2\nmid t 2.5 conn 2\nsum 2.5 2.5 0\n\n";
  const std::string once = "mid t 2.5 conn 2\nsum 2.5 2.5 0\n\n";
  EXPECT_EQ(run("-O0 " + g), head + twice);
  EXPECT_EQ(run("-O1 " + g), head + once);
  EXPECT_EQ(run("-O2 " + g), head + once);
  // Another value is another layer; the default's value given is the same one.
  EXPECT_EQ(run("-g 1 1 -layer A merge_mid -param x 2.0 -layer B merge_mid" + abc),
            head + "mid t 2.5 conn 2\nmid t 4.5 conn 2\nsum 2.5 4.5 0\n\n");
  EXPECT_EQ(run("-g 1 1 -layer A merge_mid -param x 1.0 -layer B merge_mid" + abc), head + once);
  // A layer the renderer reads, or one with an interactive parameter, is not merged.
  EXPECT_EQ(run(g + " -o A.o null"), head + "\n" + twice);
  EXPECT_EQ(run("-g 1 1 -param:interactive=1 x 1.0 -layer A merge_mid -param:interactive=1 x "
                "1.0 -layer B merge_mid" +
                abc),
            head + twice);
  // The same warning for both layers is given once, as OSL's shading system gives it.
  EXPECT_EQ(run("-g 1 1 -param:type=string x s -layer A merge_mid -param:type=string x s -layer B "
                "merge_mid" +
                abc),
            "WARNING: attempting to set parameter with wrong type: x (expected 'float', received "
            "'string')\n" +
                head + once);
  // An entry layer merged into an earlier one still runs, its output connected to nothing now.
  EXPECT_EQ(run(g + " --entry B --entry C"),
            head +
                "Entry layers: B(1) C(2)\nmid t 2.5 conn 0\nmid t 2.5 conn 2\nsum 2.5 2.5 0\n\n");
}

// isconnected() as OSL 1.13.12 answers it beyond connections between layers: asking it of an
// input is no use of the input, so the upstream layer does not run (at any level); a renderer
// output (-o, testshade's default Cout) counts as a connection out (`testshade [-O0] -g 2 1
// -layer A elide_const -layer B isconnected_asker -connect A o B x`; `testshade -g 1 1
// isconnected_out [-o r null]`).
TEST(ShadeCli, IsconnectedIsNoUseAndSeesRendererOutputs) {
  const std::string asker =
      "-g 2 1 -layer A elide_const -layer B isconnected_asker -connect A o B x";
  const std::string asked =
      "Connect A.o to B.x\nasker: isconnected(x) 1\nasker: isconnected(x) 1\n\n";
  EXPECT_EQ(run("-O0 " + asker), asked);
  EXPECT_EQ(run("-O2 " + asker), asked);
  EXPECT_EQ(run("-g 1 1 isconnected_out"), "out: r 0 Cout 2\n\n");
  EXPECT_EQ(run("-g 1 1 isconnected_out -o r null"), "\nout: r 2 Cout 0\n\n");
  EXPECT_EQ(run("-g 1 1 -layer X isconnected_out -layer Y isconnected_out -connect X r Y a -o Y.r "
                "null"),
            "Connect X.r to Y.a\n\nout: r 2 Cout 0\nout: r 2 Cout 0\n\n");
  // --options opt_merge_instances=0: identical layers are not merged (both print).
  EXPECT_EQ(run("--options opt_merge_instances=0 -g 1 1 -layer A merge_mid -layer B merge_mid "
                "-layer C merge_sum -connect A o C a -connect B o C b"),
            "Connect A.o to C.a\nConnect B.o to C.b\nmid t 2.5 conn 2\nmid t 2.5 conn 2\n"
            "sum 2.5 2.5 0\n\n");
}

// The layers of a group share one set of globals: the upstream layer, run when the downstream
// one first reads x, sees the P that layer wrote before, and the downstream layer then sees the
// Ci the upstream one set (`testshade -O<n> -g 2 1 -layer A globals_up -layer B globals_down
// -connect A f B x`, OSL 1.13.12; Lobe gave each layer its own copy).
TEST(ShadeCli, LayersShareTheirGlobals) {
  const std::string diffuse = "Ci (1, 1, 1) * diffuse ((0, 0, 1), \"label\", \"\")\n";
  const std::string emission = "Ci (1, 1, 1) * emission ()\n";
  const std::string expected = "Connect A.f to B.x\n"
                               "down before x: P 0 N 0 " +
                               diffuse +
                               "up sees P 0 N 0\n"
                               "down: x 0 P 0 N 0 " +
                               emission + "down before x: P 10 N 0 " + diffuse +
                               "up sees P 10 N 0\n"
                               "down: x 10 P 10 N 0 " +
                               emission + "\n";
  EXPECT_EQ(both("-g 2 1 -layer A globals_up -layer B globals_down -connect A f B x"), expected);
}

} // namespace

// A failed lookup's error names its kind, and an int parameter given a value past int's range
// takes the nearest int, as `testshade -param i 99999999999 lookup_kinds` (OSL 1.13.12) prints.
TEST(ShadeCli, LookupErrorsNameTheirKindAndIntValuesSaturate) {
  EXPECT_EQ(run_here("-param i 99999999999 lookup_kinds"),
            "ERROR: [RendererServices::texture] Could not open file: nosuch.tif: No such file or "
            "directory\n"
            "ERROR: [RendererServices::environment] Could not open file: nosuch.env: No such file "
            "or directory\n"
            "ERROR: [RendererServices::texture3d] Image \"nosuch.vdb\" does not exist. Also, it is "
            "not the name of an image format that OpenImageIO recognizes.\n"
            "0 0 0 0 0 0 0 0 0 i=2147483647\n\n");
  std::string low = run_here("-param i -99999999999 lookup_kinds");
  EXPECT_NE(low.find("i=-2147483648\n"), std::string::npos) << low;
  // gettextureinfo's UDIM form (`testshade [-O0] gti_udim_missing`).
  for (const char* o : {"-O0 ", "-O2 "})
    EXPECT_EQ(run_here(std::string(o) + "gti_udim_missing"),
              "ERROR: [RendererServices::get_texture_info] Invalid image file \"nosuch.tx\": Could "
              "not open file: nosuch.tx: No such file or directory\nok 0 [-1 -1]\n\n");
}

// Keyword arguments a texture lookup, gabor noise or a closure does not take, or of another type,
// compile (as oslc compiles them) and are dropped when the shader is set up, with testshade's
// messages, also in code that never runs; the calls go on without them. Expected: OSL 1.13.12,
// `testshade -O0|-O2 kw_ignored` (the same at both).
TEST(ShadeCli, KeywordArgumentsNotTakenAreDroppedWithOslsMessages) {
  const std::string expected = expected_file("kw_ignored") + "\n";
  EXPECT_EQ(run_here("-O0 kw_ignored"), expected);
  EXPECT_EQ(run_here("-O2 kw_ignored"), expected);
}

// texture()'s "subimage" by index and by name, literal or a parameter's; an unknown name is
// OpenImageIO's error. Expected: OSL 1.13.12, `testshade -O0|-O2 -g 2 2 subimage` (the same at
// both). An index the file does not have is an error and zeros (OpenImageIO asserts on it:
// OSL's testshade aborts there).
TEST(ShadeCli, TextureSubimagesByIndexAndName) {
  const std::string expected = expected_file("subimage") + "\n";
  EXPECT_EQ(run_here("-O0 -g 2 2 subimage"), expected);
  EXPECT_EQ(run_here("-O2 -g 2 2 subimage"), expected);
  for (const char* index : {"2", "-1"}) {
    std::string out = run_here(std::string("-g 1 1 -param index ") + index + " subimage");
    EXPECT_NE(out.find("ERROR: [RendererServices::texture] Unknown subimage " + std::string(index) +
                       " in texture \"subimages.exr\" (it has 2)\n"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("0 1 0 | 0 1 0 | 1 0 0 | 0 0 0 | 0 1 0 | 1 0 0 | 0 0 0\n"),
              std::string::npos)
        << out;
  }
}

// `--options range_checking=0` turns the report of an index out of range off (it was ignored).
// Expected with checks, at -O0: OSL 1.13.12, `testshade -O0 -g 2 1 range_off`. Without, OSL prints
// no error either, and its second point reads past the array and the colour (whatever lies
// there); Lobe clamps the index, as with checks.
TEST(ShadeCli, RangeCheckingOffReportsNothing) {
  const std::string where = " (group unnamed_group_1, layer 0 range_off_0, shader range_off)\n";
  EXPECT_EQ(run_here("-O0 -g 2 1 range_off"),
            "ok 3 3\nERROR: Index [4] out of range a[0..2]: range_off.osl:5" + where +
                "ERROR: Index [4] out of range c[0..2]: range_off.osl:7" + where + "ok 3 3\n\n");
  for (const char* o : {"-O0", "-O2"})
    EXPECT_EQ(run_here(std::string(o) + " -g 2 1 --options range_checking=0 range_off"),
              "ok 3 3\nok 3 3\n\n")
        << o;
}

// A connection from a layer's global carries the global as the layer leaves it (Lobe read the
// group data at no offset: garbage, and a closure crashed). Expected: OSL 1.13.12, `testshade
// -O0|-O2 --layer A glob_src --layer B glob_dst --connect A X B y`; for u and Ci (and N at -O2)
// OSL aborts on freeing after printing the line checked here.
TEST(ShadeCli, ConnectionsFromGlobalsCarryTheirValues) {
  auto shade = [](const std::string& o, const std::string& connect) {
    return run_here(o + " --layer A glob_src --layer B glob_dst --connect A " + connect);
  };
  auto head = [](const std::string& from, const std::string& to) {
    return "Connect A." + from + " to B." + to + "\nglob_src runs\nglob_dst: ";
  };
  for (const char* o : {"-O0", "-O2"}) {
    EXPECT_EQ(shade(o, "P B pp"), head("P", "pp") + "nn=0 0 0 cc= uu=-1 pp=1 1 2 P=1 1 2\n\n") << o;
    EXPECT_EQ(shade(o, "N B nn"), head("N", "nn") + "nn=0 0 1 cc= uu=-1 pp=0 0 0 P=1 1 2\n\n") << o;
    EXPECT_EQ(shade(o, "u B uu"), head("u", "uu") + "nn=0 0 0 cc= uu=0.5 pp=0 0 0 P=1 1 2\n\n")
        << o;
    EXPECT_EQ(shade(o, "Ci B cc"), head("Ci", "cc") +
                                       "nn=0 0 0 cc=(3, 3, 3) * emission () uu=-1 pp=0 0 0 "
                                       "P=1 1 2\n\n")
        << o;
  }
}

// --options lazyglobals=0, lazyunconnected=0 and lazyerror=0 run the unread layers that write a
// global, that nothing reads, or that call error(), at every shade (they were ignored). Expected:
// OSL 1.13.12, `testshade -O0|-O2 -g 1 1 [--options X=0] --layer C lazy_ci --layer E lazy_err
// --layer A lazy_out --layer B ms_b` (the same at both levels).
TEST(ShadeCli, EagerLayerOptionsRunUnreadLayers) {
  const std::string layers =
      " --layer C lazy_ci --layer E lazy_err --layer A lazy_out --layer B ms_b";
  const std::string err = "ERROR: Shader error [lazy_err]: lazy_err error 0.5\nlazy_err runs\n";
  const std::pair<const char*, std::string> cases[] = {
      {"", "ms_b runs 0\n\n"},
      {"--options lazyglobals=0", "lazy_ci runs\nms_b runs 0\n\n"},
      {"--options lazyunconnected=0",
       "lazy_ci runs\n" + err + "lazy_out runs x=5\nms_b runs 0\n\n"},
      {"--options lazyerror=0", err + "ms_b runs 0\n\n"},
  };
  for (const auto& [options, expected] : cases)
    for (const char* o : {"-O0 ", "-O2 "})
      EXPECT_EQ(run_here(std::string(o) + "-g 1 1 " + options + layers), expected) << o << options;
  // Of two identical layers merged at -O2, only the first runs.
  const std::string twins =
      "-g 1 1 --options lazyunconnected=0 --layer A1 lazy_out --layer A2 lazy_out --layer B ms_b";
  EXPECT_EQ(run_here("-O0 " + twins), "lazy_out runs x=5\nlazy_out runs x=5\nms_b runs 0\n\n");
  EXPECT_EQ(run_here("-O2 " + twins), "lazy_out runs x=5\nms_b runs 0\n\n");
}

// Layer run order as testshade's (OSL 1.13.12, `testshade -O0|-O2 -g 1 1 ARGS`): an output
// parameter connected into runs its upstream layer as its layer starts (Lobe ran it at the first
// read); --entry layers run in the order named (Lobe: in layer order); a connection from a name
// two layers share takes the first (Lobe: the last).
TEST(ShadeCli, LayersRunInTestshadesOrder) {
  for (const char* o : {"-O0 ", "-O2 "}) {
    EXPECT_EQ(
        run_here(std::string(o) + "-g 1 1 --layer A ms_a --layer B out_into --connect A f B o"),
        "Connect A.f to B.o\nms_a runs 1\nout_into starts\nout_into: i=0 o=1\n\n")
        << o;
    EXPECT_EQ(run_here(std::string(o) +
                       "-g 1 1 --param:type=string name A --layer A named --param:type=string "
                       "name B --layer B named --param:type=string name C --layer C named "
                       "--entry C --entry A"),
              "Entry layers: C(2) A(0)\nC\nA\n\n")
        << o;
  }
  EXPECT_EQ(run_here("-O0 -g 1 1 --param:type=string name first --layer A named "
                     "--param:type=string name second --layer A named --layer B ms_b --connect A "
                     "o B x"),
            "Connect A.o to B.x\nfirst\nms_b runs 1\n\n");
}

// Merging identical layers (-O2) as OSL: a value given with lockgeom=0 to one of two layers keeps
// them apart (Lobe merged them), and a value refused for its type takes its interactive flag
// with it (Lobe kept the flag and did not merge). Expected: OSL 1.13.12, `testshade -O2 PARAM
// --layer A1 merge_k --layer A2 merge_k --layer B merge_yz --connect A1 x B y --connect A2 x B z`.
TEST(ShadeCli, MergingFollowsLockgeomAndRefusedValues) {
  const std::string layers =
      " --layer A1 merge_k --layer A2 merge_k --layer B merge_yz --connect A1 x B y --connect A2 x "
      "B z";
  const std::string connects = "Connect A1.x to B.y\nConnect A2.x to B.z\n";
  const std::string once = "merge_k(1): x=1.5\n", tail = "merge_yz: y=1.5 z=1.5\n\n";
  const std::string refused = "WARNING: attempting to set parameter with wrong type: k (expected "
                              "'float', received 'int')\n";
  EXPECT_EQ(run_here("-O2 --param:lockgeom=0 k 1.0" + layers), connects + once + once + tail);
  EXPECT_EQ(run_here("-O2 --param:interactive=1 k 2" + layers), refused + connects + once + tail);
  EXPECT_EQ(run_here("-O2 --param:lockgeom=0 k 2" + layers), refused + connects + once + tail);
}

// Parameters given before --expr are the expression layer's; --param with no shader at all is
// testshade's "No shader" error; a value for a closure parameter is skipped with testshade's
// warning. Expected: OSL 1.13.12, `testshade ARGS` in tests/shade/layers.
TEST(ShadeCli, ParametersOfExpressionsAndClosures) {
  EXPECT_EQ(run_here("--param alpha 0.5 --expr 'printf(\"%g\\n\", alpha);'"), "0.5\n\n");
  EXPECT_EQ(run_here("--param k 2 --expr 'printf(\"e\\n\");'"),
            "WARNING: attempting to set nonexistent parameter: k\ne\n\n");
  EXPECT_EQ(run_here("--param k 2"), "ERROR: No shader or group was specified.\n\n"
                                     "Try `lobe shade --help` for an explanation of all "
                                     "arguments\n");
  EXPECT_EQ(run_here("--param cl 0.0 closure_param"),
            "WARNING: skipping assignment of closure: cl\nx\n\n");
}

// An unsized array parameter goes where a sized array does (assigned, passed), as oslc accepts
// it (Lobe refused to compile: "array lengths differ"). Expected: OSL 1.13.12, `testshade
// -O0|-O2 [--param:type=float[4] pa 5,6,7,8] unsized_to_sized`.
TEST(ShadeCli, UnsizedArrayParametersGoWhereSizedOnesDo) {
  for (const char* o : {"-O0 ", "-O2 "}) {
    EXPECT_EQ(run_here(std::string(o) + "unsized_to_sized"), "e=1 2 3 oa=1 2 3 sum3=6 len=3\n\n")
        << o;
    EXPECT_EQ(run_here(std::string(o) + "--param:type=float[4] pa 5,6,7,8 unsized_to_sized"),
              "e=5 6 7 oa=5 6 7 sum3=18 len=4\n\n")
        << o;
  }
  // Shorter than the function's array: read by reference, the index past it is reported and
  // clamped (at -O2 OSL names the array $newconst0).
  EXPECT_EQ(run_here("-O0 --param:type=float[2] pa 5,6 unsized_to_sized"),
            "ERROR: Index [2] out of range pa[0..1]: unsized_to_sized.osl:5 (group "
            "unnamed_group_1, layer 0 unsized_to_sized_0, shader unsized_to_sized)\n"
            "e=5 6 9 oa=5 6 0 sum3=17 len=2\n\n");
}

// A texture or gettextureinfo of a device (/dev/zero, /dev/urandom) is an error: OpenImageIO read
// it for ever (the shade hung).
TEST(ShadeCli, TexturesOfDevicesAreErrors) {
  EXPECT_EQ(run_here("-g 1 1 dev_texture"),
            "ERROR: [RendererServices::texture] Could not open file: /dev/zero: not a regular "
            "file\nERROR: Shader error [dev_texture]: Could not open file: /dev/zero: not a "
            "regular file\n0 0 0 | 0 -1 -1\n\n");
}

// A texture file that cannot be opened is told once, at the first point in grid order that meets
// it, whatever the thread count: its words in the first point's "errormessage" and "unknown"
// after, and the error of a lookup only the grid's lower half makes printed with that half's
// first point (before, the first thread to fail told it, and on two threads the message moved
// between runs). More threads than cores are run as asked, without oneTBB's warning. Expected:
// OSL 1.13.12, `testshade -t 1 -g 16 16 tex_order` (its multi-threaded runs print the same).
TEST(ShadeCli, AFileThatCannotBeOpenedIsToldAtTheFirstPointInGridOrder) {
  const std::string expected = expected_file("tex_order") + "\n";
  for (const char* threads : {"-t 1", "-t 2", "-t 5", "-t 5", "-t 5"})
    EXPECT_EQ(run_here(std::string(threads) + " -g 16 16 tex_order"), expected) << threads;
}

// At -O2 a getmessage of a constant name nothing set before it is 0 without a query (so a later
// set is no error), as OSL's optimiser folds it; at -O0 the query is made and remembered. OSL
// numbers layers by instance id in its message errors (testshade's first layer is #2).
// Expected: OSL 1.13.12, `testshade -O0|-O2 msg_fold` and `testshade -O0|-O2 -layer A
// msg_late_get -layer B msg_late_set -connect A o B i`.
TEST(ShadeCli, ImpossibleGetmessageFoldsAtO2) {
  EXPECT_EQ(run_here("-O2 msg_fold"),
            "get before set: 0\nget after set: 1 3\nloop 0: 0\nloop 1: 0\nERROR: message \"n\" "
            "already exists (created here: msg_fold.osl:12) cannot set again from "
            "msg_fold.osl:12\n\n");
  EXPECT_EQ(run_here("-O0 msg_fold"),
            "get before set: 0\nERROR: message \"m\" was queried before being set (queried here: "
            "msg_fold.osl:7) setting it now (msg_fold.osl:3) would lead to inconsistent "
            "results\nget after set: 0 -1\nloop 0: 0\nERROR: message \"n\" was queried before "
            "being set (queried here: msg_fold.osl:11) setting it now (msg_fold.osl:12) would "
            "lead to inconsistent results\nloop 1: 0\n\n");
  const std::string group = "-layer A msg_late_get -layer B msg_late_set -connect A o B i";
  EXPECT_EQ(run_here("-O2 " + group), "Connect A.o to B.i\nfirst: 0\nsecond: 0.5\n\n");
  EXPECT_EQ(run_here("-O0 " + group),
            "Connect A.o to B.i\nERROR: message \"late\" was set by layer #3 "
            "(msg_late_set.osl:4) but is being queried by layer #2 (msg_late_get.osl:5) - "
            "messages may only be transferred from nodes that appear earlier in the shading "
            "network\nfirst: 0\nsecond: 0.5\n\n");
}

// A built-in redefined names "built-in" as its previous definition; a tie among user functions
// alone is warned once, oslc keeping its first resolution, where one with built-ins among the
// candidates repeats with each check of its printf argument. Expected: OSL 1.13.12, `oslc
// oslc_overloads.osl; testshade oslc_overloads` (testshade's final blank line dropped).
TEST(ShadeCli, RedefinitionAndAmbiguityWarningsAsOslc) {
  std::string expected = expected_file("oslc_overloads");
  ASSERT_FALSE(expected.empty());
  EXPECT_EQ(run_here("oslc_overloads"), expected + "\n");
}

// A local shadowing another of its name is reported by its source name (`x`, not Lobe's IR name
// `x~2`). Expected: OSL 1.13.12, `testshade -O0 --debuguninit|--debugnan debug_shadowed`.
TEST(ShadeCli, DebugReportsNameShadowingLocalsAsTheSourceDoes) {
  EXPECT_EQ(run_here("-O0 --debuguninit debug_shadowed"),
            "ERROR: Detected possible use of uninitialized value in float x at "
            "debug_shadowed.osl:10 (group unnamed_group_1, layer 0 debug_shadowed_0, shader "
            "debug_shadowed, op 4 'printf', arg 1)\ninner x = 0\nERROR: Detected possible use of "
            "uninitialized value in float big at debug_shadowed.osl:12 (group unnamed_group_1, "
            "layer 0 debug_shadowed_0, shader debug_shadowed, op 8 'sub', arg 1)\nr = 0\n\n");
  EXPECT_EQ(run_here("-O0 --debugnan debug_shadowed"),
            "inner x = 0\nERROR: Detected inf value in big at debug_shadowed.osl:11 (op mul)\n"
            "ERROR: Detected -nan value in r at debug_shadowed.osl:12 (op sub)\nr = -nan\n\n");
}

// An element, a component or a call's result read into a variable goes straight into it (one
// --debugnan report, naming the variable); OSL's op numbers count a functioncall op before each
// inlined body and a return op for an early return. Expected: OSL 1.13.12, `testshade -O0
// --debugnan|--debuguninit debug_direct` (with --debugnan the never-written w is NaN in OSL, 0
// in Lobe: a read of no defined value, docs/language.md; its line is left out).
TEST(ShadeCli, DebugReportsOfReadsAndCallsAsOsl) {
  std::string nan = run_here("-O0 --debugnan debug_direct");
  EXPECT_EQ(nan.substr(0, nan.find("ERROR: Detected nan value in k")),
            "ERROR: Detected inf value in big at debug_direct.osl:8 (op mul)\n"
            "ERROR: Detected -nan value in nan at debug_direct.osl:9 (op sub)\n"
            "ERROR: Detected -nan value in arr at debug_direct.osl:10 (op aassign)\n"
            "ERROR: Detected -nan value in s at debug_direct.osl:11 (op aref)\n"
            "ERROR: Detected -nan value in c at debug_direct.osl:12 (op color)\n"
            "ERROR: Detected -nan value in t at debug_direct.osl:13 (op compref)\n"
            "ERROR: Detected -nan value in r at debug_direct.osl:4 (op mul)\n"
            "-nan -nan -nan 1.5\n\n");
  EXPECT_EQ(run_here("-O0 --debuguninit debug_direct"),
            "ERROR: Detected possible use of uninitialized value in float big at "
            "debug_direct.osl:9 (group unnamed_group_1, layer 0 debug_direct_0, shader "
            "debug_direct, op 3 'sub', arg 1)\nERROR: Detected possible use of uninitialized "
            "value in float w at debug_direct.osl:16 (group unnamed_group_1, layer 0 "
            "debug_direct_0, shader debug_direct, op 17 'add', arg 2)\n0 0 0 1.5\n\n");
}

// -param naming a whole struct parameter is ignored without a word; a field takes its value; a
// name the shader lacks is warned of. Expected: OSL 1.13.12, `testshade -param pp 5,6 sp`,
// `-param pp.x 5.5`, `-param ppx 1`.
TEST(ShadeCli, ParamOfAWholeStructIsIgnored) {
  auto dir = scratch_dir("sp.osl", "struct Pt { float x; float y; };\nshader sp (Pt pp = { 1, 2 }) "
                                   "{ printf (\"pp = (%g, %g)\\n\", pp.x, pp.y); }\n");
  EXPECT_EQ(run_in(dir, "-param pp 5,6 sp"), "pp = (1, 2)\n\n");
  EXPECT_EQ(run_in(dir, "-param pp.x 5.5 sp"), "pp = (5.5, 2)\n\n");
  EXPECT_EQ(run_in(dir, "-param ppx 1 sp"),
            "WARNING: attempting to set nonexistent parameter: ppx\npp = (1, 2)\n\n");
}

// An upstream output the renderer reads (-o) keeps its connection at -O2 (not replaced by its
// known value), so the upstream layer runs for the downstream entry layer. Expected: OSL
// 1.13.12, `testshade -layer U entry_up -layer D entry_dn --connect U out D x --entry D -o out
// null`.
TEST(ShadeCli, RendererOutputsKeepTheirConnections) {
  EXPECT_EQ(run_here("-layer U entry_up -layer D entry_dn --connect U out D x --entry D -o out "
                     "null"),
            "Connect U.out to D.x\n\nEntry layers: D(1)\nup ran\ndn: x = 100\n\n");
}

// A layer's write of P (or I) carries its derivatives to the layers after it and to an upstream
// layer that runs later, as OSL's layers share them (Dx(P), calculatenormal(P) of a displaced
// P). Expected: OSL 1.13.12, `testshade -g 2 2 [-O0|-O2] --layer a displace_up --layer b
// displace_dn --connect a o b i -o o null` (the same at both) and `testshade -g 2 1 [-O0|-O2]
// --layer x pderiv_up --layer y pderiv_dn --connect x o y i` (at -O2 OSL elides pderiv_up).
TEST(ShadeCli, GlobalDerivativesWrittenByALayerReachTheOthers) {
  for (const char* level : {"-O0 ", "-O2 "})
    EXPECT_EQ(run_here(std::string("-g 2 2 ") + level +
                       "--layer a displace_up --layer b displace_dn --connect a o b i -o o null"),
              "Connect a.o to b.i\n"
              "\n"
              "i=0 Dx(P)=2 0 0 Dy(P)=0 2 0 Dx(I)=2 0 0 N=0 0 4\n"
              "i=1 Dx(P)=2 0 0 Dy(P)=0 2 0 Dx(I)=2 0 0 N=0 0 4\n"
              "i=0 Dx(P)=2 0 0 Dy(P)=0 2 0 Dx(I)=2 0 0 N=0 0 4\n"
              "i=1 Dx(P)=2 0 0 Dy(P)=0 2 0 Dx(I)=2 0 0 N=0 0 4\n"
              "\n")
        << level;
  EXPECT_EQ(run_here("-g 2 1 -O0 --layer x pderiv_up --layer y pderiv_dn --connect x o y i"),
            "Connect x.o to y.i\n"
            "up P=0 1.5 3 Dx(P)=3 0 0\n"
            "dn k=0 Dx(P)=3 0 0\n"
            "up P=3 1.5 3 Dx(P)=3 0 0\n"
            "dn k=1 Dx(P)=3 0 0\n"
            "\n");
  // OSL gives the displacement's connected amount no derivatives for P's sake (`testshade -g 2
  // 2 [-O0|-O2] --layer t disp_amount --layer d disp_by --layer r displace_dn --connect t amt d
  // amt --connect d done r i`: Dx(P) 1 0 0 though amt = u * 2).
  for (const char* level : {"-O0 ", "-O2 "})
    EXPECT_EQ(run_here(std::string("-g 2 2 ") + level +
                       "--layer t disp_amount --layer d disp_by --layer r displace_dn --connect t "
                       "amt d amt --connect d done r i"),
              "Connect t.amt to d.amt\n"
              "Connect d.done to r.i\n"
              "i=1 Dx(P)=1 0 0 Dy(P)=0 1 0 Dx(I)=0 0 0 N=0 0 1\n"
              "i=1 Dx(P)=1 0 0 Dy(P)=0 1 0 Dx(I)=0 0 0 N=0 0 1\n"
              "i=1 Dx(P)=1 0 0 Dy(P)=0 1 0 Dx(I)=0 0 0 N=0 0 1\n"
              "i=1 Dx(P)=1 0 0 Dy(P)=0 1 0 Dx(I)=0 0 0 N=0 0 1\n"
              "\n")
        << level;
  EXPECT_EQ(run_here("-g 2 1 -O2 --layer x pderiv_up --layer y pderiv_dn --connect x o y i"),
            "Connect x.o to y.i\n"
            "dn k=0 Dx(P)=3 0 0\n"
            "dn k=1 Dx(P)=3 0 0\n"
            "\n");
}

// A struct member that is itself a struct connects to a struct of its type, either way round
// (Lobe compared the whole parameter's struct type and refused). Expected: OSL 1.13.12,
// `testshade [-O0] --layer A member_struct_up --layer B member_struct_dn --connect A so.in B i
// --connect A o B s.in` (the same at both).
TEST(ShadeCli, StructMembersThatAreStructsConnect) {
  for (const char* level : {"-O0 ", "-O2 "})
    EXPECT_EQ(run_here(std::string(level) +
                       "--layer A member_struct_up --layer B member_struct_dn --connect A so.in B "
                       "i --connect A o B s.in"),
              "Connect A.so.in to B.i\nConnect A.o to B.s.in\ni.a=3 s.in.a=6 s.x=-1\n\n")
        << level;
}

// An untyped -param value with blanks around its number is that number, as testshade 1.13.12
// reads it (`testshade -param f "2.5 " -param i " 5 " -param c "0.25 " blanks`; Lobe took
// "2.5 " for a string and kept the default with a type warning).
TEST(ShadeCli, UntypedValuesWithBlanksAreNumbers) {
  auto dir = scratch_dir("blanks.osl", "shader blanks(float f = 0.5, int i = 1, color c = 0)\n{\n"
                                       "    printf(\"f=%g i=%d c=%g\\n\", f, i, c);\n}\n");
  EXPECT_EQ(run_in(dir, "-param f \"2.5 \" -param i \" 5 \" -param c \"0.25 \" blanks"),
            "f=2.5 i=5 c=0.25 0.25 0.25\n\n");
}

// Errors and warnings: one identical to one of the last 25 given is not printed again, as OSL
// 1.13.12's shading system remembers 25 (a shader giving e0 ... e24, then e0 again: testshade
// prints 25 errors; e0 ... e25, then e0: 27, the repeat among them).
TEST(ShadeCli, ARepeatAfterTwentyFiveOthersIsPrintedAgain) {
  for (int distinct : {25, 26}) {
    std::string src = "shader repeats()\n{\n";
    for (int i = 0; i < distinct; ++i) src += "    error(\"e" + std::to_string(i) + "\\n\");\n";
    src += "    error(\"e0\\n\");\n    warning(\"w0\\n\");\n";
    for (int i = 1; i < distinct; ++i) src += "    warning(\"w" + std::to_string(i) + "\\n\");\n";
    src += "    warning(\"w0\\n\");\n}\n";
    auto dir = scratch_dir("repeats.osl", src);
    std::string out = run_in(dir, "repeats");
    size_t errors = 0, warnings = 0;
    for (size_t at = out.find("ERROR: "); at != std::string::npos; at = out.find("ERROR: ", at + 1))
      ++errors;
    for (size_t at = out.find("WARNING: "); at != std::string::npos;
         at = out.find("WARNING: ", at + 1))
      ++warnings;
    EXPECT_EQ(errors, size_t(distinct == 25 ? 25 : 27)) << distinct;
    EXPECT_EQ(warnings, size_t(distinct == 25 ? 25 : 27)) << distinct;
  }
}

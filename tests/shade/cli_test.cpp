// `lobe shade` end to end: layers, instance values, connections of each kind (announced
// first), lazy upstream layers, group files and image output, with specialisation off and on.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace {

std::string run(const std::string& args) {
  std::string cmd =
      std::string(LOBE_EXE) + " shade -I " + LOBE_SHADE_CORPUS + "/layers " + args + " 2>&1";
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return "<popen failed>";
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
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

// `float a[] = {1, 2}` stays unsized: an instance value of another length sets arraylength.
TEST(ShadeCli, UnsizedArrayParameterTakesTheInstanceLength) {
  EXPECT_EQ(both("unsized_array"), "arraylength 2 sum 3 last 2\n");
  EXPECT_EQ(both("-param:type=float[] a \"1 2 3\" unsized_array"), "arraylength 3 sum 6 last 3\n");
  EXPECT_EQ(both("-param:type=float[] a \"0.5 1 1.5 2 4\" unsized_array"),
            "arraylength 5 sum 9 last 4\n");
}

TEST(ShadeCli, WritesOutputImage) {
  auto file = std::filesystem::temp_directory_path() / "lobe_shade_cli_test.exr";
  std::filesystem::remove(file);
  std::string out = run("-g 4 2 -o Cout " + file.string() + " downstream_print");
  EXPECT_NE(out.find("Cin 0 0 0"), std::string::npos) << out;
  EXPECT_TRUE(std::filesystem::exists(file));
  EXPECT_GT(std::filesystem::file_size(file), 0u);
  std::filesystem::remove(file);
}

TEST(ShadeCli, ErrorsAndUsage) {
  EXPECT_NE(run("no_such_shader").find("not found"), std::string::npos);
  EXPECT_NE(run("--help").find("usage: lobe shade"), std::string::npos);
}

} // namespace

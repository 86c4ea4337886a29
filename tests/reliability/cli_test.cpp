// Reliability of the commands end to end (runs the built executable): endless shader loops are
// stopped with an error and exit status 1 (lobe shade; lobe render at set-up and while
// rendering), Ctrl-C stops and keeps what is finished, shader messages are capped, sizes are
// checked against the memory before allocating, and lobe brdf refuses bad arguments.
#include "run_command.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

extern char** environ;

namespace fs = std::filesystem;

namespace {

using lobe::testing::CmdResult;
using lobe::testing::run_cmd;
using lobe::testing::write_file;

// AddressSanitizer reserves ~16 TB of address space for its shadow memory at start-up, so an
// executable built with it cannot start under `ulimit -v` at all: the two address-space-limit
// checks below do not run in the sanitized build (docs/verification.md, "Sanitizers").
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

// A fresh folder for one test's files.
fs::path temp_dir(const std::string& name) { return lobe::testing::temp_dir("reliability", name); }

std::string read_file(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string exe() { return LOBE_EXE; }

// Shader `grow` of kind `kind` that doubles a string 40 times (a terabyte), then runs `last`.
void write_growing_string(const fs::path& file, const std::string& kind, const std::string& last) {
  write_file(file, kind +
                       " grow() {\n  string s = \"x\";\n"
                       "  for (int i = 0; i < 40; i++) s = concat(s, s);\n  " +
                       last + "\n}\n");
}

// Runs `lobe ARGS` in `cwd` with stdout and stderr to `log`, waits until the shader has written
// `started` (it does so just before its endless loop), sends SIGINT and returns the exit status
// (-1 if it did not exit by itself).
int interrupt_when_started(const std::vector<std::string>& args, const fs::path& cwd,
                           const fs::path& log, const fs::path& started) {
  std::string cmd = "cd '" + cwd.string() + "' && exec '" + exe() + "'";
  for (const std::string& a : args) cmd += " '" + a + "'";
  cmd += " > '" + log.string() + "' 2>&1";
  pid_t pid = fork();
  if (pid == 0) {
    signal(SIGINT, SIG_DFL);
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  for (int i = 0; i < 6000 && !fs::exists(started); ++i) // the CTest TIMEOUT bounds it anyway
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  kill(pid, SIGINT);
  int st = 0;
  waitpid(pid, &st, 0);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

// For camera rays, an endless loop that first says it has started (fprintf appends to the file
// at once); lobe shade's rays are camera rays, lobe render's set-up probes with shadow rays.
std::string endless_after_notice(const char* name, const fs::path& started) {
  return std::string("surface ") + name + "(output color Cout = 0)\n{\n  float x = 1;\n" +
         "  if (raytype(\"camera\")) {\n    fprintf(\"" + started.string() +
         "\", \"started\\n\");\n    while (1) { x = x * 2; }\n  }\n  Ci = diffuse(N);\n}\n";
}

// Line 3 is the loop.
const char* kEndless = "surface endless(output color Cout = 0)\n"
                       "{\n"
                       "  float x = 1; while (1) { x = x * 2; }\n"
                       "  Cout = color(x); Ci = diffuse(N);\n"
                       "}\n";

// Loops only for camera rays: set-up (which probes with shadow rays) passes, rendering stops.
const char* kEndlessCamera = "surface camloop()\n"
                             "{\n"
                             "  float x = 1;\n"
                             "  if (raytype(\"camera\")) while (1) { x = x * 2; }\n"
                             "  Ci = diffuse(N);\n"
                             "}\n";

std::string scene_json(const std::string& shader, int res = 8) {
  return R"({"camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "fov": 12},
  "settings": {"resolution": [)" +
         std::to_string(res) + ", " + std::to_string(res) + R"(], "spp": 4},
  "materials": {"m": {"shader": ")" +
         shader + R"("}},
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
  "environment": {"type": "constant", "color": 1}})";
}

} // namespace

TEST(ReliabilityShade, EndlessLoopIsAnErrorWithItsPlace) {
  fs::path d = temp_dir("shade_loop");
  write_file(d / "endless.osl", kEndless);
  CmdResult r = run_cmd("cd '" + d.string() + "' && " + exe() +
                        " shade --options max_loop_iterations=100000 endless");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_EQ(r.out, "ERROR: shader endless (group unnamed_group_1, layer 0 endless_0): loop at "
                   "endless.osl:3 ran more than "
                   "100000 iterations (max_loop_iterations); stopped\n\n"
                   "lobe shade: stopped after 0 of 1 points; no output written\n");
  // The default limit, on a grid: the first stopped point stops the grid.
  r = run_cmd("cd '" + d.string() + "' && " + exe() + " shade -g 32 32 -o Cout " +
              (d / "out.exr").string() + " endless");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("loop at endless.osl:3 ran more than 100000000 iterations"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("no output written"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "out.exr"));
}

// Ctrl-C while a shader runs without a limit: the loop stops, the command says so and writes
// the finished points; exit status 130.
TEST(ReliabilityShade, CtrlCStopsAndWritesWhatIsFinished) {
  fs::path d = temp_dir("shade_sigint");
  write_file(d / "notice.osl", endless_after_notice("notice", d / "started"));
  int st = interrupt_when_started({"shade", "--options", "max_loop_iterations=0", "-t", "1", "-g",
                                   "4", "4", "-o", "Cout", (d / "out.exr").string(), "notice"},
                                  d, d / "log", d / "started");
  std::string log = read_file(d / "log");
  EXPECT_EQ(st, 130) << log;
  EXPECT_NE(log.find("lobe shade: interrupted (Ctrl-C) after 0 of 16 points; writing the finished "
                     "points"),
            std::string::npos)
      << log;
  EXPECT_TRUE(fs::exists(d / "out.exr")) << log;
}

// error() from a shader: reported, and the exit status stays 0, as testshade's does
// (OSL 1.13.12: `testshade err` prints "ERROR: Shader error [err]: bad thing 3" and exits 0).
TEST(ReliabilityShade, ShaderErrorIsReportedWithTestshadesStatus) {
  fs::path d = temp_dir("shade_error");
  write_file(d / "err.osl",
             "shader err(output color Cout = 0) { error(\"bad thing %d\\n\", 3); Cout = 1; }\n");
  CmdResult r = run_cmd("cd '" + d.string() + "' && " + exe() + " shade err");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "ERROR: Shader error [err]: bad thing 3\n\n\n");
}

// Under a 6 GB address-space limit a 10^10-point grid is refused before anything is allocated,
// with the setting and the figure: 10^10 points x 3 float channels x 4 bytes x 2 (the image and
// its written copy) = 240 GB.
TEST(ReliabilityShade, HugeGridIsRefusedWithTheFigure) {
  fs::path d = temp_dir("shade_big");
  write_file(d / "c.osl", "shader c(output color Cout = 0) { Cout = u; }\n");
  CmdResult r;
  if (!kAddressSanitizer) {
    r = run_cmd("cd '" + d.string() + "' && ulimit -v 6000000 && " + exe() +
                " shade -g 100000 100000 c -o Cout " + (d / "big.exr").string());
    EXPECT_EQ(r.status, 1) << r.out;
    EXPECT_NE(r.out.find("lobe shade: -g 100000 100000 needs about 240.0 GB of memory"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(d / "big.exr"));
  }
  // An output that cannot be written is found before shading (no messages from the shader).
  write_file(d / "p.osl", "shader p(output color Cout = 0) { printf(\"shaded\\n\"); }\n");
  r = run_cmd("cd '" + d.string() + "' && " + exe() + " shade p -o Cout /nonexistent/dir/x.exr");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_EQ(r.out.find("shaded"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lobe shade: "), std::string::npos) << r.out;
}

// Strings a shader makes are kept within a quarter of the memory available: under a 3 GB
// address-space limit, a string doubled 40 times (a terabyte) passes it; the string that does
// not fit is made "" (so its length ends at 0, and "a" + "b" still fits), the run ends and
// says so, with exit status 1. Before, the doubling aborted on an uncaught std::bad_alloc (exit
// 134), or without a limit grew until the kernel killed the process (137).
TEST(ReliabilityShade, StringsPastTheMemoryAreAnErrorNotAnAbort) {
  if (kAddressSanitizer) GTEST_SKIP() << "cannot start under ulimit -v (see above)";
  fs::path d = temp_dir("shade_strings");
  write_growing_string(d / "grow.osl", "shader",
                       "printf(\"%d %s\\n\", strlen(s), concat(\"a\", \"b\"));");
  CmdResult r = run_cmd("cd '" + d.string() + "' && { ulimit -v 3000000 && " + exe() +
                        " shade grow 2>&1; echo \"status $?\"; }");
  EXPECT_NE(r.out.find("0 ab\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lobe shade: the shaders' strings passed the "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("status 1\n"), std::string::npos) << r.out;
}

// Messages are kept until the grid is shaded (testshade prints them in point order), within a
// quarter of the memory available: under a 2 GB address-space limit, 10^6 points printing
// 512 bytes each (512 MB) pass it; the rest are counted and reported, and the run ends
// normally. Before, the messages grew until an uncaught std::bad_alloc aborted the process
// (exit 134).
TEST(ReliabilityShade, MessagesPastTheMemoryAreCountedNotAnAbort) {
  if (kAddressSanitizer) GTEST_SKIP() << "cannot start under ulimit -v (see above)";
  fs::path d = temp_dir("shade_said");
  write_file(d / "talk.osl", "shader talk(output float f = 0) {\n  printf(\"%s %g\\n\", \"" +
                                 std::string(500, 'x') + "\", P[0]);\n  f = 1;\n}\n");
  CmdResult r = run_cmd("cd '" + d.string() + "' && { ulimit -v 2000000 && " + exe() +
                        " shade -g 1000 1000 talk -o f out.exr > stdout.txt; }");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.rfind("lobe shade: ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find(" more shader messages not shown: the grid's messages passed the "),
            std::string::npos)
      << r.out;
  EXPECT_TRUE(fs::exists(d / "out.exr"));
  // The messages kept come in order after testshade's header ("\nOutput f to out.exr\n"):
  // the first is point (0, 0)'s, where P[0] = 0.
  std::ifstream out(d / "stdout.txt");
  std::string line[3];
  for (std::string& l : line) std::getline(out, l);
  EXPECT_EQ(line[0], "");
  EXPECT_EQ(line[1], "Output f to out.exr");
  EXPECT_EQ(line[2], std::string(500, 'x') + " 0");
}

// A shader whose variables cannot fit on a shading thread's stack (a 10^9-element local array:
// 4 GB of floats; OSL 1.13's testshade crashes with SIGSEGV on it) is refused when the material
// is built, naming the array, its size and its line; an array within the limit shades. The same
// check guards lobe render's set-up (one build path).
TEST(ReliabilityShade, HugeLocalArrayIsAnErrorNotAStackOverflow) {
  fs::path d = temp_dir("shade_array");
  write_file(d / "big.osl", "shader big(output float f = 0) {\n"
                            "  float a[1000000000];\n"
                            "  a[int(u * 7)] = u;\n"
                            "  f = a[int(v * 3)];\n"
                            "}\n");
  CmdResult r = run_cmd("cd '" + d.string() + "' && " + exe() + " shade -g 2 2 big -o f null");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("the material's arrays need 4.0 GB of stack while it shades, more "
                       "than the limit of 1.0 MB; the largest is 'a' (float[1000000000], 4.0 GB) "
                       "in shader 'big' (layer 'big_0', big.osl:2)"),
            std::string::npos)
      << r.out;
  // 10^4 floats (40 kB) are fine: f = a[0] = u at u = 0 and 1 (-g 2 1).
  write_file(d / "ok.osl", "shader ok(output float f = 0) {\n"
                           "  float a[10000];\n"
                           "  a[int(u * 7)] = u;\n"
                           "  f = a[int(u * 7)];\n"
                           "  printf(\"%g\\n\", f);\n"
                           "}\n");
  r = run_cmd("cd '" + d.string() + "' && " + exe() + " shade -g 2 1 ok -o f null");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("0\n1\n"), std::string::npos) << r.out;
}

// An image whose header claims more pixels than the memory can hold (a 10^6 x 10^6 PPM: 12 TB
// as floats) is refused before its pixels are allocated, naming the file and the figure.
TEST(ReliabilityRender, HugeImageIsRefusedWithTheFigure) {
  fs::path d = temp_dir("render_image");
  write_file(d / "big.ppm", "P6\n1000000 1000000\n255\n\x01\x02\x03");
  write_file(d / "s.json",
             "{\"camera\": {\"eye\": [0, 0, 5], \"look_at\": [0, 0, 0], \"fov\": 40},\n"
             " \"settings\": {\"resolution\": [8, 8], \"spp\": 1},\n"
             " \"environment\": {\"type\": \"map\", \"file\": \"big.ppm\"}}\n");
  CmdResult r =
      run_cmd("cd '" + d.string() + "' && " + exe() + " render s.json -o out.exr --progress none");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("big.ppm (1000000x1000000, 3 channels) needs about 12.0 TB of memory "
                       "(its pixels as floats)"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(d / "out.exr"));
  // The same file as a texture: OpenImageIO would read it whole (it is not tiled) and its failed
  // allocation would abort the process (OSL's testshade runs out of memory on it); the lookup
  // is refused with the figure (3 bytes a pixel, x 4/3 for the MIP levels: 4 TB) and gives 0,
  // an error as testshade reports texture errors (exit status 0).
  write_file(d / "tex.osl", "shader tex(output color c = 1) { c = texture(\"big.ppm\", u, v); }\n");
  r = run_cmd("cd '" + d.string() + "' && " + exe() + " shade -g 2 2 tex -o c null");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(
      r.out.find("ERROR: [RendererServices::texture] big.ppm (1000000x1000000, 3 channels, not "
                 "tiled) needs about 4.0 TB of memory (read whole into the texture cache, "
                 "with its MIP levels)"),
      std::string::npos)
      << r.out;
}

TEST(ReliabilityRender, EndlessLoopAtSetupIsAnError) {
  fs::path d = temp_dir("render_setup_loop");
  write_file(d / "endless.osl", kEndless);
  write_file(d / "s.json", scene_json("endless"));
  CmdResult r = run_cmd(exe() + " render -q --materials jit --max-loop-iterations 100000 " +
                        (d / "s.json").string() + " -o " + (d / "o.png").string());
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_EQ(r.out,
            "lobe render: " + (d / "s.json").string() +
                ": /materials/m: material 'm': shader endless (group m, layer 0 m): loop at " +
                (d / "endless.osl").string() +
                ":3 ran more than 100000 iterations (max_loop_iterations); stopped (while "
                "finding emitters)\n");
  EXPECT_FALSE(fs::exists(d / "o.png"));
}

TEST(ReliabilityRender, EndlessLoopWhileRenderingIsAnError) {
  fs::path d = temp_dir("render_loop");
  write_file(d / "camloop.osl", kEndlessCamera);
  write_file(d / "s.json", scene_json("camloop"));
  CmdResult r = run_cmd(exe() + " render -q --materials jit " + (d / "s.json").string() + " -o " +
                        (d / "o.png").string());
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(
      r.out.find("lobe render: " + (d / "s.json").string() +
                 ": /materials/m: material 'm': shader camloop (group m, layer 0 m): loop at " +
                 (d / "camloop.osl").string() +
                 ":4 ran more than 100000000 iterations (max_loop_iterations); stopped (while "
                 "rendering); rendering stopped, no image written\n"),
      std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(d / "o.png"));
}

// A material whose strings pass their memory (a quarter of what is available: under a 4 GB
// address-space limit, a string doubled 40 times) renders with the string that did not fit made
// "" (the sphere's albedo 0.5 where it fits would give 0.25), writes the image and says so,
// with exit status 1.
TEST(ReliabilityRender, StringsPastTheMemoryAreAnError) {
  if (kAddressSanitizer) GTEST_SKIP() << "cannot start under ulimit -v (see above)";
  fs::path d = temp_dir("render_strings");
  write_growing_string(d / "grow.osl", "surface",
                       "Ci = (strlen(s) == 0 ? 0.5 : 0.25) * diffuse(N);");
  write_file(d / "s.json", R"({"camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "fov": 12},
  "settings": {"resolution": [4, 4], "spp": 1},
  "materials": {"m": {"shader": "grow"}},
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
  "environment": {"type": "constant", "color": 1}})");
  CmdResult r = run_cmd("cd '" + d.string() + "' && { ulimit -v 4000000 && " + exe() +
                        " render -q s.json -o o.exr; }");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("lobe render: the shaders' strings passed the "), std::string::npos)
      << r.out;
  EXPECT_TRUE(fs::exists(d / "o.exr"));
}

// Ctrl-C while shaders loop without a limit: rendering stops, the finished samples are written.
TEST(ReliabilityRender, CtrlCWritesThePartialImage) {
  fs::path d = temp_dir("render_sigint");
  write_file(d / "notice.osl", endless_after_notice("notice", d / "started"));
  write_file(d / "s.json", scene_json("notice"));
  int st = interrupt_when_started({"render", "-q", "--materials", "jit", "--max-loop-iterations",
                                   "0", (d / "s.json").string(), "-o", (d / "o.png").string()},
                                  d, d / "log", d / "started");
  std::string log = read_file(d / "log");
  EXPECT_EQ(st, 130) << log;
  EXPECT_NE(log.find("interrupted: wrote the finished samples to " + (d / "o.png").string()),
            std::string::npos)
      << log;
  EXPECT_TRUE(fs::exists(d / "o.png"));
}

// A printf of a different line at every shade: at most 10 lines per material, then a summary.
// A material whose measured_bsdf file does not load renders its lobe black, and lobe render
// says so (once, naming the file) instead of a silently dark image.
TEST(ReliabilityRender, MeasuredFileThatDoesNotLoadIsReported) {
  fs::path d = temp_dir("render_merl");
  write_file(d / "meas.osl", "surface meas() { Ci = measured_bsdf(N, \"missing.binary\"); }\n");
  write_file(d / "s.json", scene_json("meas"));
  CmdResult r =
      run_cmd("cd '" + d.string() + "' && " + exe() + " render -q --materials jit s.json -o o.png");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "warning: measured_bsdf: cannot open measured BRDF 'missing.binary'; its lobes "
                   "are black\n");
}

TEST(ReliabilityRender, ShaderMessagesAreCapped) {
  fs::path d = temp_dir("render_printf");
  write_file(d / "chatty.osl",
             "surface chatty() { printf(\"at %g %g\\n\", u, v); Ci = diffuse(N); }\n");
  write_file(d / "s.json", scene_json("chatty", 16));
  CmdResult r = run_cmd(exe() + " render -q --materials jit " + (d / "s.json").string() + " -o " +
                        (d / "o.png").string());
  EXPECT_EQ(r.status, 0) << r.out;
  int lines = 0, summaries = 0;
  std::stringstream s(r.out);
  for (std::string line; std::getline(s, line);) {
    ++lines;
    if (line.find(": ... and ") != std::string::npos &&
        line.find(" more message lines") != std::string::npos)
      ++summaries;
  }
  EXPECT_EQ(lines, 11) << r.out;
  EXPECT_EQ(summaries, 1) << r.out;
}

// 16384^2 pixels at 148 bytes each (the accumulator's 44, the light paths' film's 24, and two
// copies of 10 float channels: cmd_render.cpp): 39.7 GB.
TEST(ReliabilityRender, HugeResolutionIsRefusedWithTheFigure) {
  if (kAddressSanitizer) GTEST_SKIP() << "ASan's shadow memory cannot start under ulimit -v";
  fs::path d = temp_dir("render_big");
  CmdResult r = run_cmd("ulimit -v 6000000 && " + exe() + " render -q --res 16384 16384 -o " +
                        (d / "big.exr").string());
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("lobe render: --res 16384 16384 needs about 39.7 GB of memory"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(d / "big.exr"));
}

TEST(ReliabilityBrdf, InvalidArgumentsAreRefused) {
  struct Case {
    std::string args, message;
  } cases[] = {
      {"'microfacet(\"beckman\", N, 0.2, 1.5, 0)'", "unknown distribution \"beckman\""},
      {"'conductor_bsdf(N, U, 0.2, 0.2, color(0.2,0.9,1.1), color(3.9,2.4,2.2), \"GGX\")'",
       "unknown distribution \"GGX\""},
      {"'diffuse(normal(0, 0, nan))'", "not a finite number"},
      {"'oren_nayar(N, 1e999)'", "not a finite number"},
      {"'diffuse(N)' --sample 0.5,1,0.2", "--sample: random numbers must lie in [0, 1)"},
      {"'diffuse(N)' --sample 0.5,-0.1,0.2", "--sample: random numbers must lie in [0, 1)"},
      {"'diffuse(N)' --sample 0.5,nan,0.2", "--sample: random numbers must lie in [0, 1)"},
      {"'diffuse(N)' --theta nan --sample 0.5,0.5,0.5", "--theta must be an angle"},
      {"'diffuse(N)' --albedo nan", "--albedo angles must lie in [0, 180]"},
      {"'diffuse(N)' --wo nan,0,1 --sample 0.5,0.5,0.5", "--wo must be finite and non-zero"},
      {"'diffuse(N)' --eval 0,0,1,0,0,0", "--eval: directions must be finite and non-zero"},
      // A measured BRDF whose file does not load has no lobe: an error, not a table of zeros
      // (before: exit status 0 and albedo 0).
      {"'measured_bsdf(N, \"/nonexistent/a/rather/long/path/to/gold.binary\")' --albedo 30",
       "lobe brdf: error: measured_bsdf: cannot open measured BRDF "
       "'/nonexistent/a/rather/long/path/to/gold.binary'"},
  };
  for (const Case& c : cases) {
    CmdResult r = run_cmd(exe() + " brdf " + c.args);
    EXPECT_EQ(r.status, 1) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.message), std::string::npos) << c.args << "\n" << r.out;
  }
  // The names it knows still work.
  CmdResult r = run_cmd(exe() + " brdf 'microfacet(\"beckmann\", N, 0.2, 1.5, 0)' --albedo 0");
  EXPECT_EQ(r.status, 0) << r.out;
}

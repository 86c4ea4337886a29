// `lobe info [options] shader [shader ...]`: each shader's parameters, as OSL's oslinfo lists
// them (compiler/ir/query.h), read from OSL source (or Lobe IR text) instead of a .oso.
//   -v             verbose: defaults, metadata and struct fields on lines of their own
//   --param NAME   only this parameter, without the shader line
//   -p SEARCHPATH  colon-separated directories to find shaders in
//   --runstats     print only the time each shader took to load
//   -I DIR         #include directory, also searched for shaders (a Lobe extension)
// A shader is `x`, `x.osl`, `x.lir`, `x.oso` (oslc's compiled form, which stands for x.osl) or a
// path, found by the one search order (compiler/driver/search.h) in the current directory, the
// -p and -I directories, then stdlib_shaders/ (as `lobe render` finds materials), and loaded by
// the compile driver. Output follows oslinfo, with one deliberate difference: a
// shader that is missing or does not compile gives exit status 1 (oslinfo exits 0).
#include "command.h"

#include "driver/driver.h"
#include "ir/query.h"
#include "lobe/install.h"

#include <chrono>
#include <cstdio>

namespace {

struct Options {
  lobe::ir::DescribeOptions describe{.verbose = false, .param = ""};
  bool runstats = false;
  std::vector<std::string> search; // -p, split at ':'
  std::vector<std::string> includes;
  std::vector<std::string> files;
};

// oslinfo's help, in its layout.
void help() {
  std::printf("lobe info -- list parameters of an OSL shader\n"
              "Lobe " LOBE_VERSION ", Open Shading Language 1.13 compatible\n"
              "\n"
              "Usage: lobe info [options] file0 [file1 ...]\n"
              "\n"
              "    --help         Print help message\n"
              "    -v             Verbose output\n"
              "    --runstats     Benchmark shader loading time for queries\n"
              "    -p SEARCHPATH  Set searchpath for shaders\n"
              "    --param NAME   Output information about just this parameter\n"
              "    -I DIR         Add DIR to the #include and shader search paths\n");
}

// An argument error as oslinfo reports it: the help on stdout, the message on stderr.
int arg_error(const std::string& message) {
  help();
  std::fprintf(stderr, "lobe info error: %s\n", message.c_str());
  return 1;
}

void split_path(const std::string& path, std::vector<std::string>& out) {
  size_t b = 0;
  while (b <= path.size()) {
    size_t e = path.find_first_of(":;", b);
    if (e == std::string::npos) e = path.size();
    if (e > b) out.push_back(path.substr(b, e - b));
    b = e + 1;
  }
}

// Fills `o`; returns -1 to go on, else the exit status (after --help or an argument error).
int parse_args(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&](std::string& dst) {
      if (i + 1 >= argc) return false;
      dst = argv[++i];
      return true;
    };
    std::string v;
    if (a == "--help" || a == "-h") {
      help();
      return 0;
    } else if (a == "-v") {
      o.describe.verbose = true;
    } else if (a == "--runstats") {
      o.runstats = true;
    } else if (a == "--param" || a == "-p" || a == "-I") {
      if (!value(v)) return arg_error("Missing parameter 1 from option \"" + a + "\"");
      if (a == "--param") o.describe.param = v;
      if (a == "-p") split_path(v, o.search);
      if (a == "-I") o.includes.push_back(v);
    } else if (a.rfind("-I", 0) == 0 && a.size() > 2) {
      o.includes.push_back(a.substr(2));
    } else if (a.size() > 1 && a[0] == '-') {
      return arg_error("Invalid option \"" + a + "\"");
    } else {
      o.files.push_back(a);
    }
  }
  if (o.files.empty()) { // oslinfo with no shader prints its help
    help();
    return 0;
  }
  return -1;
}

// Lists one shader; false when it is missing or does not compile (reported as oslinfo does:
// an empty shader line on stdout, the error on stderr).
bool info(const std::string& name, const Options& o) {
  auto t0 = std::chrono::steady_clock::now();
  std::vector<std::string> dirs = {"."};
  dirs.insert(dirs.end(), o.search.begin(), o.search.end());
  dirs.insert(dirs.end(), o.includes.begin(), o.includes.end());
  if (std::string stdlib = lobe::stdlib_shader_dir(); !stdlib.empty()) dirs.push_back(stdlib);
  std::string path = lobe::driver::find_shader(name, dirs, lobe::driver::Prefer::Compiled);
  if (path.empty()) { // in oslinfo's words: the name with .oso unless it ends so
    std::printf(" \"\"\n");
    std::fprintf(stderr, "ERROR: File %s not found\n",
                 (name.ends_with(".oso") ? name : name + ".oso").c_str());
    return false;
  }
  lobe::driver::Options d;
  d.frontend.include_dirs = o.includes;
  lobe::driver::Loaded l = lobe::driver::load_file(path, d);
  if (!l.shader) { // warnings of a shader that compiles are not shown: oslinfo shows none
    std::printf(" \"\"\n");
    std::fputs(l.rendered().c_str(), stderr);
    std::fprintf(stderr, "ERROR: Failed to compile %s\n", path.c_str());
    return false;
  }
  std::string text = lobe::ir::describe(*l.shader, o.describe);
  if (o.runstats) {
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%g sec for %s\n", s, name.c_str());
    return true;
  }
  std::fwrite(text.data(), 1, text.size(), stdout);
  return true;
}

int run_info(int argc, char** argv) {
  Options o;
  int st = parse_args(argc, argv, o);
  if (st >= 0) return st;
  bool ok = true;
  for (const std::string& f : o.files) ok &= info(f, o);
  return ok ? 0 : 1;
}

} // namespace

LOBE_COMMAND(info, "list a shader's parameters, as OSL's oslinfo does", run_info);

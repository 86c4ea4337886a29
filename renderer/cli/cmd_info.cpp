// `lobe info shader [-I dir]`: the shader's type, name, parameters with their defaults and
// metadata, in the style of `oslinfo -v`. The shader is named by path or by name
// (`lobe info test` finds test.osl or test.lir in the current directory or an -I dir).
#include "command.h"
#include "load_shader.h"

#include "ir/query.h"

#include <cstdio>

namespace {

int run_info(int argc, char** argv) {
  std::string name;
  std::vector<std::string> dirs;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::printf("usage: lobe info shader [-I dir]\n");
      return 0;
    }
    if (a == "-I" && i + 1 < argc)
      dirs.push_back(argv[++i]);
    else if (a.rfind("-I", 0) == 0 && a.size() > 2)
      dirs.push_back(a.substr(2));
    else if (a == "-v")
      continue; // oslinfo's verbose flag: always verbose
    else if (name.empty() && a[0] != '-')
      name = a;
    else {
      std::fprintf(stderr, "usage: lobe info shader [-I dir]\n");
      return 2;
    }
  }
  if (name.empty()) {
    std::fprintf(stderr, "usage: lobe info shader [-I dir]\n");
    return 2;
  }
  std::string path = lobe::cli::find_shader(name, dirs);
  if (path.empty()) {
    std::fprintf(stderr, "lobe info: cannot find shader '%s'\n", name.c_str());
    return 1;
  }
  lobe::lower::PipelineOptions po;
  po.frontend.include_dirs = dirs;
  lobe::cli::Loaded l =
      lobe::cli::is_ir_text(path) ? lobe::cli::load_ir_text(path) : lobe::cli::load_osl(path, po);
  std::fputs(l.errors.c_str(), stderr);
  if (!l.shader) return l.status;
  std::string text = lobe::ir::describe(*l.shader);
  std::fwrite(text.data(), 1, text.size(), stdout);
  return 0;
}

} // namespace

LOBE_COMMAND(info, "describe a shader's parameters (oslinfo -v style)", run_info);

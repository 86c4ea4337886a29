// Shared by `lobe compile` and `lobe info`: finds a shader by name or path and loads it as
// Lobe IR. Sources: Lobe IR text (.lir, as printed by `lobe compile --emit=ir`) and OSL
// source (.osl, or any other name) through the compile pipeline (compiler/lower/pipeline.h).
#pragma once

#include "lower/pipeline.h"

#include "ir/ir.h"
#include "ir/parser.h"
#include "ir/verifier.h"

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace lobe::cli {

// Where `lobe compile` and `lobe info` look for shader `name`: `x.oso` stands for `x` (oslc's
// output; Lobe reads the source), a name ending in .osl or .lir is that file, any other name is
// name.osl, else name.lir. A relative name is looked for in each of `dirs` in order ("." is the
// current directory), an absolute one where it is. "" if not found.
inline std::string find_shader(std::string name, const std::vector<std::string>& dirs) {
  namespace fs = std::filesystem;
  if (fs::path(name).extension() == ".oso") name.resize(name.size() - 4);
  std::string ext = fs::path(name).extension().string();
  std::vector<std::string> files = {name};
  if (ext != ".osl" && ext != ".lir") files = {name + ".osl", name + ".lir"};
  std::vector<std::string> places = dirs;
  if (fs::path(name).is_absolute()) places = {""};
  std::error_code ec;
  for (const std::string& d : places)
    for (const std::string& f : files) {
      fs::path p = d.empty() || d == "." ? fs::path(f) : fs::path(d) / f;
      if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
    }
  return "";
}

struct Loaded {
  std::optional<ir::Shader> shader;
  std::string errors; // rendered, for stderr
  int status = 0;     // 0 ok, 1 input error, 2 not supported
};

inline Loaded load_ir_text(const std::string& path) {
  Loaded r;
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  ir::ParseResult pr = ir::parse(ss.str());
  if (!pr.shader) {
    r.errors = path + ":" + std::to_string(pr.error.line) + ":" + std::to_string(pr.error.column) +
               ": error: " + pr.error.message + "\n";
    r.status = 1;
    return r;
  }
  for (const std::string& e : ir::verify(*pr.shader)) r.errors += path + ": error: " + e + "\n";
  if (!r.errors.empty()) {
    r.status = 1;
    return r;
  }
  r.shader = std::move(pr.shader);
  return r;
}

inline bool is_ir_text(const std::string& path) {
  return path.size() >= 4 && path.compare(path.size() - 4, 4, ".lir") == 0;
}

// OSL source through the front end and lowering. Diagnostics (warnings too) in `errors`.
inline Loaded load_osl(const std::string& path, const lower::PipelineOptions& options) {
  Loaded r;
  lower::PipelineResult pr = lower::compile_osl({path, std::nullopt}, options);
  r.errors = pr.diagnostics;
  if (!pr.ok || !pr.shader) {
    r.status = 1;
    return r;
  }
  r.shader = std::move(pr.shader);
  return r;
}

} // namespace lobe::cli

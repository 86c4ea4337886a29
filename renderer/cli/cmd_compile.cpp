// `lobe compile file [-I dir] [-D NAME[=val]] [-U NAME] [-o out] [--emit=ast|ir|llvm|asm]
// [-O0|-O1|-O2]` Compiles a shader and writes the requested form (default: Lobe IR text) to
// stdout or -o. OSL source goes through the whole pipeline (compiler/lower/pipeline.h); Lobe IR
// text (.lir) is parsed, verified and re-optimised. --emit=llvm|asm compile the shader (OSL or
// IR text) as a one-layer group the way the ShadingSystem does (its defaults, specialised
// above -O0) and print the LLVM IR after the JIT's pipeline at that level, or the host assembly
// (runtime/group/emit_text.h). Diagnostics go to stderr; exit status 1 on errors in the
// input, 2 on usage errors.
#include "command.h"
#include "load_shader.h"

#include "ast/ast_dump.h"
#include "emit_text.h"
#include "ir/printer.h"
#include "passes/constfold.h"
#include "passes/dce.h"
#include "passes/derivs.h"

#include <cstdio>
#include <cstring>

namespace {

struct Options {
  std::string file, out, emit = "ir";
  std::vector<std::string> includes, defines, undefines;
  int opt = 1;
};

void usage(FILE* f) {
  std::fprintf(f, "usage: lobe compile file.osl|file.lir [-I dir] [-D NAME[=val]] [-U NAME]\n"
                  "                    [-o out] [--emit=ast|ir|llvm|asm] [-O0|-O1|-O2]\n");
}

// Returns 0 on success, 2 on a usage error (message printed).
int parse_args(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&](const char* opt, std::string& dst) {
      if (a.size() > std::strlen(opt)) {
        dst = a.substr(std::strlen(opt));
        return true;
      }
      if (i + 1 >= argc) return false;
      dst = argv[++i];
      return true;
    };
    std::string v;
    if (a == "-h" || a == "--help") {
      usage(stdout);
      return -1;
    } else if (a.rfind("--emit=", 0) == 0)
      o.emit = a.substr(7);
    else if (a == "-O0" || a == "-O1" || a == "-O2")
      o.opt = a[2] - '0';
    else if (a.rfind("-I", 0) == 0) {
      if (!value("-I", v)) return 2;
      o.includes.push_back(v);
    } else if (a.rfind("-D", 0) == 0) {
      if (!value("-D", v)) return 2;
      o.defines.push_back(v);
    } else if (a.rfind("-U", 0) == 0) {
      if (!value("-U", v)) return 2;
      o.undefines.push_back(v);
    } else if (a == "-o") {
      if (i + 1 >= argc) return 2;
      o.out = argv[++i];
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "lobe compile: unknown option '%s'\n", a.c_str());
      return 2;
    } else if (o.file.empty())
      o.file = a;
    else {
      std::fprintf(stderr, "lobe compile: more than one input file\n");
      return 2;
    }
  }
  if (o.file.empty()) return 2;
  if (o.emit != "ast" && o.emit != "ir" && o.emit != "llvm" && o.emit != "asm") {
    std::fprintf(stderr, "lobe compile: unknown --emit form '%s'\n", o.emit.c_str());
    return 2;
  }
  return 0;
}

int write_output(const Options& o, const std::string& text) {
  if (o.out.empty()) {
    std::fwrite(text.data(), 1, text.size(), stdout);
    return 0;
  }
  FILE* f = std::fopen(o.out.c_str(), "wb");
  if (!f) {
    std::fprintf(stderr, "lobe compile: cannot write '%s'\n", o.out.c_str());
    return 1;
  }
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
  return 0;
}

// OSL source: the typed AST (--emit=ast) or the verified IR, optimised at -O1.
int compile_source(const Options& o, const std::string& path) {
  lobe::lower::PipelineOptions po;
  po.frontend.include_dirs = o.includes;
  po.frontend.defines = o.defines;
  po.frontend.undefines = o.undefines;
  po.lower = o.emit != "ast";
  po.optimize = o.opt > 0;
  lobe::lower::PipelineResult r = lobe::lower::compile_osl({path, std::nullopt}, po);
  std::fputs(r.diagnostics.c_str(), stderr);
  if (!r.ok) return 1;
  if (o.emit == "ast")
    return write_output(o, lobe::ast::dump(*r.tu, {.types = true, .stdlib = false}));
  return write_output(o, lobe::ir::print(*r.shader));
}

int run_compile(int argc, char** argv) {
  Options o;
  int st = parse_args(argc, argv, o);
  if (st < 0) return 0;
  if (st) {
    usage(stderr);
    return 2;
  }
  std::string path = lobe::cli::find_shader(o.file, o.includes);
  if (path.empty()) {
    std::fprintf(stderr, "lobe compile: cannot find shader '%s'\n", o.file.c_str());
    return 1;
  }
  if (o.emit == "llvm" || o.emit == "asm") {
    lobe::CompileOptions co;
    co.include_dirs = o.includes;
    co.defines = o.defines;
    co.undefines = o.undefines;
    co.opt_level = o.opt;
    lobe::DiagnosticList diags;
    std::string text;
    bool ok = lobe::group::emit_shader_text(
        path, co, o.emit == "asm" ? lobe::group::EmitForm::Assembly : lobe::group::EmitForm::LlvmIr,
        text, diags);
    for (const lobe::Diagnostic& d : diags) {
      std::fputs(d.text.c_str(), stderr);
      if (d.text.empty() || d.text.back() != '\n') std::fputc('\n', stderr);
    }
    if (!ok) return 1;
    return write_output(o, text);
  }
  if (!lobe::cli::is_ir_text(path)) return compile_source(o, path);
  if (o.emit != "ir") {
    std::fprintf(stderr, "lobe compile: --emit=%s needs OSL source\n", o.emit.c_str());
    return 2;
  }
  lobe::cli::Loaded l = lobe::cli::load_ir_text(path);
  if (!l.shader) {
    std::fputs(l.errors.c_str(), stderr);
    return l.status;
  }
  if (o.opt > 0)
    for (int round = 0; round < 8; ++round)
      if (!(lobe::passes::fold_constants(*l.shader) | lobe::passes::eliminate_dead_code(*l.shader)))
        break;
  lobe::passes::analyze_derivatives(*l.shader);
  return write_output(o, lobe::ir::print(*l.shader));
}

} // namespace

LOBE_COMMAND(compile, "compile a shader to Lobe IR (or LLVM IR / assembly)", run_compile);

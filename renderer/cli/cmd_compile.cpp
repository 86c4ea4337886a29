// `lobe compile [options] file`: compiles a shader as OSL's oslc does, to Lobe IR text (Lobe's
// compiled form, as .oso is OSL's). Without -o the output is the shader's name with .lir in the
// current directory, as oslc writes `name.oso` there (the file's base name when the shader has
// none, as for --emit=ast); stdout says `Compiled x.osl -> name.lir` (not
// with -q), or `FAILED x.osl` with exit status 1. Options, one word or two (-Idir, -I dir):
//   -o FILE                  the output file
//   -I DIR, -D N[=V], -U N   #include directory, preprocessor definitions
//   -O0 | -O1 | -O2          optimisation level (default -O1)
//   -q, -v                   no `Compiled` line / the default; the last one wins
//   -Werror                  warnings are errors
//   -E                       print the preprocessed source to stdout instead of compiling
//   --no-fast-math           fold math builtins with libm (CompileOptions::fast_math = false)
//   --emit=ast|ir|llvm|asm   print that form to stdout (or -o FILE), without oslc's lines: the
//                            typed AST, the IR, or the shader compiled as a one-layer group the
//                            way the ShadingSystem does, as LLVM IR after the JIT's pipeline at
//                            the -O level or host assembly (runtime/group/emit_text.h)
// oslc's -d, -embed-source and -buffer are accepted and do nothing; other unknown options are
// ignored with a warning (oslc ignores them silently). The input is a path or a shader name
// found by the one search order (compiler/driver/search.h) in the current directory, then the
// -I dirs (`x` finds x.osl, then x.lir); it is loaded by the compile driver
// (compiler/driver/driver.h): Lobe IR text (.lir) is parsed, verified and re-optimised. Diagnostics
// go to stderr in Clang's form (file:line:col, the source line, a caret; oslc prints file:line).
// Exit status 1 on errors in the input, 2 on usage errors.
#include "command.h"

#include "ast/ast_dump.h"
#include "diag/source_manager.h"
#include "driver/driver.h"
#include "emit_text.h"
#include "ir/printer.h"

#include <cstdio>
#include <cstring>
#include <filesystem>

namespace {

namespace fs = std::filesystem;

struct Options {
  std::string file, out;
  std::string emit; // "" writes the compiled file; else ast|ir|llvm|asm to stdout or -o
  std::vector<std::string> includes, defines, undefines;
  int opt = 1;
  bool quiet = false, werror = false, preprocess_only = false;
  bool fast_math = true;
};

void help() {
  std::printf("lobe compile -- Lobe " LOBE_VERSION ", an Open Shading Language 1.13 compiler\n"
              "Usage:  lobe compile [options] file\n"
              "  Options:\n"
              "\t--help         Print this usage message\n"
              "\t-o filename    Specify output filename\n"
              "\t-v             Verbose mode\n"
              "\t-q             Quiet mode\n"
              "\t-Ipath         Add path to the #include search path\n"
              "\t-Dsym[=val]    Define preprocessor symbol\n"
              "\t-Usym          Undefine preprocessor symbol\n"
              "\t-O0, -O1, -O2  Set optimization level (default=1)\n"
              "\t-E             Only preprocess the input and output to stdout\n"
              "\t-Werror        Treat all warnings as errors\n"
              "\t--no-fast-math Fold math builtins as libm computes them\n"
              "\t--emit=FORM    Print the ast, ir, llvm or asm to stdout (or -o) instead\n");
}

// Fills `o`; returns -1 to go on, else the exit status (after --help or a usage error).
int parse_args(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    // -Xvalue or -X value.
    auto value = [&](const char* opt, std::vector<std::string>& dst) {
      if (a.size() > std::strlen(opt))
        dst.push_back(a.substr(std::strlen(opt)));
      else if (i + 1 < argc)
        dst.push_back(argv[++i]);
      else
        return false;
      return true;
    };
    bool ok = true;
    if (a == "--help" || a == "-h") {
      help();
      return 0;
    } else if (a.rfind("--emit=", 0) == 0) {
      o.emit = a.substr(7);
    } else if (a == "-O0" || a == "-O1" || a == "-O2") {
      o.opt = a[2] - '0';
    } else if (a == "-q" || a == "-v") {
      o.quiet = a == "-q";
    } else if (a == "--no-fast-math") {
      o.fast_math = false;
    } else if (a == "-Werror") {
      o.werror = true;
    } else if (a == "-E") {
      o.preprocess_only = true;
    } else if (a.rfind("-I", 0) == 0) {
      ok = value("-I", o.includes);
    } else if (a.rfind("-D", 0) == 0) {
      ok = value("-D", o.defines);
    } else if (a.rfind("-U", 0) == 0) {
      ok = value("-U", o.undefines);
    } else if (a == "-o") {
      ok = i + 1 < argc;
      if (ok) o.out = argv[++i];
    } else if (a == "-d" || a == "-embed-source" || a == "--embed-source" || a == "-buffer") {
      continue; // oslc's debugging aids: nothing to do for Lobe IR
    } else if (a == "-MF" || a == "-MT" || a == "-MD" || a == "-MMD" || a == "-M" || a == "-MM") {
      std::fprintf(stderr, "lobe compile: warning: %s (dependency files) is not supported\n",
                   a.c_str());
      if ((a == "-MF" || a == "-MT") && i + 1 < argc) ++i;
    } else if (a.size() > 1 && a[0] == '-') {
      std::fprintf(stderr, "lobe compile: warning: unknown option '%s' ignored\n", a.c_str());
    } else if (o.file.empty()) {
      o.file = a;
    } else {
      std::fprintf(stderr, "lobe compile: more than one input file ('%s', '%s')\n", o.file.c_str(),
                   a.c_str());
      return 2;
    }
    if (!ok) {
      std::fprintf(stderr, "lobe compile: option '%s' needs a value\n", a.c_str());
      return 2;
    }
  }
  if (o.file.empty()) { // as oslc: no input prints the help
    help();
    return 0;
  }
  if (!o.emit.empty() && o.emit != "ast" && o.emit != "ir" && o.emit != "llvm" && o.emit != "asm") {
    std::fprintf(stderr, "lobe compile: unknown --emit form '%s'\n", o.emit.c_str());
    return 2;
  }
  return -1;
}

// Writes `text` to -o FILE or to the default name (`shader`.lir, else the file's base name), or
// to stdout for --emit without -o. `Compiled X -> Y` follows a file written (unless -q).
bool write_output(const Options& o, const std::string& text, const std::string& shader = "") {
  std::string out = o.out;
  if (out.empty() && !o.emit.empty()) {
    std::fwrite(text.data(), 1, text.size(), stdout);
    return true;
  }
  if (out.empty()) out = (shader.empty() ? fs::path(o.file).stem().string() : shader) + ".lir";
  std::error_code ec;
  if (fs::equivalent(out, o.file, ec)) {
    std::fprintf(stderr, "lobe compile: error: the output \"%s\" is the input; give -o FILE\n",
                 out.c_str());
    return false;
  }
  FILE* f = std::fopen(out.c_str(), "wb");
  if (!f) {
    std::fprintf(stderr, "lobe compile: error: could not open \"%s\" for writing\n", out.c_str());
    return false;
  }
  bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  ok &= std::fclose(f) == 0;
  if (!ok) std::fprintf(stderr, "lobe compile: error: could not write \"%s\"\n", out.c_str());
  if (ok && !o.quiet) std::printf("Compiled %s -> %s\n", o.file.c_str(), out.c_str());
  return ok;
}

lobe::frontend::FrontendOptions frontend_options(const Options& o) {
  lobe::frontend::FrontendOptions fo;
  fo.include_dirs = o.includes;
  fo.defines = o.defines;
  fo.undefines = o.undefines;
  return fo;
}

// -E: the preprocessed text on stdout.
bool preprocess(const Options& o, const std::string& path) {
  lobe::diag::DiagnosticEngine diags;
  diags.set_warnings_as_errors(o.werror);
  lobe::diag::SourceManager sm;
  std::string text =
      lobe::frontend::preprocess({path, std::nullopt}, frontend_options(o), diags, sm);
  std::fputs(lobe::diag::render_all(diags, sm).c_str(), stderr);
  if (diags.has_errors()) return false;
  std::fwrite(text.data(), 1, text.size(), stdout);
  return true;
}

// OSL source: the typed AST (--emit=ast) or the verified IR, optimised at -O1 and -O2; Lobe IR
// text: parsed, verified, re-optimised above -O0, its derivative flags recomputed.
bool compile_file(const Options& o, const std::string& path) {
  lobe::driver::Options d;
  d.frontend = frontend_options(o);
  d.lower = o.emit != "ast";
  d.optimize = o.opt > 0;
  d.fast_math = o.fast_math;
  d.warnings_as_errors = o.werror;
  d.reanalyze_ir = true;
  lobe::driver::Loaded l = lobe::driver::load_file(path, d);
  std::fputs(l.rendered().c_str(), stderr);
  if (!l.ok) return false;
  if (o.emit == "ast")
    return write_output(o, lobe::ast::dump(*l.tu, {.types = true, .stdlib = false}));
  return write_output(o, lobe::ir::print(*l.shader), l.shader->name);
}

// --emit=llvm|asm (OSL or IR text) through the runtime.
bool emit_machine_text(const Options& o, const std::string& path) {
  lobe::CompileOptions co;
  co.include_dirs = o.includes;
  co.defines = o.defines;
  co.undefines = o.undefines;
  co.opt_level = o.opt;
  co.fast_math = o.fast_math;
  lobe::DiagnosticList diags;
  std::string text;
  bool ok = lobe::group::emit_shader_text(
      path, co, o.emit == "asm" ? lobe::group::EmitForm::Assembly : lobe::group::EmitForm::LlvmIr,
      text, diags);
  for (const lobe::Diagnostic& d : diags) {
    std::fputs(d.text.c_str(), stderr);
    if (d.text.empty() || d.text.back() != '\n') std::fputc('\n', stderr);
    ok &= !(o.werror && d.severity == lobe::Diagnostic::Severity::Warning);
  }
  return ok && write_output(o, text);
}

int run_compile(int argc, char** argv) {
  Options o;
  int st = parse_args(argc, argv, o);
  if (st >= 0) return st;
  bool oslc_lines = o.emit.empty(); // FAILED on stdout, as oslc prints it
  std::error_code ec;
  std::string path =
      fs::is_regular_file(o.file, ec) ? o.file : lobe::driver::find_shader(o.file, [&] {
        std::vector<std::string> dirs = {"."};
        dirs.insert(dirs.end(), o.includes.begin(), o.includes.end());
        return dirs;
      }());
  bool ok = false;
  if (path.empty()) {
    std::fprintf(stderr, "error: Input file \"%s\" not found\n", o.file.c_str());
  } else if (lobe::driver::is_ir_path(path) && (o.preprocess_only || o.emit == "ast")) {
    std::fprintf(stderr, "lobe compile: %s needs OSL source\n",
                 o.preprocess_only ? "-E" : "--emit=ast");
    return 2;
  } else if (o.preprocess_only) {
    ok = preprocess(o, path);
  } else if (o.emit == "llvm" || o.emit == "asm") {
    ok = emit_machine_text(o, path);
  } else {
    ok = compile_file(o, path);
  }
  if (!ok && oslc_lines) std::printf("FAILED %s\n", o.file.c_str());
  return ok ? 0 : 1;
}

} // namespace

LOBE_COMMAND(compile, "compile a shader to Lobe IR, as OSL's oslc does", run_compile);

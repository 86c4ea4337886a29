// Subcommand registration for the `lobe` executable.
//
//   static int run_compile(int argc, char** argv);   // argv[0] is "compile"
//   LOBE_COMMAND(compile, "compile a shader to IR, LLVM IR or assembly", run_compile);
//
// Exit status: 0 success, 1 user error (bad input, diagnostics printed), 2 usage error.
#pragma once

#include <map>
#include <string>

namespace lobe::cli {

struct Command {
  const char* summary;
  int (*run)(int argc, char** argv);
};

std::map<std::string, Command>& commands();

struct Registrar {
  Registrar(const char* name, const char* summary, int (*run)(int, char**)) {
    commands()[name] = Command{summary, run};
  }
};

} // namespace lobe::cli

#define LOBE_COMMAND(name, summary, fn)                                                            \
  static const ::lobe::cli::Registrar lobe_command_registrar_##name(#name, summary, fn)

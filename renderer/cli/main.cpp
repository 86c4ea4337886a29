// `lobe`: dispatches to the subcommand named by the first argument.
#include "command.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <new>

namespace lobe::cli {
std::map<std::string, Command>& commands() {
  static std::map<std::string, Command> table;
  return table;
}
} // namespace lobe::cli

static void usage(FILE* out) {
  std::fprintf(out, "usage: lobe <command> [options]\n\ncommands:\n");
  for (const auto& [name, cmd] : lobe::cli::commands())
    std::fprintf(out, "  %-10s %s\n", name.c_str(), cmd.summary);
  std::fprintf(out, "\n'lobe <command> --help' describes a command's options.\n");
}

int main(int argc, char** argv) {
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  if (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
      !std::strcmp(argv[1], "help")) {
    usage(stdout);
    return 0;
  }
  if (!std::strcmp(argv[1], "--version") || !std::strcmp(argv[1], "version")) {
    std::printf("lobe " LOBE_VERSION " (Open Shading Language 1.13 compatible)\n");
    return 0;
  }
  auto& table = lobe::cli::commands();
  auto it = table.find(argv[1]);
  if (it == table.end()) {
    std::fprintf(stderr, "lobe: unknown command '%s'\n\n", argv[1]);
    usage(stderr);
    return 2;
  }
  // The last line of defence: a command that runs out of memory or meets an error nobody
  // expected says so and exits 1, never terminate() and exit 134.
  try {
    return it->second.run(argc - 1, argv + 1);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "lobe %s: error: out of memory (a request too big for this machine; "
                 "try a smaller resolution, grid or scene)\n",
                 argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lobe %s: error: %s\n", argv[1], e.what());
  }
  return 1;
}

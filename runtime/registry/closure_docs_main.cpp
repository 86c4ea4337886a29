// closure_docs: prints the closures reference table generated from the registry, or, with
// `--update FILE`, rewrites the generated sections of FILE in place (the closure table of
// docs/closures.md, the library calls of docs/language.md).
//   ./build/runtime/registry/closure_docs --update docs/closures.md
//   ./build/runtime/registry/closure_docs --update docs/language.md
#include "closure_docs.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

int main(int argc, char** argv) {
  if (argc == 1) {
    std::fputs(lobe::registry::closure_reference_markdown().c_str(), stdout);
    return 0;
  }
  if (argc != 3 || std::strcmp(argv[1], "--update") != 0) {
    std::fprintf(stderr, "usage: closure_docs [--update docs/closures.md | docs/language.md]\n");
    return 2;
  }
  std::ifstream in(argv[2], std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string doc = ss.str();
  if (!in || !lobe::registry::replace_generated_section(doc)) {
    std::fprintf(stderr, "closure_docs: %s: no generated section (marker lines)\n", argv[2]);
    return 1;
  }
  std::ofstream(argv[2], std::ios::binary) << doc;
  return 0;
}

// scene_docs: prints the shape-kinds table generated from shape_kinds.cpp, or, with
// `--update FILE`, rewrites the generated section of FILE (docs/scene-format.md) in place.
//   ./build/renderer/scene/scene_docs --update docs/scene-format.md
#include "shape_kinds.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

int main(int argc, char** argv) {
  if (argc == 1) {
    std::fputs(lobe::scene::shape_reference_markdown().c_str(), stdout);
    return 0;
  }
  if (argc != 3 || std::strcmp(argv[1], "--update") != 0) {
    std::fprintf(stderr, "usage: scene_docs [--update docs/scene-format.md]\n");
    return 2;
  }
  std::ifstream in(argv[2], std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string doc = ss.str();
  if (!in || !lobe::scene::replace_shape_section(doc)) {
    std::fprintf(stderr, "scene_docs: %s: no generated section (marker lines)\n", argv[2]);
    return 1;
  }
  std::ofstream(argv[2], std::ios::binary) << doc;
  return 0;
}

// Generated sections of docs/: a table written from one of the project's tables between two
// marker lines of a Markdown file, and the small tool that prints or rewrites them. Used by
// closure_docs (closures, library calls, math functions) and scene_docs (shape kinds); each
// has a test that the committed text is what its table generates.
#pragma once

#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

namespace lobe::registry {

// Replaces the text between the line holding `begin` and the one holding `end` with `text`:
// 1 when replaced, 0 when `doc` has no `begin`, -1 when the pair is broken.
inline int replace_between(std::string& doc, const char* begin, const char* end,
                           const std::string& text) {
  size_t b = doc.find(begin);
  if (b == std::string::npos) return 0;
  size_t body = doc.find('\n', b);
  size_t e = doc.find(end, b);
  if (body == std::string::npos || e == std::string::npos || e < body) return -1;
  doc.replace(body + 1, e - (body + 1), text);
  return 1;
}

// A docs tool's main: with no argument prints `generate()`; with `--update FILE` rewrites
// FILE's generated sections through `replace` (false: none found). Exit status 0, 1 (no
// section or unreadable file) or 2 (usage).
inline int docs_tool_main(int argc, char** argv, const char* tool, const char* files,
                          const std::function<std::string()>& generate,
                          const std::function<bool(std::string&)>& replace) {
  if (argc == 1) {
    std::fputs(generate().c_str(), stdout);
    return 0;
  }
  if (argc != 3 || std::strcmp(argv[1], "--update") != 0) {
    std::fprintf(stderr, "usage: %s [--update %s]\n", tool, files);
    return 2;
  }
  std::ifstream in(argv[2], std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string doc = ss.str();
  if (!in || !replace(doc)) {
    std::fprintf(stderr, "%s: %s: no generated section (marker lines)\n", tool, argv[2]);
    return 1;
  }
  std::ofstream(argv[2], std::ios::binary) << doc;
  return 0;
}

} // namespace lobe::registry

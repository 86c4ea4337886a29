// closure_docs: prints the closures reference table generated from the registry, or, with
// `--update FILE`, rewrites the generated sections of FILE in place (the closure table of
// docs/closures.md, the library calls and math functions of docs/language.md).
//   ./build/runtime/registry/closure_docs --update docs/closures.md
//   ./build/runtime/registry/closure_docs --update docs/language.md
#include "closure_docs.h"
#include "generated_docs.h"

int main(int argc, char** argv) {
  return lobe::registry::docs_tool_main(
      argc, argv, "closure_docs", "docs/closures.md | docs/language.md",
      lobe::registry::closure_reference_markdown, lobe::registry::replace_generated_section);
}

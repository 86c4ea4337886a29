// scene_docs: prints the shape-kinds table generated from shape_kinds.cpp, or, with
// `--update FILE`, rewrites the generated sections of FILE (docs/scene-format.md: the shape
// kinds and the light kinds of light_kinds.cpp) in place.
//   ./build/renderer/scene/scene_docs --update docs/scene-format.md
#include "generated_docs.h"
#include "shape_kinds.h"

int main(int argc, char** argv) {
  return lobe::registry::docs_tool_main(argc, argv, "scene_docs", "docs/scene-format.md",
                                        lobe::scene::shape_reference_markdown,
                                        lobe::scene::replace_scene_sections);
}

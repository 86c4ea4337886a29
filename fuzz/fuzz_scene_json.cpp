// JSON scenes (`lobe render scene.json`). The scene "lives" in a directory that does not
// exist, so relative mesh and texture names resolve to nothing.
#include "scene.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string error;
  std::string text(reinterpret_cast<const char*>(data), size);
  (void)lobe::scene::parse_json_scene(text, "/nonexistent-lobe-fuzz/scene.json", error);
  return 0;
}

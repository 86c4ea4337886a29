// OSL testrender XML scenes (`lobe render scene.xml`), read like fuzz_scene_json.
#include "scene.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string error;
  std::string text(reinterpret_cast<const char*>(data), size);
  (void)lobe::scene::parse_xml_scene(text, "/nonexistent-lobe-fuzz/scene.xml", error);
  return 0;
}

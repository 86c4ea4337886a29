// Wavefront OBJ meshes (scene "mesh" shapes), through tinyobjloader and Lobe's re-indexing.
#include "fuzz_util.h"
#include "mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lobe::scene::Mesh mesh;
  (void)lobe::scene::load_obj(lobe::fuzz::temp_file(".obj", data, size), mesh);
  return 0;
}

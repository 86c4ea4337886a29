// PLY meshes (ASCII and binary, either byte order), Lobe's own reader (ply_reader.cpp).
#include "fuzz_util.h"
#include "mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lobe::scene::Mesh mesh;
  (void)lobe::scene::load_ply(lobe::fuzz::temp_file(".ply", data, size), mesh);
  return 0;
}

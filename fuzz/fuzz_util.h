// Shared helpers for the libFuzzer targets (fuzz/README.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace lobe::fuzz {

// The loaders that only read from a path (meshes, MERL files) get the input through a file
// in /dev/shm (memory), one per process so that parallel fuzzers (-jobs) do not collide.
inline std::string temp_file(const char* ext, const uint8_t* data, size_t size) {
  std::string path = "/dev/shm/lobe-fuzz-" + std::to_string(getpid()) + ext;
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    if (size) std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  return path;
}

} // namespace lobe::fuzz

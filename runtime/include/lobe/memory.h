// Bounded memory: a size the user sets or a file declares (a grid, a resolution, an image's
// width and height, a scene's triangles) is turned into the bytes it will cost before anything
// is allocated, and refused when that exceeds what the process can have: the smaller of the
// physical memory and what the address-space and data limits (ulimit -v, ulimit -d) leave above
// the memory already in use. Used by the commands, the image reader and the renderer's set-up.
#pragma once

#include <cstdint>
#include <string>

namespace lobe {

// Bytes this process may still allocate (an estimate; UINT64_MAX when nothing limits it).
uint64_t available_memory_bytes();

// "12.3 GB" (powers of 1000; B, kB, MB, GB, TB, PB, EB).
std::string format_bytes(double bytes);

// "" when `bytes` fits in the available memory; else the error, naming `setting` (e.g.
// "-g 100000 100000") and both figures: "SETTING needs about X of memory (WHAT), more than the Y
// available (physical memory, ulimit -v and -d); use a smaller size".
std::string check_memory(const std::string& setting, double bytes, const char* what);

} // namespace lobe

// Bounded memory: a size the user sets or a file declares (a grid, a resolution, an image's
// width and height, a scene's triangles) is turned into the bytes it will cost before anything
// is allocated, and refused when that exceeds what the process can have: the smaller of the
// physical memory and what the address-space and data limits (ulimit -v, ulimit -d) leave above
// the memory already in use. Used by the commands, the image reader and the renderer's set-up.
//
// Large buffers on transparent huge pages: a LargeVector<T> is a std::vector whose blocks of
// 2 MiB and more are mapped on their own, starting on a 2 MiB boundary, and marked
// MADV_HUGEPAGE (where the kernel's THP setting is "madvise", the default of many
// distributions, memory is otherwise faulted in 4 KiB at a time). Touching such a block first
// then costs one page fault per whole 2 MiB it spans (the tail past the last whole one stays in
// 4 KiB pages: nothing is rounded up) instead of one per 4 KiB; in a virtual machine a fault
// costs several microseconds, and the environment tables, meshes and film of one render took
// thousands. Smaller blocks come from operator new. Built with AddressSanitizer, every block
// comes from operator new, so that the sanitizer still checks them; off Linux, likewise.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <string>
#include <vector>

namespace lobe {

// Bytes this process may still allocate (an estimate; UINT64_MAX when nothing limits it).
uint64_t available_memory_bytes();

// "12.3 GB" (powers of 1000; B, kB, MB, GB, TB, PB, EB).
std::string format_bytes(double bytes);

// "" when `bytes` fits in the available memory; else the error, naming `setting` (e.g.
// "-g 100000 100000") and both figures: "SETTING needs about X of memory (WHAT), more than the Y
// available (physical memory, ulimit -v and -d); use a smaller size".
std::string check_memory(const std::string& setting, double bytes, const char* what);

// A block of `bytes` for LargeAllocator (std::bad_alloc when there is no memory for it), and
// its release (with the same `bytes`).
void* allocate_large(std::size_t bytes);
void release_large(void* p, std::size_t bytes) noexcept;
// Whether blocks of 2 MiB and more get a mapping of their own here (false when built with
// AddressSanitizer, and off Linux).
bool large_blocks_mapped();

template <class T> struct LargeAllocator {
  using value_type = T;
  LargeAllocator() = default;
  template <class U> LargeAllocator(const LargeAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocate_large(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { release_large(p, n * sizeof(T)); }
  template <class U> bool operator==(const LargeAllocator<U>&) const noexcept { return true; }
};

template <class T> using LargeVector = std::vector<T, LargeAllocator<T>>;

} // namespace lobe

// Bounded memory (lobe/memory.h): what the process may still allocate, and the check; large
// blocks on huge pages.
#include "lobe/memory.h"

#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>

namespace lobe {

// Bytes this process may still allocate (an estimate; UINT64_MAX when nothing limits it).
uint64_t available_memory_bytes() {
  uint64_t avail = UINT64_MAX;
  long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page > 0) avail = uint64_t(pages) * uint64_t(page);
  uint64_t in_use = 0; // virtual size now: what ulimit -v already counts
  {
    std::ifstream statm("/proc/self/statm");
    uint64_t vm_pages = 0;
    if (statm >> vm_pages && page > 0) in_use = vm_pages * uint64_t(page);
  }
  for (int which : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit r{};
    if (getrlimit(which, &r) == 0 && r.rlim_cur != RLIM_INFINITY) {
      uint64_t lim = uint64_t(r.rlim_cur);
      uint64_t left = lim > in_use ? lim - in_use : 0;
      if (left < avail) avail = left;
    }
  }
  return avail;
}

// "12.3 GB" (powers of 1000; B, kB, MB, GB, TB).
std::string format_bytes(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000 && u < 6) bytes /= 1000, ++u;
  char buf[32];
  std::snprintf(buf, sizeof buf, u ? "%.1f %s" : "%.0f %s", bytes, units[u]);
  return buf;
}

// "" when `bytes` fits in the available memory; else the error, naming `setting` (e.g.
// "-g 100000 100000") and both figures.
std::string check_memory(const std::string& setting, double bytes, const char* what) {
  uint64_t avail = available_memory_bytes();
  if (avail == UINT64_MAX || bytes <= double(avail)) return "";
  return setting + " needs about " + format_bytes(bytes) + " of memory (" + what +
         "), more than the " + format_bytes(double(avail)) +
         " available (physical memory, ulimit -v and -d); use a smaller size";
}

namespace {

constexpr std::size_t kHugePage = std::size_t(1) << 21; // x86-64's 2 MiB page
constexpr std::size_t kPage = 4096;

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kMapLarge = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kMapLarge = false;
#else
constexpr bool kMapLarge = true;
#endif
#else
constexpr bool kMapLarge = true;
#endif

// Whether a block of `bytes` is mapped on its own (else it comes from operator new).
bool mapped(std::size_t bytes) { return large_blocks_mapped() && bytes >= kHugePage; }

// The bytes a mapped block of `bytes` takes: whole 4 KiB pages.
std::size_t mapped_size(std::size_t bytes) { return (bytes + kPage - 1) & ~(kPage - 1); }

} // namespace

void* allocate_large(std::size_t bytes) {
  if (!mapped(bytes)) return ::operator new(bytes);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Map a huge page more than needed, keep the part from the first 2 MiB boundary on and give
  // back the rest.
  const std::size_t size = mapped_size(bytes);
  if (size < bytes || size + kHugePage < size) throw std::bad_alloc();
  void* raw =
      mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(raw), end = start + size + kHugePage;
  const std::uintptr_t aligned = (start + kHugePage - 1) & ~std::uintptr_t(kHugePage - 1);
  if (aligned > start) munmap(raw, aligned - start);
  if (end > aligned + size) munmap(reinterpret_cast<void*>(aligned + size), end - (aligned + size));
  madvise(reinterpret_cast<void*>(aligned), size, MADV_HUGEPAGE); // a hint: may be refused
  return reinterpret_cast<void*>(aligned);
#else
  return ::operator new(bytes);
#endif
}

bool large_blocks_mapped() {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  return kMapLarge;
#else
  return false;
#endif
}

void release_large(void* p, std::size_t bytes) noexcept {
  if (!mapped(bytes))
    ::operator delete(p);
  else
    munmap(p, mapped_size(bytes));
}

} // namespace lobe

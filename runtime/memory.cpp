// Bounded memory (lobe/memory.h): what the process may still allocate, and the check.
#include "lobe/memory.h"

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

} // namespace lobe

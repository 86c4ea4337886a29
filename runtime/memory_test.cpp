// LargeVector (lobe/memory.h): large blocks on their own 2 MiB-aligned mapping, marked for huge
// pages; contents kept through growth, copies and moves on either side of the 2 MiB line.
#include "lobe/memory.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <new>
#include <sstream>
#include <string>

using namespace lobe;

namespace {

constexpr std::uintptr_t kHuge = std::uintptr_t(1) << 21;

// The "THPeligible:" field of the mapping of /proc/self/smaps that holds `p` (-1: not found).
int thp_eligible(const void* p) {
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  std::ifstream in("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= a && a < hi;
      continue;
    }
    if (inside && line.rfind("THPeligible:", 0) == 0) return std::stoi(line.substr(12));
  }
  return -1;
}

// The kernel's THP mode: "always", "madvise" or "never" (the bracketed word), "" if unknown.
std::string thp_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string s;
  std::getline(in, s);
  auto l = s.find('['), r = s.find(']');
  return l == std::string::npos || r == std::string::npos ? "" : s.substr(l + 1, r - l - 1);
}

} // namespace

TEST(LargeVector, BigBlocksStartOnAHugePageBoundaryAndAreMarkedForHugePages) {
  if (!large_blocks_mapped()) GTEST_SKIP() << "blocks come from operator new here (ASan build)";
  LargeVector<float> v(size_t(3) << 20, 1.5f); // 12 MiB
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % kHuge, 0u);
  for (size_t i = 0; i < v.size(); i += 4093) ASSERT_EQ(v[i], 1.5f) << i;
  const std::string mode = thp_mode();
  if (mode == "madvise" || mode == "always")
    EXPECT_EQ(thp_eligible(v.data()), 1) << "THP mode " << mode;
  // Just under 2 MiB: from operator new, no alignment asked of it.
  LargeVector<char> small((size_t(1) << 21) - 1, 'x');
  EXPECT_EQ(small.back(), 'x');
}

TEST(LargeVector, KeepsItsValuesThroughGrowthCopiesAndMoves) {
  LargeVector<uint32_t> v;
  const uint32_t n = 1500000; // 6 MB: grows from operator new's blocks into mapped ones
  for (uint32_t i = 0; i < n; ++i) v.push_back(i * 2654435761u);
  LargeVector<uint32_t> copy = v;
  LargeVector<uint32_t> moved = std::move(v);
  ASSERT_EQ(copy.size(), n);
  ASSERT_EQ(moved.size(), n);
  for (uint32_t i = 0; i < n; ++i) {
    ASSERT_EQ(copy[i], i * 2654435761u) << i;
    ASSERT_EQ(moved[i], i * 2654435761u) << i;
  }
  copy.resize(10);
  copy.shrink_to_fit(); // back to operator new
  EXPECT_EQ(copy[9], 9 * 2654435761u);
}

TEST(LargeVector, AnImpossibleSizeIsBadAlloc) {
  if (!large_blocks_mapped()) GTEST_SKIP() << "operator new's: ASan reports this itself";
  EXPECT_THROW(allocate_large(std::size_t(1) << 62), std::bad_alloc);  // 4 EiB
  EXPECT_THROW(allocate_large(~std::size_t(0) - 100), std::bad_alloc); // rounding overflows
}

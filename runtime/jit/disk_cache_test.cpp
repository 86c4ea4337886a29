// The disk cache's bound (disk_cache.h): past the limit the least recently used entries go,
// a read counts as a use, and what stays still reads back.
#include "disk_cache.h"
#include "jit.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace lobe::jit {
namespace {

TEST(DiskCache, TrimRemovesLeastRecentlyUsedFirst) {
  char dir[] = "/tmp/lobe_cache_trim_XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  setenv("LOBE_CACHE_DIR", dir, 1);
  setenv("LOBE_CACHE_MAX_MB", "1000", 1); // no trim while filling
  const std::string data(100000, 'x');    // ~100 kB an entry
  for (int i = 0; i < 8; ++i) cache_write("t", "key " + std::to_string(i), data);
  // The entry files (disk_cache.h: <prefix>-<16 hex digits of the key's hash>.bin), entry i
  // last used (10 - i) hours ago, so 7 is the newest...
  auto now = fs::file_time_type::clock::now();
  std::vector<std::pair<int, fs::path>> by_key;
  for (int i = 0; i < 8; ++i) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx",
                  static_cast<unsigned long long>(fnv1a("key " + std::to_string(i))));
    fs::path path = fs::path(dir) / ("t-" + std::string(hex) + ".bin");
    ASSERT_TRUE(fs::exists(path)) << path;
    fs::last_write_time(path, now - std::chrono::hours(10 - i));
    by_key.emplace_back(i, path);
  }
  // ...then entry 1 is read again: the most recently used now (its time moves on; set to an
  // hour ago, so that the entry written below is newer whatever the clocks' granularity).
  std::string got;
  ASSERT_TRUE(cache_read("t", "key 1", got));
  EXPECT_EQ(got, data);
  EXPECT_GT(fs::last_write_time(by_key[1].second), now - std::chrono::minutes(10));
  fs::last_write_time(by_key[1].second, now - std::chrono::hours(1));
  // A limit of 5 entries' worth trims to at most 3.75: entries 0, 2, 3, 4 and 5 go (oldest
  // first), 6, 7 and the re-read 1 stay.
  cache_trim(dir, 5 * 100200);
  for (const auto& [i, path] : by_key) EXPECT_EQ(fs::exists(path), i == 1 || i == 6 || i == 7) << i;
  ASSERT_TRUE(cache_read("t", "key 7", got));
  EXPECT_EQ(got, data);
  EXPECT_FALSE(cache_read("t", "key 0", got));
  // cache_write trims by LOBE_CACHE_MAX_MB: 0.25 MB holds at most two entries afterwards.
  setenv("LOBE_CACHE_MAX_MB", "0.25", 1);
  cache_write("t", "key 8", data);
  int left = 0;
  for (const auto& f : fs::directory_iterator(dir)) left += f.path().extension() == ".bin";
  EXPECT_EQ(left, 1); // 6, 7 and 1 went, oldest first; the new entry stays
  EXPECT_TRUE(cache_read("t", "key 8", got));
  unsetenv("LOBE_CACHE_MAX_MB");
  unsetenv("LOBE_CACHE_DIR");
  fs::remove_all(dir);
}

// Every key names the build of Lobe that compiled the code (Jit::target_identity), so that a
// rebuilt Lobe never loads what another build cached: its GNU build ID, read here from the
// running file by binutils' readelf, independently of Lobe's walk of its own loaded notes.
TEST(DiskCache, KeysNameTheBuild) {
  std::string id = own_build_id();
  char cmd[64];
  std::snprintf(cmd, sizeof cmd, "readelf -n /proc/%d/exe 2>/dev/null", int(getpid()));
  std::string out;
  if (FILE* p = popen(cmd, "r")) {
    std::array<char, 512> buf;
    while (fgets(buf.data(), int(buf.size()), p)) out += buf.data();
    pclose(p);
  }
  size_t at = out.find("Build ID: ");
  if (at == std::string::npos) GTEST_SKIP() << "no readelf, or no build ID in this test binary";
  std::string want = out.substr(at + 10, out.find('\n', at) - at - 10);
  EXPECT_EQ(id, want);
  EXPECT_GE(id.size(), 16u);
  std::string error;
  auto jit = Jit::create(error);
  ASSERT_TRUE(jit) << error;
  EXPECT_NE(jit->target_identity().find("; build " + want), std::string::npos)
      << jit->target_identity();
}

} // namespace
} // namespace lobe::jit

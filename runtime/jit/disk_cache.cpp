// The disk cache of machine code; see disk_cache.h.
#include "disk_cache.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace lobe::jit {

namespace {

constexpr char kMagic[] = "lobe machine-code cache 1\n";

std::string entry_path(const std::string& folder, const std::string& prefix,
                       const std::string& key) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a(key)));
  return folder + "/" + prefix + "-" + hex + ".bin";
}

void put_u64(std::string& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(char((v >> (8 * i)) & 0xff));
}

bool get_u64(const std::string& in, size_t& at, uint64_t& v) {
  if (at > in.size() || in.size() - at < 8) return false;
  v = 0;
  for (int i = 0; i < 8; ++i) v |= uint64_t(static_cast<unsigned char>(in[at + i])) << (8 * i);
  at += 8;
  return true;
}

// The folder's bound: LOBE_CACHE_MAX_MB megabytes (default 256).
uint64_t max_bytes() {
  if (const char* e = std::getenv("LOBE_CACHE_MAX_MB")) {
    char* end = nullptr;
    double mb = std::strtod(e, &end);
    if (end != e && mb >= 0 && mb < 1e9) return uint64_t(mb * 1024 * 1024);
  }
  return uint64_t(256) << 20;
}

} // namespace

void cache_trim(const std::string& folder, uint64_t limit) {
  namespace fs = std::filesystem;
  std::error_code ec;
  struct Entry {
    fs::file_time_type used;
    uint64_t size;
    fs::path path;
  };
  std::vector<Entry> entries;
  uint64_t total = 0;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if (p.extension() != ".bin") continue;
    std::error_code e1, e2;
    uint64_t size = it->file_size(e1);
    fs::file_time_type used = it->last_write_time(e2);
    if (e1 || e2) continue;
    entries.push_back({used, size, p});
    total += size;
  }
  if (total <= limit) return;
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.used < b.used; });
  for (const Entry& e : entries) { // least recently used first, down to 3/4 of the limit
    if (total <= limit / 4 * 3) break;
    if (fs::remove(e.path, ec)) total -= e.size;
  }
}

uint64_t fnv1a(std::string_view bytes) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string bytes_identity(std::string_view bytes) {
  return std::to_string(bytes.size()) + " " + std::to_string(fnv1a(bytes));
}

std::string cache_folder() {
  if (const char* d = std::getenv("LOBE_CACHE_DIR")) {
    if (!*d || std::strcmp(d, "off") == 0) return "";
    return d;
  }
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/lobe";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/lobe";
  return "";
}

bool cache_read(const std::string& prefix, const std::string& key, std::string& data) {
  std::string folder = cache_folder();
  if (folder.empty()) return false;
  std::ifstream in(entry_path(folder, prefix, key), std::ios::binary);
  if (!in) return false;
  std::stringstream ss;
  ss << in.rdbuf();
  std::string file = ss.str();
  const size_t magic = sizeof kMagic - 1;
  if (file.compare(0, magic, kMagic) != 0) return false;
  size_t at = magic;
  uint64_t key_size = 0, data_size = 0, sum = 0;
  if (!get_u64(file, at, key_size) || key_size > file.size() - at) return false;
  if (file.compare(at, key_size, key) != 0 || key_size != key.size()) return false;
  at += key_size;
  if (!get_u64(file, at, data_size) || !get_u64(file, at, sum)) return false;
  if (data_size != file.size() - at) return false;
  std::string_view body(file.data() + at, data_size);
  if (fnv1a(body) != sum) return false;
  data.assign(body);
  // Used now: the last to go when the folder is trimmed. The kernel's clock, as a write's.
  ::utimensat(AT_FDCWD, entry_path(folder, prefix, key).c_str(), nullptr, 0);
  return true;
}

void cache_write(const std::string& prefix, const std::string& key, const std::string& data) {
  std::string folder = cache_folder();
  if (folder.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  std::string path = entry_path(folder, prefix, key);
  static std::atomic<uint64_t> serial{0}; // threads of one process write apart
  std::string tmp =
      path + ".tmp" + std::to_string(::getpid()) + "." + std::to_string(serial.fetch_add(1));
  std::string file(kMagic);
  put_u64(file, key.size());
  file += key;
  put_u64(file, data.size());
  put_u64(file, fnv1a(data));
  file += data;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return;
    out.write(file.data(), std::streamsize(file.size()));
    if (!out) {
      out.close();
      std::filesystem::remove(tmp, ec);
      return;
    }
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) std::filesystem::remove(tmp, ec);
  cache_trim(folder, max_bytes());
}

} // namespace lobe::jit

// The disk cache of machine code; see disk_cache.h.
#include "disk_cache.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

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

} // namespace

uint64_t fnv1a(std::string_view bytes) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
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
  return true;
}

void cache_write(const std::string& prefix, const std::string& key, const std::string& data) {
  std::string folder = cache_folder();
  if (folder.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  std::string path = entry_path(folder, prefix, key);
  std::string tmp = path + ".tmp" + std::to_string(::getpid());
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
}

} // namespace lobe::jit

// StringTable: interning behind a mutex, with each thread's recent strings in front of it.
#include "env.h"

#include "lobe/memory.h"

#include <array>
#include <new>

namespace lobe::shadeops {

namespace {
std::atomic<uint64_t> next_table_serial{1};

// A thread's recently interned strings: a slot per hash value modulo kRecentSlots, a new string
// replacing the one in its slot. `serial` names the table (0: empty slot).
constexpr size_t kRecentSlots = 256;
struct Recent {
  uint64_t serial = 0;
  const char* text = nullptr;
  size_t size = 0;
};
} // namespace

// Bytes a string of `size` characters costs in the table, about (its node and heap block).
constexpr uint64_t kNodeBytes = 64;

StringTable::StringTable()
    : serial_(next_table_serial.fetch_add(1, std::memory_order_relaxed)),
      empty_(strings_.emplace().first->c_str()), budget_(available_memory_bytes() / 4) {}

bool StringTable::room(size_t bytes) {
  if (bytes_.load(std::memory_order_relaxed) + bytes + kNodeBytes <= budget_) return true;
  exhausted_.store(true, std::memory_order_relaxed);
  return false;
}

const char* StringTable::intern(std::string_view s) {
  thread_local std::array<Recent, kRecentSlots> recent;
  Recent& r = recent[TextHash{}(s) % kRecentSlots];
  if (r.serial == serial_ && std::string_view(r.text, r.size) == s) return r.text;
  const char* text;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = strings_.find(s);
    if (it == strings_.end()) {
      if (!room(s.size())) return empty_;
      try {
        it = strings_.emplace(s).first;
      } catch (const std::bad_alloc&) { // never through the shader's frames
        exhausted_.store(true, std::memory_order_relaxed);
        return empty_;
      }
      bytes_.fetch_add(s.size() + kNodeBytes, std::memory_order_relaxed);
    }
    text = it->c_str();
  }
  r = {serial_, text, s.size()};
  return text;
}

const DeclaredClosureInfo* DeclaredClosureTable::get(const char* name,
                                                     const std::vector<DeclaredClosureArg>& args,
                                                     uint32_t block_size) {
  std::string key = name;
  for (const DeclaredClosureArg& a : args)
    key += "|" + std::string(a.keyword ? a.keyword : "") + ":" + std::to_string(int(a.base)) + "[" +
           std::to_string(a.arraylen) + "]@" + std::to_string(a.offset);
  std::lock_guard<std::mutex> lock(mutex_);
  auto [it, fresh] = entries_.try_emplace(key);
  Entry& e = it->second;
  if (fresh) {
    e.args = args;
    e.info = {name, e.args.data(), uint32_t(e.args.size()), block_size};
  }
  return &e.info;
}

} // namespace lobe::shadeops

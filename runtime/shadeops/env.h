// The run-time environment JIT-compiled code reaches through one constant pointer baked into
// each material: the string interner (strings in shader code are interned `const char*` so
// that equality is pointer equality) and the closure printer used by printf's `%s`.
// Owned by the ShadingSystem; outlives every Material compiled by it.
#pragma once

#include "lobe/shading.h"
#include "text_hash.h"

#include <atomic>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

namespace lobe::shadeops {

// What debug_uninit fills string locals with before they are written (OSL's marker text).
inline constexpr const char* kUninitializedString = "!!!uninitialized!!!";

// Thread-safe string interner: equal strings give the same pointer, valid for the table's life.
// Shaders intern at every point that builds a string (format, concat, substr), mostly the same
// few strings: each thread remembers the strings it interned last, one per slot of a small table
// indexed by hash, so that interning one of them again takes no lock and allocates nothing.
//
// Bounded memory: the strings are kept for the table's life, within a quarter of the memory
// available when it was made (lobe/memory.h); a string past that is interned as "" instead and
// the table says so (exhausted(): the commands report it), so that a shader that grows a string
// without end (`s = concat(s, s)` in a loop) is stopped short of the process's memory.
class StringTable {
public:
  StringTable();
  const char* intern(std::string_view s);
  // Whether a string of `bytes` more fits in the budget; false (and exhausted() from then on)
  // when not: a builder asks before it makes a long string, and makes "" instead.
  bool room(size_t bytes);
  const char* empty() const { return empty_; }
  bool exhausted() const { return exhausted_.load(std::memory_order_relaxed); }
  uint64_t budget() const { return budget_; }
  // Unique among all tables ever made: names this table in per-thread caches of its strings.
  uint64_t serial() const { return serial_; }

private:
  // Tells a thread's remembered strings apart from those of another table, even one since
  // destroyed at the same address.
  const uint64_t serial_;
  std::mutex mutex_;
  // Node-based: element addresses are stable.
  std::unordered_set<std::string, TextHash, std::equal_to<>> strings_;
  const char* empty_ = nullptr; // the interned ""
  uint64_t budget_ = 0;
  std::atomic<uint64_t> bytes_{0}; // the strings' bytes and their nodes, about
  std::atomic<bool> exhausted_{false};
};

// Descriptions of shader-declared closures (lobe/shading.h), one per distinct name and argument
// list, kept for the table's life: closures built by any material point at them.
class DeclaredClosureTable {
public:
  // `args`' keyword names must be interned strings.
  const DeclaredClosureInfo* get(const char* name, const std::vector<DeclaredClosureArg>& args,
                                 uint32_t block_size);

private:
  struct Entry {
    DeclaredClosureInfo info;
    std::vector<DeclaredClosureArg> args;
  };
  std::mutex mutex_;
  std::map<std::string, Entry> entries_; // by a text key of name and arguments
};

struct RuntimeEnv {
  RuntimeEnv() = default;
  RuntimeEnv(const RuntimeEnv&) = delete;
  RuntimeEnv& operator=(const RuntimeEnv&) = delete;
  ~RuntimeEnv();

  StringTable strings;
  DeclaredClosureTable declared_closures;
  // OpenImageIO TextureSystem, created on the first texture lookup (texture.cpp).
  void* texture_system = nullptr;
  std::once_flag texture_once;
  // Set by the first point-cloud call, which warns that Lobe has none (ops_dict.cpp).
  std::atomic<bool> pointcloud_warned{false};
  // Renders a closure tree for printf("%s"); null: a built-in fallback format.
  std::string (*closure_printer)(const ClosureNode*) = nullptr;
};

} // namespace lobe::shadeops

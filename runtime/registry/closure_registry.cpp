// The closure registry's look-ups over the table in closure_table.h.
#include "closure_registry.h"

#include "closure_table.h"

#include <deque>
#include <string>
#include <vector>

namespace lobe::registry {
namespace {

// The built-in table followed by the registered entries; reserved once, so never moved.
struct Entries {
  std::vector<ClosureEntry> list;
  std::deque<std::string> strings;              // keys, names, docs, parameter texts
  std::deque<std::vector<ClosureParam>> params; // parameter lists of registered entries
  Entries() {
    list.reserve(kMaxClosures);
    list.assign(std::begin(table::kClosures), std::end(table::kClosures));
  }
  const char* keep(const char* s) { return s ? strings.emplace_back(s).c_str() : nullptr; }
};
Entries& entries() {
  static Entries e;
  return e;
}

} // namespace

std::span<const ClosureEntry> closures() { return entries().list; }

const ClosureEntry* find_by_key(std::string_view key) {
  int id = id_of(key);
  return id < 0 ? nullptr : &entries().list[size_t(id)];
}

int id_of(std::string_view key) {
  int id = table::index_of(key);
  if (id >= 0) return id;
  const auto& list = entries().list;
  for (size_t i = std::size(table::kClosures); i < list.size(); ++i)
    if (key == list[i].key) return int(i);
  return -1;
}

int add_closure(const ClosureEntry& entry, const char** error) {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return -1;
  };
  Entries& e = entries();
  if (!entry.key || !*entry.key) return fail("a closure needs a name");
  if (id_of(entry.key) >= 0) return fail("a closure of that name exists");
  if (e.list.size() >= kMaxClosures) return fail("too many closures registered");
  std::vector<ClosureParam>& params = e.params.emplace_back();
  for (const ClosureParam& p : entry.params)
    params.push_back({e.keep(p.name), p.type, p.keyword, e.keep(p.default_value), e.keep(p.doc),
                      p.always_printed});
  const char* key = e.keep(entry.key);
  e.list.push_back({key, entry.name ? e.keep(entry.name) : key, params, entry.flags,
                    e.keep(entry.doc ? entry.doc : "")});
  return int(e.list.size() - 1);
}

const char* kernel_symbol(int id, Kernel k) {
  static constexpr const char* kSymbols[][5] = {
#define LOBE_SYMBOLS(key, ...)                                                                     \
  {LOBE_KERNEL_SYMBOL(key, setup), LOBE_KERNEL_SYMBOL(key, eval), LOBE_KERNEL_SYMBOL(key, sample), \
   LOBE_KERNEL_SYMBOL(key, pdf), LOBE_KERNEL_SYMBOL(key, albedo)},
      LOBE_CLOSURE_TABLE(LOBE_SYMBOLS)
#undef LOBE_SYMBOLS
  };
  if (id < 0 || id >= closure_id::kCount || !has_kernel(table::kClosures[id].flags)) return nullptr;
  return kSymbols[id][static_cast<int>(k)];
}

} // namespace lobe::registry

// The closure registry's look-ups over the table in closure_table.h.
#include "closure_registry.h"

#include "closure_table.h"

namespace lobe::registry {

std::span<const ClosureEntry> closures() { return table::kClosures; }

const ClosureEntry* find_by_key(std::string_view key) {
  int id = id_of(key);
  return id < 0 ? nullptr : &table::kClosures[id];
}

int id_of(std::string_view key) { return table::index_of(key); }

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

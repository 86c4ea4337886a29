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

} // namespace lobe::registry

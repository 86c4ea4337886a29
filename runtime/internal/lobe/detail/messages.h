// Internal: setmessage/getmessage storage of one ShadingContext (runtime/shadeops/ops_query.cpp
// reads and writes it; Material::shade clears it). Not part of the renderer API.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

namespace lobe::detail {

struct MessageStore {
  struct Entry {
    const char* name = nullptr; // interned: equal names are equal pointers
    int32_t type = 0;           // type code (base | arraylen << 8, as codegen passes it)
    bool set = false;           // false: queried before anything set it
    uint32_t offset = 0;        // of the value (no derivatives) in `data`
    const char* file = nullptr; // where it was set (or first queried)
    int32_t line = 0;
    int32_t layer = -1;
  };
  std::vector<Entry> entries;
  std::vector<unsigned char> data;

  void clear() {
    entries.clear();
    data.clear();
  }
  Entry* find(const char* name) {
    for (Entry& e : entries)
      if (e.name == name || (e.name && name && !std::strcmp(e.name, name))) return &e;
    return nullptr;
  }
};

} // namespace lobe::detail

// A disk cache of compiled machine code (closure kernels, materials), keyed by everything that
// affects it.
//
// An entry is one file, <folder>/<prefix>-<16 hex digits of the key's hash>.bin, holding a magic
// line, the whole key, the data's size and a checksum of the data. A read checks all of them:
// an entry that is truncated, corrupt, from another format or (hash collision) for another key
// is a miss, and the next write replaces it. Writes go to a temporary file renamed into place,
// so a reader never sees half an entry and concurrent writers of the same key are harmless.
// Any failure to read or write only costs the compile again; it is never an error.
//
// The folder is $LOBE_CACHE_DIR when set (empty or "off": no cache), else
// $XDG_CACHE_HOME/lobe, else $HOME/.cache/lobe. It is kept under $LOBE_CACHE_MAX_MB megabytes
// (default 256): after a write that takes it past, the least recently used entries go (a read
// marks an entry used) until it is under three quarters of that.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace lobe::jit {

std::string cache_folder(); // "" when caching is off

// FNV-1a, 64 bits.
uint64_t fnv1a(std::string_view bytes);
// "<size> <FNV-1a>" of some bytes (a bitcode file) for a cache key.
std::string bytes_identity(std::string_view bytes);

// True with `data` when a valid entry for `key` exists.
bool cache_read(const std::string& prefix, const std::string& key, std::string& data);
// Stores `data` for `key` (best effort), then trims the folder.
void cache_write(const std::string& prefix, const std::string& key, const std::string& data);
// Removes the least recently used entries of `folder` while it holds more than `limit` bytes,
// down to three quarters of it (what cache_write does with $LOBE_CACHE_MAX_MB).
void cache_trim(const std::string& folder, uint64_t limit);

} // namespace lobe::jit

// Per-thread shading state: the arena closures are built in, and error/warning reporting for
// shader run-time events (out-of-range index, division by zero, ...). One ShadingContext per
// thread; reset() between shading points. Never shared between threads.
#pragma once

#include "lobe/renderer_services.h"
#include "lobe/shading.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lobe {

namespace detail {
struct MessageStore;
}

class ShadingContext {
public:
  explicit ShadingContext(size_t arena_bytes = 64 * 1024);
  ~ShadingContext();
  ShadingContext(ShadingContext&&) noexcept;
  ShadingContext& operator=(ShadingContext&&) noexcept;

  // Frees every closure allocated since the last reset (O(1): rewinds the arena).
  void reset() { used_ = 0; }

  // 8-byte-aligned storage from the arena; null when the arena is exhausted (the closure
  // builder then drops the component and counts it in closures_dropped).
  void* allocate(size_t bytes);

  // Sends text from shader code to `print` if set, else appends it to `output`.
  void message(const std::string& text);

  // Per-thread scratch for a material's group data (layer parameters and outputs) during
  // shade(); Material::read_output reads the most recent shade() from here.
  std::vector<unsigned char> groupdata;
  const void* groupdata_owner = nullptr; // the Material that last wrote `groupdata`

  // Message sink for printf/warning/error from shader code. Default: append to `output`.
  std::function<void(const std::string&)> print;
  std::string output;
  int errors = 0;
  int warnings = 0;
  uint64_t closures_dropped = 0;

  // The renderer's answers to user data, getattribute and trace (renderer_services.h);
  // null: none.
  const RendererServices* renderer = nullptr;
  // The last trace() of the current shade.
  TraceHit trace_hit;

  // setmessage/getmessage storage of the current shade(), created on first use.
  detail::MessageStore& messages();
  // Forgets the previous shade's messages and trace result (Material::shade calls it).
  void begin_shade();

private:
  std::unique_ptr<detail::MessageStore> messages_;
  std::unique_ptr<unsigned char[]> arena_;
  size_t capacity_ = 0;
  size_t used_ = 0;
};

} // namespace lobe

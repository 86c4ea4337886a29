// Per-thread shading state: the arena closures are built in, and error/warning reporting for
// shader run-time events (out-of-range index, division by zero, ...). One ShadingContext per
// thread; reset() between shading points. Never shared between threads.
#pragma once

#include "lobe/renderer_services.h"
#include "lobe/shading.h"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lobe {

namespace detail {
struct MessageStore;
class Dictionaries;
} // namespace detail

class ShadingContext {
public:
  explicit ShadingContext(size_t arena_bytes = 64 * 1024);
  ~ShadingContext();
  ShadingContext(ShadingContext&&) noexcept;
  ShadingContext& operator=(ShadingContext&&) noexcept;

  // Frees every closure allocated since the last reset (O(1): rewinds the arena).
  void reset() { used_ = 0; }

  // 8-byte-aligned storage from the arena; null when the arena is exhausted (the closure
  // builder then drops the component and counts it in closures_dropped). Inline: the closure
  // shadeops are linked into shader code from bitcode (runtime/shadeops/CMakeLists.txt).
  void* allocate(size_t bytes) {
    size_t start = (used_ + 7) & ~size_t(7);
    if (start > capacity_ || bytes > capacity_ - start) return nullptr;
    used_ = start + bytes;
    return arena_.get() + start;
  }

  // What shader code says: printf text as is; a warning or an error as one line without its
  // "WARNING: " / "ERROR: " prefix and newline, as OSL words them ("Shader error [name]: ...",
  // "Index [5] out of range a[0..2]: f.osl:3 (group g, layer 0 l, shader s)").
  enum class MessageKind : uint8_t { Print, Warning, Error };
  // Sends a message to `report` if set, else to `print` (or `output`) formatted as OSL's
  // testshade prints it: "WARNING: text\n", "ERROR: text\n". Never throws (it runs inside
  // shader code): a message that cannot be delivered (no memory for it, a sink that threw) is
  // counted in `messages_lost`.
  void message(MessageKind kind, const std::string& text) noexcept;
  void message(const std::string& text) noexcept { message(MessageKind::Print, text); }
  // A run-time error or warning from shader code (counted in `errors` / `warnings`).
  void error(const std::string& text) noexcept {
    ++errors;
    message(MessageKind::Error, text);
  }
  void warning(const std::string& text) noexcept {
    ++warnings;
    message(MessageKind::Warning, text);
  }

  // Per-thread scratch for a material's group data (layer parameters and outputs) during
  // shade(); Material::read_output reads the most recent shade() from here.
  std::vector<unsigned char> groupdata;
  const void* groupdata_owner = nullptr; // the Material that last wrote `groupdata`

  // Message sinks for printf/warning/error from shader code: `report` receives each message
  // with its kind; without it, `print` receives the formatted text; without either, it is
  // appended to `output`.
  std::function<void(MessageKind, const std::string&)> report;
  std::function<void(const std::string&)> print;
  std::string output;
  int errors = 0;
  int warnings = 0;
  // This shade's place among a run's shades (`lobe shade`: the grid point's index), for what is
  // told once a run (a texture file that cannot be opened): the shade of the smallest order that
  // meets it tells it, so a grid shaded on several threads says it at its first point, whichever
  // ran first. Equal orders (a renderer's, all 0): the first to meet it.
  uint64_t order = 0;
  uint64_t closures_dropped = 0;
  uint64_t messages_lost = 0;

  // Bounded execution (CompileOptions::max_loop_iterations). `stopped`: the current shade was
  // stopped in a loop, because it ran past the material's limit (an error was reported, naming
  // the shader and the loop's place) or because `cancel` was set (no error); the shade then
  // returned at once, sg.Ci is null (black) and output parameters are as the loop left them.
  // begin_shade() clears it. `cancel`: set by another thread (a Ctrl-C handler, a renderer
  // abandoning a frame) to stop running shaders at their next loop check, within about 65536
  // iterations; null: never.
  bool stopped = false;
  const std::atomic<bool>* cancel = nullptr;

  // The renderer's answers to user data, getattribute and trace (renderer_services.h);
  // null: none.
  const RendererServices* renderer = nullptr;
  // The last trace() of the current shade.
  TraceHit trace_hit;

  // setmessage/getmessage storage of the current shade(), created on first use.
  detail::MessageStore& messages();
  // Forgets the previous shade's messages and trace result (Material::shade calls it).
  void begin_shade();
  // The XML documents dict_find has read, and the node ids it gave out: kept for the context's
  // life (node ids stay valid across shades, as OSL's do), created on first use.
  detail::Dictionaries& dictionaries();

private:
  std::unique_ptr<detail::MessageStore> messages_;
  std::unique_ptr<detail::Dictionaries> dictionaries_;
  std::unique_ptr<unsigned char[]> arena_;
  size_t capacity_ = 0;
  size_t used_ = 0;
};

} // namespace lobe

// ShadingContext: the per-thread arena closures are built in, and the sink for messages from
// shader code (printf, run-time errors). Rewinding the arena is O(1), so the renderer can
// reset it at every shading point.
#include "lobe/context.h"

#include "lobe/detail/dictionary.h"
#include "lobe/detail/messages.h"
#include "lobe/renderer_services.h"

#include <algorithm>
#include <cstdlib>
#include <iterator>

namespace lobe {

ShadingContext::ShadingContext(size_t arena_bytes)
    : arena_(new unsigned char[arena_bytes]), capacity_(arena_bytes) {}
ShadingContext::~ShadingContext() = default;
ShadingContext::ShadingContext(ShadingContext&&) noexcept = default;
ShadingContext& ShadingContext::operator=(ShadingContext&&) noexcept = default;

detail::MessageStore& ShadingContext::messages() {
  if (!messages_) messages_ = std::make_unique<detail::MessageStore>();
  return *messages_;
}

detail::Dictionaries& ShadingContext::dictionaries() {
  if (!dictionaries_) dictionaries_ = std::make_unique<detail::Dictionaries>();
  return *dictionaries_;
}

void ShadingContext::begin_shade() {
  if (messages_) messages_->clear(); // a material without messages never makes a store
  trace_hit = TraceHit{};
  stopped = false;
}

namespace {
const char* const kTypeNames[] = {"int",    "float",  "color",  "point",
                                  "vector", "normal", "matrix", "string"};
}

std::optional<DataType> DataType::parse(std::string_view text) {
  size_t br = text.find('[');
  std::string_view name = text.substr(0, br);
  DataType t;
  auto it = std::find(std::begin(kTypeNames), std::end(kTypeNames), name);
  if (it == std::end(kTypeNames)) return std::nullopt;
  t.base = Base(it - std::begin(kTypeNames));
  if (br != std::string_view::npos) {
    std::string n(text.substr(br + 1));
    if (text.back() != ']') return std::nullopt;
    t.arraylen = std::atoi(n.c_str());
    if (t.arraylen < 1) return std::nullopt;
  }
  return t;
}

std::string DataType::str() const {
  std::string s = kTypeNames[size_t(base)];
  if (arraylen > 0) { // appended piecewise: "[" + to_string(n) trips GCC 12's -Wrestrict
    s += "[";
    s += std::to_string(arraylen);
    s += "]";
  }
  return s;
}

void ShadingContext::message(MessageKind kind, const std::string& text) noexcept {
  try {
    if (report) {
      report(kind, text);
      return;
    }
    std::string line = kind == MessageKind::Print     ? text
                       : kind == MessageKind::Warning ? "WARNING: " + text + "\n"
                                                      : "ERROR: " + text + "\n";
    if (print)
      print(line);
    else
      output += line;
  } catch (...) { // out of memory, or a sink that threw: never through the shader's frames
    ++messages_lost;
  }
}

} // namespace lobe
